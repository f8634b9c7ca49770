#pragma once
// The sketching session (thesis 3.2.1): the cross sections sketched so far, the model
// reconstructed after every accepted stroke, and undo/redo over both. The reference planes and
// the camera belong to the caller (input/InputState): a stroke arrives with the camera it was
// drawn under and the plane it was drawn on.
//
// Every operation either succeeds or returns a Status with the reason and leaves the session
// exactly as it was (sections, model, undo history).
//
// Geometry as values: the state is a plain value (SessionState); undo/redo keep snapshots of it,
// so an undo restores the identical model, bit for bit. The stored curves are the user's own
// (lifted, preprocessed) curves; curve sewing (rule 4) runs on the whole set at every rebuild,
// so the model is a function of the set of curves, not of the order they were drawn in.
#include <string>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/reconstruct.h"
#include "modeling/status.h"
#include "modeling/stroke_preprocess.h"

namespace ps {

struct SessionParams {
  StrokeParams stroke;  // preprocessing of cross-section strokes (15 px filter, thesis-facts)
  bool improve = true;  // refinement + smoothing of the preview (4.5.1)
  // Above this many faces in the initial union the preview is shown unimproved (with a hint):
  // the improvement's exact self-intersection checks would stall the interactive loop.
  std::size_t improve_max_faces = 6000;
  double lambda = 0.5;  // deformation balance, kept for the deformation tool
};

// A sculpting operation by stroke (thesis 3.2.2; modeling/sculpt_cut.h, sculpt_smooth.h), kept
// with the camera it was drawn under so it can be applied again.
struct SculptOp {
  enum class Kind { kCut, kTunnel, kSmooth, kExtrude };
  Kind kind = Kind::kCut;
  std::vector<Vec2> stroke;  // window pixels (kExtrude: the closed base stroke on the surface)
  Vec2 side = Vec2::Zero();  // kCut: a window point on the side to remove
  Camera camera;
  // kExtrude: the silhouette stroke on the automatic reference plane, and its camera.
  std::vector<Vec2> silhouette;
  Camera silhouette_camera;
};
const char* sculpt_kind_name(SculptOp::Kind kind);

// The operation applied to a model (refusals name the reason; the model is a value).
Result<TriMesh> apply_sculpt(const TriMesh& model, const SculptOp& op);

struct SessionState {
  SectionSet sections;  // the user's curves (before sewing)
  SectionSet sewn;      // the curves the model interpolates (after sewing)
  // Sculpting operations, applied in order to the reconstruction of `sewn`. Editing the
  // sections rebuilds the reconstruction and applies them again; a section edit that makes one
  // of them fail is refused (the sculpted model is never silently lost).
  std::vector<SculptOp> ops;
  TriMesh model;        // reconstruction of `sewn`, then `ops` (empty when there are no sections)
  std::vector<std::string> hints;  // e.g. "the model has 2 separate parts"
};

class SketchSession {
 public:
  explicit SketchSession(SessionParams params = {});

  const SessionState& state() const { return state_; }
  const SessionParams& params() const { return params_; }

  // A window-space stroke (pixels) drawn under `camera` on `plane`: preprocessed (3.3.1),
  // lifted onto the plane, checked against the stroke rules (3.3.2), sewn (rule 4), then the
  // model is rebuilt. Refused strokes leave everything unchanged.
  Status add_window_stroke(const std::vector<Vec2>& window_points, const Camera& camera,
                           const Plane& plane);
  // A closed curve given in 3D on `plane` (points are projected onto it).
  Status add_section(const Plane& plane, const std::vector<Vec3>& points);
  Status delete_section(int index);
  // Applies a sculpting operation to the current model (undoable like every other change).
  Status sculpt(const SculptOp& op);
  // The section whose window-space polyline passes nearest to `window_point`, within
  // `radius_px`; -1 if none.
  int pick_section(const Vec2& window_point, const Camera& camera, double radius_px) const;

  // Parameters by name: "lambda" in [0, 1], "improve" (0 or 1), "filter_px" > 0.
  Status set_parameter(const std::string& name, double value);
  Status undo();
  Status redo();
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }

  // Last reconstruction's report (timings, zones, warnings).
  const ReconstructReport& last_report() const { return report_; }

 private:
  // Rebuild `next` (sew + reconstruct); on success commit it, pushing the old state on the undo
  // stack; on failure leave everything unchanged.
  Status commit(SessionState next);

  SessionParams params_;
  SessionState state_;
  std::vector<SessionState> undo_;
  std::vector<SessionState> redo_;
  ReconstructReport report_;
};

}  // namespace ps
