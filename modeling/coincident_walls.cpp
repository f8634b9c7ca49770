// Coincident walls of a zone's frusta made one surface (see the header).
#include "modeling/coincident_walls.h"

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <array>

namespace ps::exact {

int align_coincident_walls(std::vector<SurfaceMesh>& meshes, const std::vector<SnappedSolid>& solids, double tol,
                           std::vector<char>* kept) {
  int changes = 0;
  auto untagged = [&](std::size_t m, SurfaceMesh::Vertex_index v) {
    const auto& tags = solids[m].tags;
    const std::size_t i = v.idx();
    return i >= tags.size() || (tags[i][0] < 0 && tags[i][1] < 0 && tags[i][2] < 0);
  };
  struct Ref {
    std::size_t mesh;
    SurfaceMesh::Vertex_index v;
    Vec3 p;
  };
  std::vector<Ref> refs;
  for (std::size_t m = 0; m < meshes.size(); ++m)
    for (auto v : meshes[m].vertices()) refs.push_back({m, v, rounded_point(meshes[m].point(v))});
  std::sort(refs.begin(), refs.end(), [](const Ref& a, const Ref& b) {
    return a.p.x() < b.p.x() || (a.p.x() == b.p.x() && (a.mesh < b.mesh || (a.mesh == b.mesh && a.v < b.v)));
  });
  std::vector<SurfaceMesh> original = meshes;
  std::vector<char> changed(meshes.size(), 0);
  // Points within tol of a point of a lower-numbered frustum take that point.
  for (std::size_t i = 0; i < refs.size(); ++i)
    for (std::size_t j = i + 1; j < refs.size() && refs[j].p.x() - refs[i].p.x() <= tol; ++j) {
      const Ref& a = refs[i].mesh <= refs[j].mesh ? refs[i] : refs[j];
      const Ref& b = refs[i].mesh <= refs[j].mesh ? refs[j] : refs[i];
      if (a.mesh == b.mesh || (a.p - b.p).norm() > tol || !untagged(b.mesh, b.v)) continue;
      if (meshes[b.mesh].point(b.v) == meshes[a.mesh].point(a.v)) continue;
      meshes[b.mesh].point(b.v) = meshes[a.mesh].point(a.v);
      changed[b.mesh] = 1;
      ++changes;
    }
  // Undirected edges of each mesh by rounded end points (equal exact points round equally;
  // distinct ones within tol were merged above).
  using Key = std::array<double, 6>;
  auto point_of = [&](std::size_t m, SurfaceMesh::Vertex_index v) { return rounded_point(meshes[m].point(v)); };
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
      // Walls only: a zone-face cap (every corner on its plane) keeps its triangulation, which
      // the neighbouring zone's cap must match.
      if (!untagged(m, sm.source(h)) && !untagged(m, sm.target(h))) continue;
      if (!untagged(m, sm.target(sm.next(h))) && !untagged(m, sm.target(sm.next(o)))) continue;
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
      changed[m] = 1;
      ++changes;
    }
  }
  if (kept) kept->assign(meshes.size(), 0);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (!changed[m]) continue;
    if (!unusable_operand(meshes[m]).empty() || CGAL::Polygon_mesh_processing::does_self_intersect(meshes[m]))
      meshes[m] = std::move(original[m]);
    else if (kept)
      (*kept)[m] = 1;
  }
  return changes;
}

}  // namespace ps::exact
