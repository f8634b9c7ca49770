// Connectors between frusta meeting on a zone edge: see the header. The hull is CGAL's
// convex_hull_3 on the inexact-constructions kernel: its output points are copies of the input
// points (no constructions), and its predicates are exact.
#include "modeling/frustum_connectors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include "modeling/mesh_topology.h"

namespace ps {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Hull = CGAL::Surface_mesh<Point>;
using Key = std::array<double, 3>;
using Tags = std::array<int, 3>;

Key key_of(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
bool untagged(const Tags& t) { return t[0] < 0 && t[1] < 0 && t[2] < 0; }
std::size_t uz(int i) { return static_cast<std::size_t>(i); }

// Vertex neighbours of every vertex, sorted (deterministic runs).
std::vector<std::vector<int>> neighbours(const TriMesh& m) {
  std::vector<std::vector<int>> adj(m.vertices.size());
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) {
      adj[uz(f[uz(k)])].push_back(f[uz((k + 1) % 3)]);
      adj[uz(f[uz(k)])].push_back(f[uz((k + 2) % 3)]);
    }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return adj;
}

}  // namespace

std::vector<SnappedSolid> with_frustum_connectors(const std::vector<SnappedSolid>& frusta, const std::vector<Plane>& planes,
                                                  int* added, PairUnionMemo* memo) {
  const std::size_t nf = frusta.size();
  std::vector<std::vector<std::vector<int>>> adj(nf);
  std::vector<int> half(nf, 0);
  // === Shared bottom points, by coordinates.
  std::map<Key, std::vector<std::pair<int, int>>> at;
  for (std::size_t a = 0; a < nf; ++a) {
    const TriMesh& m = frusta[a].mesh;
    if (m.vertices.size() % 2 != 0 || frusta[a].tags.size() != m.vertices.size()) continue;
    adj[a] = neighbours(m);
    half[a] = static_cast<int>(m.vertices.size() / 2);
    for (int i = 0; i < half[a]; ++i) at[key_of(m.vertices[uz(i)])].emplace_back(static_cast<int>(a), i);
  }
  std::map<std::pair<int, int>, std::map<int, int>> shared;  // (a, b), a < b: vertex of a -> vertex of b
  for (const auto& [k, list] : at)
    for (std::size_t p = 0; p < list.size(); ++p)
      for (std::size_t q = p + 1; q < list.size(); ++q) {
        auto x = list[p], y = list[q];
        if (x.first == y.first) continue;
        if (x.first > y.first) std::swap(x, y);
        shared[{x.first, y.first}].emplace(x.second, y.second);
      }

  // === One hull per run of shared points.
  std::vector<std::vector<SnappedSolid>> after(nf);
  int count = 0;
  for (const auto& [ab, pairs] : shared) {
    const SnappedSolid& A = frusta[uz(ab.first)];
    const SnappedSolid& B = frusta[uz(ab.second)];
    // Only a pair whose own union is refused gets connectors: each connector is one more
    // operand with exactly coplanar contacts, the configuration CGAL 5.5's corefinement is
    // least robust on (a connector added to a pair that did not need one crashed it).
    if (memo ? memo->unites(A, B) : static_cast<bool>(union_snapped_solids({A, B}, planes))) continue;
    std::vector<SnappedSolid> pair_connectors;
    const auto& adj_a = adj[uz(ab.first)];
    const auto& adj_b = adj[uz(ab.second)];
    std::set<int> seen;
    for (const auto& start : pairs) {
      if (seen.count(start.first)) continue;
      std::vector<int> run{start.first};
      seen.insert(start.first);
      for (std::size_t q = 0; q < run.size(); ++q)
        for (int w : adj_a[uz(run[q])])
          if (pairs.count(w) && !seen.count(w)) {
            seen.insert(w);
            run.push_back(w);
          }
      // Points: the run, and the untagged top points next to it in both frusta.
      std::map<Key, Tags> points;
      auto add_tops = [&](const SnappedSolid& s, const std::vector<std::vector<int>>& adj_s, int half_s, int v) {
        for (int w : adj_s[uz(v)])
          if (w >= half_s && untagged(s.tags[uz(w)])) points.emplace(key_of(s.mesh.vertices[uz(w)]), s.tags[uz(w)]);
      };
      for (int i : run) {
        points.emplace(key_of(A.mesh.vertices[uz(i)]), A.tags[uz(i)]);
        add_tops(A, adj_a, half[uz(ab.first)], i);
        add_tops(B, adj_b, half[uz(ab.second)], pairs.at(i));
      }
      if (points.size() < 4) continue;
      std::vector<Point> pts;
      for (const auto& [k, t] : points) pts.emplace_back(k[0], k[1], k[2]);
      Hull hull;
      CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
      if (!CGAL::is_closed(hull) || hull.number_of_faces() < 4) continue;  // flat: no wedge to fill
      SnappedSolid c;
      std::map<Hull::Vertex_index, int> index;
      for (auto v : hull.vertices()) {
        const Point& p = hull.point(v);
        index[v] = static_cast<int>(c.mesh.vertices.size());
        c.mesh.vertices.emplace_back(p.x(), p.y(), p.z());
        c.tags.push_back(points.at(Key{p.x(), p.y(), p.z()}));
      }
      for (auto f : hull.faces()) {
        Face t{};
        int k = 0;
        for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
          if (k < 3) t[uz(k)] = index[v];
          ++k;
        }
        if (k != 3) continue;
        c.mesh.faces.push_back(t);
      }
      // A sliver hull would degenerate when its points are snapped. The volume is taken about
      // one of its vertices: the hull is zone-sized, far from the origin.
      const Box3 box = bounding_box(c.mesh.vertices);
      const double d = box.diagonal();
      if (!(signed_volume(c.mesh, c.mesh.vertices.front()) > 1e-9 * d * d * d)) continue;
      pair_connectors.push_back(std::move(c));
    }
    // Kept only when they make the pair's union valid.
    if (pair_connectors.empty()) continue;
    std::vector<SnappedSolid> check{A};
    check.insert(check.end(), pair_connectors.begin(), pair_connectors.end());
    check.push_back(B);
    if (!union_snapped_solids(check, planes)) continue;
    count += static_cast<int>(pair_connectors.size());
    for (auto& c : pair_connectors) after[uz(ab.first)].push_back(std::move(c));
  }
  if (added) *added = count;
  std::vector<SnappedSolid> out;
  out.reserve(nf + static_cast<std::size_t>(count));
  for (std::size_t a = 0; a < nf; ++a) {
    out.push_back(frusta[a]);
    for (auto& c : after[a]) out.push_back(std::move(c));
  }
  return out;
}

}  // namespace ps
