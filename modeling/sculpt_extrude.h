#pragma once
// Extrusion by strokes (thesis 3.2.2; issue 6 point 2): a closed stroke drawn on the surface
// selects a region and gives the base curve; a reference plane orthogonal to that region is made
// through the stroke's centre; a silhouette stroke drawn on that plane defines the new part,
// which is the base curve swept along the silhouette's skeleton and joined to the model by exact
// union (mesh_boolean.h), the join then smoothed. A silhouette drawn into the model digs instead:
// the part is subtracted, a pocket, or a tunnel (genus + 1) when it comes out at the back; the
// skeleton follows the silhouette, so a bent silhouette bends the tunnel. docs/sculpting.md, "Extrusion", says exactly
// what is built and why.
//
// Strokes are in window pixels (x right, y down). The base stroke is drawn under `camera`; the
// silhouette under options.silhouette_camera when set (normally the user turns the view to see
// the reference plane), else under `camera` too. Every refusal names what is wrong and leaves the
// model untouched (inputs are values).
#include <optional>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct ExtrudeOptions {
  // The two rotations of the reference plane (thesis 3.2.2), radians, right-handed:
  //   spin: about the line through the centre along the region's mean normal;
  //   tilt: about the line through the centre along the (spun) stroke diameter, i.e. the
  //         direction from the stroke's first point to the stroke point farthest from it.
  double spin = 0.0;
  double tilt = 0.0;
  std::optional<Camera> silhouette_camera;  // camera of the silhouette stroke (default: camera)
  int section_points = 48;  // the base curve resampled by arc length to this many points (>= 8)
  int stations = 24;        // rungs of the skeleton from the base to the tip (>= 4)
  int smooth_steps = 6;     // smoothing of the join (0: none); halved on a self-intersection
  double smooth_radius = 0.0;  // join region radius (<= 0: a quarter of the base width)
  // How near the silhouette's ends must be to the base curve, as a fraction of its width.
  double end_tolerance = 0.35;
};

// Whether spin and tilt (ExtrudeOptions) turn the reference plane acceptably: spin any finite
// angle; tilt strictly between -pi/2 and pi/2 (at +-pi/2 the normal axis would lie in the
// surface). Else the reason.
Status check_plane_rotation(double spin, double tilt);

// The automatic reference plane (what the app shows while the user draws the silhouette).
struct ExtrudePlane {
  Plane plane;                      // the reference plane (contains centre, normal_axis, across)
  Vec3 centre = Vec3::Zero();       // centroid of the projected base curve
  Vec3 normal_axis = Vec3::UnitZ(); // the region's mean normal after the tilt (in the plane, outward)
  Vec3 across = Vec3::UnitX();      // the diameter direction after the spin (in the plane)
  Vec3 region_normal = Vec3::UnitZ();  // the region's mean normal before any rotation
  std::vector<Vec3> base_curve;     // the base stroke projected on the surface (closed, resampled)
};

// Projects the base stroke and builds the reference plane. Refused: fewer than 3 points, a
// non-finite point, a stroke that is not closed (its ends farther apart than a fifth of its size,
// at least 12 px) or crosses itself, a point whose ray misses the model.
Result<ExtrudePlane> extrusion_reference_plane(const TriMesh& model, const std::vector<Vec2>& base_stroke_px,
                                               const Camera& camera, const ExtrudeOptions& options = {});

struct ExtrudeReport {
  ExtrudePlane plane;
  TriMesh part;                 // the new part before the union
  int join_vertices = 0;        // vertices on the intersection curve of model and part
  int smoothed_vertices = 0;    // vertices moved by the join smoothing
  int smooth_steps = 0;         // smoothing steps actually applied
  int boolean_attempts = 0;     // 1, or more when the part was nudged after a rounding fold
  double added_volume = 0.0;    // volume(result) - volume(model) (negative when digging)
  bool dug = false;             // the silhouette went into the model: the part was subtracted
  int genus_change = 0;         // 1 when the dug part came out at the back (a tunnel)
};

Result<TriMesh> extrude_by_strokes(const TriMesh& model, const std::vector<Vec2>& base_stroke_px,
                                   const std::vector<Vec2>& silhouette_px, const Camera& camera,
                                   const ExtrudeOptions& options = {}, ExtrudeReport* report = nullptr);

}  // namespace ps
