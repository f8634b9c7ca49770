#include "modeling/gap_fill.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "modeling/polygon_triangulate.h"

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

std::uint64_t directed_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

int fill_planar_gaps(TriMesh& mesh, double plane_tol, std::vector<int>* added) {
  if (added) added->clear();
  // === Boundary half-edges: directed edges a -> b of a face with no face holding b -> a. The
  // fill runs the other way, b -> a.
  std::vector<std::uint64_t> directed;
  directed.reserve(3 * mesh.faces.size());
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k) directed.push_back(directed_key(f[uz(k)], f[uz((k + 1) % 3)]));
  std::sort(directed.begin(), directed.end());
  std::vector<std::pair<int, int>> fill_edges;  // (from, to) of the filling faces
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[uz(k)], b = f[uz((k + 1) % 3)];
      if (!std::binary_search(directed.begin(), directed.end(), directed_key(b, a))) fill_edges.emplace_back(b, a);
    }
  if (fill_edges.empty()) return 0;
  // === Loops: follow each fill edge to the one starting at its end.
  std::sort(fill_edges.begin(), fill_edges.end());
  for (std::size_t i = 1; i < fill_edges.size(); ++i)
    if (fill_edges[i].first == fill_edges[i - 1].first) return -1;  // two ways on: ambiguous
  auto next_of = [&](int v) -> int {
    const auto it = std::lower_bound(fill_edges.begin(), fill_edges.end(), std::make_pair(v, -1));
    return it != fill_edges.end() && it->first == v ? static_cast<int>(it - fill_edges.begin()) : -1;
  };
  std::vector<char> used(fill_edges.size(), 0);
  std::vector<Face> new_faces;
  int loops = 0;
  for (std::size_t s = 0; s < fill_edges.size(); ++s) {
    if (used[s]) continue;
    std::vector<int> loop;
    int e = static_cast<int>(s);
    while (e >= 0 && !used[uz(e)]) {
      used[uz(e)] = 1;
      loop.push_back(fill_edges[uz(e)].first);
      e = next_of(fill_edges[uz(e)].second);
    }
    if (e != static_cast<int>(s) || loop.size() < 3) return -1;  // open chain or a 2-gon
    // === Planarity against the Newell plane.
    std::vector<Vec3> corners;
    corners.reserve(loop.size());
    for (int v : loop) corners.push_back(mesh.vertices[uz(v)]);
    Vec3 normal = newell_normal(corners), centre = Vec3::Zero();
    for (const Vec3& p : corners) centre += p;
    centre /= static_cast<double>(corners.size());
    const double len = normal.norm();
    if (!(len > 0.0) || !std::isfinite(len)) return -1;
    normal /= len;
    for (const Vec3& p : corners)
      if (std::abs((p - centre).dot(normal)) > plane_tol) return -1;
    for (const auto& t : triangulate_polygon_3d(corners))
      new_faces.push_back({loop[uz(t[0])], loop[uz(t[1])], loop[uz(t[2])]});
    ++loops;
  }
  const int first = static_cast<int>(mesh.faces.size());
  mesh.faces.insert(mesh.faces.end(), new_faces.begin(), new_faces.end());
  if (added)
    for (int f = first; f < static_cast<int>(mesh.faces.size()); ++f) added->push_back(f);
  return loops;
}

}  // namespace ps
