// Zone union through Nef polyhedra (see the header). The only translation unit including
// CGAL's Nef_polyhedron_3 (slow to compile).
#include "modeling/nef_union.h"

#include "modeling/exact_snap.h"

#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <algorithm>
#include <array>
#include <map>
#include <mutex>
#include <string>

namespace ps {

Result<TriMesh> union_snapped_solids_at_once(const std::vector<SnappedSolid>& solids, const std::vector<Plane>& planes,
                                             bool allow_non_manifold, bool* manifold) {
  using Nef = CGAL::Nef_polyhedron_3<exact::K>;
  if (solids.empty()) return TriMesh{};
  // One at a time: the zone unions run in parallel, and CGAL does not document
  // Nef_polyhedron_3 as safe to use from several threads at once (its construction goes
  // through shared static helpers). The fallback is rare, so serialising it costs little.
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> hold(one_at_a_time);
  Nef acc;  // the empty set
  for (std::size_t i = 0; i < solids.size(); ++i) {
    const exact::SurfaceMesh sm = exact::snapped_surface_mesh(solids[i], planes);
    if (const std::string why = exact::unusable_operand(sm); !why.empty())
      return Result<TriMesh>::error("frustum " + std::to_string(i) + " " + why + " after snapping");
    try {
      acc += Nef(sm);
    } catch (const std::exception& e) {
      return Result<TriMesh>::error(std::string("exact union of all frusta failed: ") + e.what());
    }
  }
  if (manifold) *manifold = acc.is_simple();
  if (!acc.is_simple()) {
    if (!allow_non_manifold) return Result<TriMesh>::error("the union of all frusta is not a 2-manifold either");
    // The boundary as triangles on shared exact points: frusta that touch along an edge or at
    // a point share those vertices, which the stitch's pinch resolution then separates or joins.
    std::vector<exact::K::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    CGAL::convert_nef_polyhedron_to_polygon_soup(acc, points, polygons, /*triangulate_all_faces=*/true);
    // Points are listed once per shell: the same exact point (hence the same rounded one)
    // becomes one vertex.
    TriMesh m;
    std::map<std::array<double, 3>, int> index_of;
    std::vector<int> vertex_of(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3 p = exact::rounded_point(points[i]);
      const auto [it, added] = index_of.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(m.vertices.size()));
      if (added) m.vertices.push_back(p);
      vertex_of[i] = it->second;
    }
    // The soup of a non-manifold Nef polyhedron can list a facet once per shell that reaches
    // it: identical triangles are kept once.
    std::vector<Face> seen;
    for (const auto& poly : polygons) {
      if (poly.size() != 3) return Result<TriMesh>::error("the exact union of all frusta gave a face that is not a triangle");
      Face f{vertex_of[poly[0]], vertex_of[poly[1]], vertex_of[poly[2]]};
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
      while (f[0] > f[1] || f[0] > f[2]) f = Face{f[1], f[2], f[0]};
      seen.push_back(f);
    }
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    m.faces = std::move(seen);
    return m;
  }
  exact::SurfaceMesh out;
  CGAL::convert_nef_polyhedron_to_polygon_mesh(acc, out, /*triangulate_all_faces=*/true);
  if (const std::string why = exact::unusable_operand(out); !why.empty())
    return Result<TriMesh>::error("the exact union of all frusta " + why);
  return exact::rounded(out);
}

}  // namespace ps
