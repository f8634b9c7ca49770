#pragma once
// The sketch-based deformation tool (thesis 3.2.2 "Deformation tool" and 3.3.3): what turns pen
// strokes into the handles, targets and region the deformer (edge_graph_deformer.h) needs.
//
//   1. Handle curve: a window stroke is projected on the mesh by ray casting (CGAL AABB tree);
//      the handle vertices are the vertices of the faces its projection crosses, ordered by the
//      arc length of their closest point on the projected curve.
//   2. Reference planes: the base plane is the least-squares plane of the handle points
//      (Eqs. 3.6-3.8, SVD of the centred points); it turns about the axis through the
//      projections of the first and last handle points; the projection plane contains that
//      axis and is orthogonal to the base plane.
//   3. Target curve: the new stroke lifted onto the base plane, optionally combined with a
//      shadow stroke on the projection plane: P_i = P_i^b + V_i, V_i = P_i^p - P_i^bp.
//   4. Handle targets: each handle vertex goes to the target curve at its arc-length parameter
//      (keeping its offset from the handle curve by default, so the band of handle vertices
//      around the curve is not collapsed onto it).
//   5. ROI: Euclidean radius around the handle, a closed screen-space lasso, or a brush.
//
// Conventions: window pixels as in camera.h (x right, y down). Every function leaves its inputs
// unchanged; a stroke that misses the mesh is refused with a reason.
#include <memory>
#include <optional>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// First-hit ray casting against a mesh (CGAL AABB tree over its triangles), built once per mesh.
class MeshRayCaster {
 public:
  explicit MeshRayCaster(const TriMesh& mesh);
  ~MeshRayCaster();
  MeshRayCaster(MeshRayCaster&&) noexcept;
  MeshRayCaster& operator=(MeshRayCaster&&) noexcept;

  struct Hit {
    int face = -1;
    Vec3 point = Vec3::Zero();
    double distance = 0.0;  // along the ray
  };
  std::optional<Hit> first_hit(const Ray& ray) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct HandleCurve {
  std::vector<Vec3> points;        // the stroke's projection on the surface, in stroke order
  std::vector<int> faces;          // faces it crosses (each once, in order)
  std::vector<int> vertices;       // handle vertices, ordered by `parameters`
  std::vector<double> parameters;  // normalised arc length in [0, 1] of each vertex's closest curve point
  std::vector<Vec3> anchors;       // that closest point on the curve, per vertex
};

// Samples the stroke at least every `step_px` pixels; refused when fewer than two samples hit.
Result<HandleCurve> project_handle_stroke(const TriMesh& mesh, const MeshRayCaster& caster, const Camera& camera,
                                          const std::vector<Vec2>& stroke_px, double step_px = 1.0);

// Surface points under the stroke (misses are skipped).
std::vector<Vec3> project_stroke(const MeshRayCaster& caster, const Camera& camera, const std::vector<Vec2>& stroke_px);

// Eqs. 3.6-3.8: the plane through the centroid whose normal is the right singular vector of the
// centred points for the smallest singular value. Refused for fewer than 3 points or collinear
// points (no unique plane).
Result<Plane> least_squares_plane(const std::vector<Vec3>& points);

struct ReferencePlanes {
  Plane base, projection;
  Vec3 axis_point = Vec3::Zero();      // projection of the first handle point on the fitted plane
  Vec3 axis_direction = Vec3::UnitX(); // towards the projection of the last handle point
};

// `rotation` turns the base plane (radians, right-handed about axis_direction).
Result<ReferencePlanes> reference_planes(const std::vector<Vec3>& handle_points, double rotation = 0.0);

// The new handle curve: `base_px` lifted on the base plane; with a non-empty `shadow_px` on the
// projection plane (resampled by arc length to the base curve's point count) it becomes the
// space curve P_i = P_i^b + (P_i^p - proj(P_i^b)). Refused if a point's ray misses a plane.
Result<std::vector<Vec3>> target_curve(const Camera& camera, const ReferencePlanes& planes,
                                       const std::vector<Vec2>& base_px, const std::vector<Vec2>& shadow_px = {});
// The same with the shadow drawn under its own camera (the view turned to face the projection
// plane after drawing the base stroke).
Result<std::vector<Vec3>> target_curve(const Camera& base_camera, const std::vector<Vec2>& base_px,
                                       const Camera& shadow_camera, const std::vector<Vec2>& shadow_px,
                                       const ReferencePlanes& planes);

// Target position per handle vertex (same order as handle.vertices).
std::vector<Vec3> map_handles_to_target(const TriMesh& mesh, const HandleCurve& handle,
                                        const std::vector<Vec3>& target, bool keep_offsets = true);

// The point at normalised arc length u in [0, 1] of an open polyline (at least one point).
Vec3 point_at_arc_length(const std::vector<Vec3>& polyline, double u);
// Resample an open polyline to n >= 2 points evenly spaced by arc length.
std::vector<Vec3> resample_by_arc_length(const std::vector<Vec3>& polyline, int n);

// === ROI selection (every result excludes `exclude`, normally the handle vertices; sorted)
std::vector<int> roi_by_radius(const TriMesh& mesh, const std::vector<int>& handle_vertices, double radius);
// Vertices in front of the camera whose window projection lies inside the closed lasso
// (even-odd rule; the last point connects to the first).
std::vector<int> roi_by_lasso(const TriMesh& mesh, const Camera& camera, const std::vector<Vec2>& lasso_px,
                              const std::vector<int>& exclude = {});
// Vertices within `radius` of any brush point (brush points are on the surface).
std::vector<int> roi_by_brush(const TriMesh& mesh, const std::vector<Vec3>& brush_points, double radius,
                              const std::vector<int>& exclude = {});

}  // namespace ps
