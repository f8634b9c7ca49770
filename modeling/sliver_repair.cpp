// Flat slivers folded by rounding (see the header).
#include "modeling/sliver_repair.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "modeling/zone_stitch.h"

namespace ps {
namespace {
std::size_t uz(int i) { return static_cast<std::size_t>(i); }

// A seam left open after the T-junction split has two sides that meet at vertices rounding left
// apart by less than tol (stress seed 38: the two ends of a removed strip, 1 ulp apart, each
// corner of one side). Hand-written for the same reason as the rest of this file; the merge is
// limited to vertices on open edges, so the sheets the pinch resolution separated elsewhere
// (1e-10 of the diagonal apart, closed on both sides) are not touched.
void close_pinched_seams(TriMesh& mesh, double tol) {
  std::vector<std::uint64_t> directed;
  directed.reserve(mesh.faces.size() * 3);
  auto dkey = [](int a, int b) { return static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint64_t>(b); };
  for (const auto& f : mesh.faces)
    for (std::size_t i = 0; i < 3; ++i) directed.push_back(dkey(f[i], f[(i + 1) % 3]));
  std::sort(directed.begin(), directed.end());
  std::vector<int> open;
  for (const auto& f : mesh.faces)
    for (std::size_t i = 0; i < 3; ++i)
      if (!std::binary_search(directed.begin(), directed.end(), dkey(f[(i + 1) % 3], f[i]))) {
        open.push_back(f[i]);
        open.push_back(f[(i + 1) % 3]);
      }
  if (open.empty()) return;
  std::sort(open.begin(), open.end());
  open.erase(std::unique(open.begin(), open.end()), open.end());
  // Pairs within tol, by a sweep along x; each vertex goes to the smallest index of its group.
  std::sort(open.begin(), open.end(), [&](int a, int b) { return mesh.vertices[uz(a)].x() < mesh.vertices[uz(b)].x(); });
  std::vector<int> to(mesh.vertices.size());
  for (std::size_t v = 0; v < to.size(); ++v) to[v] = static_cast<int>(v);
  auto find = [&](int v) {
    while (to[uz(v)] != v) v = to[uz(v)] = to[uz(to[uz(v)])];
    return v;
  };
  bool merged = false;
  for (std::size_t i = 0; i < open.size(); ++i)
    for (std::size_t j = i + 1; j < open.size(); ++j) {
      const Vec3& a = mesh.vertices[uz(open[i])];
      const Vec3& b = mesh.vertices[uz(open[j])];
      if (b.x() - a.x() > tol) break;
      if ((a - b).norm() > tol) continue;
      const int ra = find(open[i]), rb = find(open[j]);
      if (ra == rb) continue;
      to[uz(std::max(ra, rb))] = std::min(ra, rb);
      merged = true;
    }
  if (!merged) return;
  std::vector<Face> kept;
  kept.reserve(mesh.faces.size());
  for (Face f : mesh.faces) {
    for (int& c : f) c = find(c);
    if (f[0] != f[1] && f[1] != f[2] && f[2] != f[0]) kept.push_back(f);
  }
  mesh.faces = std::move(kept);
}
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
  close_pinched_seams(mesh, tol);
  return removed;
}


}  // namespace ps
