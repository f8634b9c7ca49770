// Zone union through Nef polyhedra (see the header). The only translation unit including
// CGAL's Nef_polyhedron_3 (slow to compile).
#include "modeling/nef_union.h"

#include "modeling/exact_snap.h"
#include "modeling/zone_stitch.h"

#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <array>
#include <mutex>
#include <string>

namespace ps {
namespace {

using SurfaceMesh = exact::SurfaceMesh;
using Point = exact::K::Point_3;

// === Coincident walls
//
// Two frusta of a zone can meet face to face along a wall they share: both rise from the same
// zone edge to the same two top points (stress seed 2: the pulled top points of two frusta whose
// sections meet on that edge land on the same place). In exact arithmetic the Nef union glues
// them only if the two walls are the same surface. They are not when the top points, computed
// by different formulas, differ by a rounding step, or when each frustum splits the (slightly
// non-planar) quad along the other diagonal: then a void a few 1e-17 thick stays between them,
// bounded by both walls, and the boundary is not a 2-manifold. So before the union, points of
// different frusta within `tol` of each other are made one exact point (the one of the
// lower-numbered frustum), and a wall edge whose quad another frustum splits along the other
// diagonal is flipped to match. A frustum that is no longer usable after that (a collinear or
// self-intersecting face) is left as it was. Hand-written: no CGAL function aligns the
// triangulations of two meshes along a shared patch.
void align_coincident_walls(std::vector<SurfaceMesh>& meshes, double tol) {
  struct Ref {
    std::size_t mesh;
    SurfaceMesh::Vertex_index v;
    Vec3 p;
  };
  std::vector<Ref> refs;
  for (std::size_t m = 0; m < meshes.size(); ++m)
    for (auto v : meshes[m].vertices()) refs.push_back({m, v, exact::rounded_point(meshes[m].point(v))});
  std::sort(refs.begin(), refs.end(), [](const Ref& a, const Ref& b) {
    return a.p.x() < b.p.x() || (a.p.x() == b.p.x() && (a.mesh < b.mesh || (a.mesh == b.mesh && a.v < b.v)));
  });
  std::vector<SurfaceMesh> original = meshes;
  // Points within tol of a point of a lower-numbered frustum take that point.
  for (std::size_t i = 0; i < refs.size(); ++i)
    for (std::size_t j = i + 1; j < refs.size() && refs[j].p.x() - refs[i].p.x() <= tol; ++j) {
      const Ref& a = refs[i].mesh <= refs[j].mesh ? refs[i] : refs[j];
      const Ref& b = refs[i].mesh <= refs[j].mesh ? refs[j] : refs[i];
      if (a.mesh == b.mesh || (a.p - b.p).norm() > tol) continue;
      meshes[b.mesh].point(b.v) = meshes[a.mesh].point(a.v);
    }
  // Undirected edges of each mesh by rounded end points (equal exact points round equally;
  // distinct ones within tol were merged above).
  using Key = std::array<double, 6>;
  auto point_of = [&](std::size_t m, SurfaceMesh::Vertex_index v) { return exact::rounded_point(meshes[m].point(v)); };
  auto edge_key = [](const Vec3& a, const Vec3& b) {
    const bool lt = std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    const Vec3& lo = lt ? a : b;
    const Vec3& hi = lt ? b : a;
    return Key{lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()};
  };
  std::vector<std::vector<Key>> edges(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    for (auto e : meshes[m].edges()) {
      const auto h = meshes[m].halfedge(e);
      edges[m].push_back(edge_key(point_of(m, meshes[m].source(h)), point_of(m, meshes[m].target(h))));
    }
    std::sort(edges[m].begin(), edges[m].end());
  }
  for (std::size_t m = 1; m < meshes.size(); ++m) {
    SurfaceMesh& sm = meshes[m];
    std::vector<SurfaceMesh::Halfedge_index> flips;
    for (auto e : sm.edges()) {
      const auto h = sm.halfedge(e), o = sm.opposite(h);
      if (sm.is_border(h) || sm.is_border(o)) continue;
      const Vec3 r = point_of(m, sm.target(sm.next(h))), s = point_of(m, sm.target(sm.next(o)));
      const Key other = edge_key(r, s);
      const Vec3 p = point_of(m, sm.source(h)), q = point_of(m, sm.target(h));
      for (std::size_t a = 0; a < m; ++a) {
        // The other diagonal is an edge of a lower-numbered frustum, and the quad's sides are too.
        if (!std::binary_search(edges[a].begin(), edges[a].end(), other)) continue;
        if (!std::binary_search(edges[a].begin(), edges[a].end(), edge_key(p, r)) ||
            !std::binary_search(edges[a].begin(), edges[a].end(), edge_key(p, s)) ||
            !std::binary_search(edges[a].begin(), edges[a].end(), edge_key(q, r)) ||
            !std::binary_search(edges[a].begin(), edges[a].end(), edge_key(q, s)))
          continue;
        flips.push_back(h);
        break;
      }
    }
    for (auto h : flips) {
      // The flipped diagonal must not be an edge already (a tetrahedral corner).
      if (CGAL::halfedge(sm.target(sm.next(h)), sm.target(sm.next(sm.opposite(h))), sm).second) continue;
      CGAL::Euler::flip_edge(h, sm);
    }
  }
  for (std::size_t m = 0; m < meshes.size(); ++m)
    if (!exact::unusable_operand(meshes[m]).empty() || CGAL::Polygon_mesh_processing::does_self_intersect(meshes[m]))
      meshes[m] = std::move(original[m]);
}

}  // namespace

Result<TriMesh> union_snapped_solids_at_once(const std::vector<SnappedSolid>& solids, const std::vector<Plane>& planes,
                                             bool allow_non_manifold, bool* manifold) {
  using Nef = CGAL::Nef_polyhedron_3<exact::K>;
  if (solids.empty()) return TriMesh{};
  // One at a time: the zone unions run in parallel, and CGAL does not document
  // Nef_polyhedron_3 as safe to use from several threads at once (its construction goes
  // through shared static helpers). The fallback is rare, so serialising it costs little.
  static std::mutex one_at_a_time;
  const std::lock_guard<std::mutex> hold(one_at_a_time);
  std::vector<SurfaceMesh> meshes;
  double diag = 0;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    meshes.push_back(exact::snapped_surface_mesh(solids[i], planes));
    if (const std::string why = exact::unusable_operand(meshes.back()); !why.empty())
      return Result<TriMesh>::error("frustum " + std::to_string(i) + " " + why + " after snapping");
    diag = std::max(diag, bounding_box(solids[i].mesh.vertices).diagonal());
  }
  align_coincident_walls(meshes, 1e-14 * diag);
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
