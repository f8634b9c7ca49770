// Flat slivers folded by rounding (see the header).
#include "modeling/sliver_repair.h"

#include <algorithm>
#include <cstddef>

#include "modeling/zone_stitch.h"

namespace ps {
namespace {
std::size_t uz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

double face_height(const TriMesh& mesh, const Face& f) {
  const Vec3& a = mesh.vertices[uz(f[0])];
  const Vec3& b = mesh.vertices[uz(f[1])];
  const Vec3& c = mesh.vertices[uz(f[2])];
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  if (!(longest > 0.0)) return 0.0;
  return (b - a).cross(c - a).norm() / longest;  // twice the area over the base
}

int remove_folded_slivers(TriMesh& mesh, const std::vector<std::array<int, 2>>& crossing, double tol) {
  const std::size_t nf = mesh.faces.size();
  // === Seeds: flat faces with a vertex on a crossing face.
  std::vector<char> near(mesh.vertices.size(), 0);
  for (const auto& pair : crossing)
    for (int f : pair)
      if (f >= 0 && uz(f) < nf)
        for (int v : mesh.faces[uz(f)]) near[uz(v)] = 1;
  std::vector<char> flat(nf, 0), remove(nf, 0);
  for (std::size_t f = 0; f < nf; ++f) flat[f] = face_height(mesh, mesh.faces[f]) <= tol ? 1 : 0;
  std::vector<int> stack;
  for (std::size_t f = 0; f < nf; ++f) {
    if (!flat[f]) continue;
    const Face& fc = mesh.faces[f];
    if (near[uz(fc[0])] || near[uz(fc[1])] || near[uz(fc[2])]) {
      remove[f] = 1;
      stack.push_back(static_cast<int>(f));
    }
  }
  if (stack.empty()) return 0;
  // === Grow over flat faces sharing an edge (a strip along a crease).
  std::vector<std::pair<std::uint64_t, int>> edges;  // undirected edge key, face
  edges.reserve(nf * 3);
  auto key = [](int a, int b) {
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint64_t>(std::max(a, b));
  };
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t i = 0; i < 3; ++i)
      edges.emplace_back(key(mesh.faces[f][i], mesh.faces[f][(i + 1) % 3]), static_cast<int>(f));
  std::sort(edges.begin(), edges.end());
  while (!stack.empty()) {
    const Face fc = mesh.faces[uz(stack.back())];
    stack.pop_back();
    for (std::size_t i = 0; i < 3; ++i) {
      const std::uint64_t k = key(fc[i], fc[(i + 1) % 3]);
      auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(k, -1));
      for (; it != edges.end() && it->first == k; ++it) {
        const auto g = uz(it->second);
        if (flat[g] && !remove[g]) {
          remove[g] = 1;
          stack.push_back(it->second);
        }
      }
    }
  }
  // === Remove, then zip the seams.
  std::vector<Face> kept;
  kept.reserve(nf);
  int removed = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    if (remove[f]) ++removed;
    else kept.push_back(mesh.faces[f]);
  }
  mesh.faces = std::move(kept);
  split_t_junctions(mesh, tol);
  return removed;
}

}  // namespace ps
