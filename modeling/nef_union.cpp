// Zone union through Nef polyhedra (see the header). The only translation unit including
// CGAL's Nef_polyhedron_3 (slow to compile).
#include "modeling/nef_union.h"

#include "modeling/coincident_walls.h"
#include "modeling/exact_snap.h"
#include "modeling/zone_stitch.h"

#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <algorithm>
#include <array>
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
  std::vector<exact::SurfaceMesh> meshes;
  double diag = 0;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    meshes.push_back(exact::snapped_surface_mesh(solids[i], planes));
    if (const std::string why = exact::unusable_operand(meshes.back()); !why.empty())
      return Result<TriMesh>::error("frustum " + std::to_string(i) + " " + why + " after snapping");
    diag = std::max(diag, bounding_box(solids[i].mesh.vertices).diagonal());
  }
  exact::align_coincident_walls(meshes, solids, 1e-14 * diag);
  Nef acc;  // the empty set
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const exact::SurfaceMesh& sm = meshes[i];
    try {
      acc += Nef(sm);
    } catch (const std::exception& e) {
      return Result<TriMesh>::error(std::string("exact union of all frusta failed: ") + e.what());
    }
  }
  const bool simple = acc.is_simple();
  if (manifold) *manifold = simple;
  if (!simple) {
    if (!allow_non_manifold) return Result<TriMesh>::error("the union of all frusta is not a 2-manifold either");
    // The boundary as triangles on shared exact points: frusta that touch along an edge or at
    // a point share those vertices, which the stitch's pinch resolution then separates or joins.
    std::vector<exact::K::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    CGAL::convert_nef_polyhedron_to_polygon_soup(acc, points, polygons, /*triangulate_all_faces=*/true);
    TriMesh m;
    m.vertices.reserve(points.size());
    for (const auto& p : points) m.vertices.push_back(exact::rounded_point(p));
    for (const auto& poly : polygons) {
      if (poly.size() != 3) return Result<TriMesh>::error("the exact union of all frusta gave a face that is not a triangle");
      m.faces.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[1]), static_cast<int>(poly[2])});
    }
    // Points are listed once per shell: the same exact point (hence the same rounded one)
    // becomes one vertex (a weld of identical positions only). A facet can be listed once per
    // shell that reaches it: in canonical order identical triangles are neighbours, kept once.
    m = weld_vertices(m, 0.0);
    canonicalize(m);
    m.faces.erase(std::unique(m.faces.begin(), m.faces.end()), m.faces.end());
    return m;
  }
  exact::SurfaceMesh out;
  CGAL::convert_nef_polyhedron_to_polygon_mesh(acc, out, /*triangulate_all_faces=*/true);
  if (const std::string why = exact::unusable_operand(out); !why.empty())
    return Result<TriMesh>::error("the exact union of all frusta " + why);
  return exact::rounded(out);
}

}  // namespace ps
