#pragma once
// Sculpting through the screen (thesis 3.2.2): cutting a part off the model along an open stroke,
// and tunnelling a hole through it along a closed stroke. Both sweep the stroke along the camera's
// viewing rays into a tool solid (view_extrusion.h) and subtract it exactly (mesh_boolean.h), so
// the result is closed and the cut is capped.
//
// Strokes are in window pixels (x right, y down), under `camera`. "On the model" means inside the
// model's silhouette: the point's viewing ray meets the model (tested against the projected
// triangles). Every refusal names what is wrong and leaves the model untouched (inputs are values).
#include <array>
#include <vector>

#include "modeling/camera.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// Cutting: an open stroke that enters and leaves the silhouette (it starts and ends off the
// model and passes over it), and a second stroke's point `remove_side_px` marking the side to
// remove. The stroke is extended straight from both ends to a frame around the silhouette, and
// the part of the frame on the marked side, swept along the viewing rays through the whole model,
// is subtracted. The result may have several components (a cut through a U keeps both arms).
Result<TriMesh> cut_by_stroke(const TriMesh& model, const std::vector<Vec2>& stroke_px,
                              const Vec2& remove_side_px, const Camera& camera);

// Tunnelling: a closed stroke lying wholly inside the silhouette; the region it encloses, swept
// along the viewing rays through the whole model, is subtracted. On a solid part this digs a
// hole through the model and raises its genus by one.
Result<TriMesh> tunnel_by_stroke(const TriMesh& model, const std::vector<Vec2>& closed_stroke_px,
                                 const Camera& camera);

// Is a window point inside the model's silhouette under `camera`? The model's triangles are
// projected once at construction (those with a corner behind the eye are left out); each query
// tests the projected triangles (a box test first). For many queries on one view (stroke
// recognition probes every few pixels) build one and reuse it.
class SilhouetteTest {
 public:
  SilhouetteTest(const TriMesh& model, const Camera& camera);
  bool covers(const Vec2& px) const;
  // Box of the projected vertices (empty when nothing is in front of the eye: lo > hi).
  Vec2 lo() const { return lo_; }
  Vec2 hi() const { return hi_; }

 private:
  std::vector<std::array<Vec2, 3>> tris_;
  Vec2 lo_ = Vec2::Constant(1e300), hi_ = Vec2::Constant(-1e300);
};

// One-shot form of SilhouetteTest.
bool on_silhouette(const TriMesh& model, const Camera& camera, const Vec2& px);

}  // namespace ps
