// Extrusion of a window-space polygon along viewing rays (see view_extrusion.h).
#include "modeling/view_extrusion.h"

#include <cmath>
#include <limits>
#include <string>

#include "modeling/mesh_topology.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/polyline_crossing.h"

namespace ps {

DepthRange depth_range(const TriMesh& mesh, const Camera& camera) {
  const Vec3 f = (camera.target - camera.eye).normalized();
  DepthRange r{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& v : mesh.vertices) {
    const double d = (v - camera.eye).dot(f);
    r.min = std::min(r.min, d);
    r.max = std::max(r.max, d);
  }
  return r;
}

Result<TriMesh> extrude_window_polygon(const std::vector<Vec2>& poly, const Camera& camera, double near_depth,
                                       double far_depth) {
  const std::size_t n = poly.size();
  if (n < 3) return Result<TriMesh>::error("the polygon has " + std::to_string(n) + " corner(s); it needs at least 3");
  for (std::size_t i = 0; i < n; ++i)
    if (!poly[i].allFinite()) return Result<TriMesh>::error("polygon corner " + std::to_string(i) + " is not finite");
  if (!(near_depth < far_depth) || !std::isfinite(near_depth) || !std::isfinite(far_depth) ||
      (!camera.orthographic && !(near_depth > 0)))
    return Result<TriMesh>::error("the depth range [" + std::to_string(near_depth) + ", " + std::to_string(far_depth) +
                                  "] is empty or starts behind the eye");
  const double area2 = signed_area_2d(poly);
  if (!(std::abs(area2) > 0)) return Result<TriMesh>::error("the polygon encloses no area");
  if (auto x = first_self_crossing(poly))
    return Result<TriMesh>::error("the polygon crosses itself at (" + std::to_string(x->x()) + ", " +
                                  std::to_string(x->y()) + ")");

  const Vec3 f = (camera.target - camera.eye).normalized();
  TriMesh m;
  m.vertices.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Ray r = camera.ray(poly[i].x(), poly[i].y());
    // A point o + t d lies at depth (o - eye) . f + t (d . f).
    const double base = (r.origin - camera.eye).dot(f), slope = r.direction.dot(f);
    m.vertices[i] = r.origin + (near_depth - base) / slope * r.direction;
    m.vertices[i + n] = r.origin + (far_depth - base) / slope * r.direction;
  }
  const auto tris = triangulate_polygon_2d(poly);
  const int ni = static_cast<int>(n);
  for (const auto& t : tris) {
    m.faces.push_back({t[0], t[1], t[2]});
    m.faces.push_back({t[0] + ni, t[2] + ni, t[1] + ni});
  }
  for (int i = 0; i < ni; ++i) {
    const int j = (i + 1) % ni;
    m.faces.push_back({i, j + ni, j});
    m.faces.push_back({i, i + ni, j + ni});
  }
  // Window y points down and the rays diverge, so the orientation is settled by the volume.
  if (signed_volume(m, m.vertices.front()) < 0)  // near the mesh: no cancellation far from the origin
    for (auto& face : m.faces) std::swap(face[1], face[2]);
  return m;
}

}  // namespace ps
