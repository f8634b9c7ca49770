#include "modeling/pinch_separate.h"

#include "modeling/disjoint_sets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

struct Half {
  std::uint64_t key;
  int face, corner;  // edge `corner` of `face` joins its corners corner and corner + 1
};

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Corner slot of vertex v in face f (3 f + k), or -1.
int corner_of(const std::vector<Face>& faces, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (faces[uz(f)][uz(k)] == v) return 3 * f + k;
  return -1;
}

}  // namespace

// Candidates of the maximin direction: see the header.
Vec3 fan_cone_direction(const std::vector<Vec3>& u) {
  const std::size_t n = u.size();
  if (n == 0 || n > 24) return Vec3::Zero();
  Vec3 best = Vec3::Zero();
  double best_margin = 0.0;
  auto consider = [&](const Vec3& c) {
    const double len = c.norm();
    if (!(len > 1e-12) || !std::isfinite(len)) return;
    const Vec3 d = c / len;
    double margin = u[0].dot(d);
    for (std::size_t i = 1; i < n && margin > best_margin; ++i) margin = std::min(margin, u[i].dot(d));
    if (margin > best_margin) best_margin = margin, best = d;
  };
  for (std::size_t i = 0; i < n; ++i) {
    consider(u[i]);
    for (std::size_t j = i + 1; j < n; ++j) {
      consider(u[i] + u[j]);
      for (std::size_t k = j + 1; k < n; ++k) {
        const Vec3 c = (u[j] - u[i]).cross(u[k] - u[i]);
        consider(c);
        consider(-c);
      }
    }
  }
  return best;
}

int separate_pinches(TriMesh& mesh, double gap, std::vector<int>* moved, PinchMode mode,
                     PinchDirection direction) {
  if (moved) moved->clear();
  const auto& faces = mesh.faces;
  const auto& pos = mesh.vertices;
  const std::size_t nf = faces.size();
  // === Half-edges grouped by undirected edge.
  std::vector<Half> halves;
  halves.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      halves.push_back({edge_key(faces[f][uz(k)], faces[f][uz((k + 1) % 3)]), static_cast<int>(f), k});
  std::sort(halves.begin(), halves.end(),
            [](const Half& x, const Half& y) { return x.key != y.key ? x.key < y.key : x.face < y.face; });

  // === Corners glued across edges: both faces of a manifold edge; the faces of one wedge of a
  // pinched edge (step 1 of the header).
  DisjointSets uf(3 * nf);
  struct Around {
    double angle;
    int face;
    bool forward;  // runs a -> b
  };
  std::vector<Around> around;
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i + 1;
    while (j < halves.size() && halves[j].key == halves[i].key) ++j;
    const int a = static_cast<int>(halves[i].key >> 32), b = static_cast<int>(halves[i].key & 0xffffffffu);
    auto glue = [&](int f, int g) {
      uf.unite(corner_of(faces, f, a), corner_of(faces, g, a));
      uf.unite(corner_of(faces, f, b), corner_of(faces, g, b));
    };
    const std::size_t count = j - i;
    if (count == 1) return -1;  // boundary edge: not a closed surface
    if (count == 2) {
      glue(halves[i].face, halves[i + 1].face);
    } else {
      const Vec3 pa = pos[uz(a)];
      const Vec3 d = (pos[uz(b)] - pa).normalized();
      if (!d.allFinite()) return -1;
      around.clear();
      Vec3 e1 = Vec3::Zero(), e2 = Vec3::Zero();
      for (std::size_t h = i; h < j; ++h) {
        const Face& t = faces[uz(halves[h].face)];
        const int k = halves[h].corner;
        const bool forward = t[uz(k)] == a;
        const Vec3 u = pos[uz(t[uz((k + 2) % 3)])] - pa;
        const Vec3 up = u - d * d.dot(u);
        if (h == i) {
          e1 = up.normalized();
          e2 = d.cross(e1);
          if (!e1.allFinite()) return -1;
        }
        around.push_back({std::atan2(up.dot(e2), up.dot(e1)), halves[h].face, forward});
      }
      std::sort(around.begin(), around.end(), [](const Around& x, const Around& y) { return x.angle < y.angle; });
      const std::size_t n = around.size();
      for (std::size_t q = 0; q < n; ++q) {
        if (around[q].angle == around[(q + 1) % n].angle) return -1;
        if (around[q].forward == around[(q + 1) % n].forward) return -1;  // directions must alternate
      }
      // Solid wedges: each b -> a face with the next face; empty wedges (kJoin): each a -> b
      // face with the next face.
      const bool opener_runs_forward = mode == PinchMode::kJoin;
      for (std::size_t q = 0; q < n; ++q)
        if (around[q].forward == opener_runs_forward) glue(around[q].face, around[(q + 1) % n].face);
    }
    i = j;
  }
  // === Fans per vertex (step 2; vertex pinches without a pinched edge are split too): the
  // first corner of each vertex, in face order, keeps it.
  const std::size_t nv = pos.size();
  std::vector<int> owner_root(nv, -1);
  std::vector<int> vertex_of_root(3 * nf, -1);
  std::vector<Vec3> vertices = pos;
  std::vector<Face> new_faces = faces;
  std::vector<int> split_vertices;
  std::vector<char> is_split(nv, 0);
  for (std::size_t c = 0; c < 3 * nf; ++c) {
    const int v = faces[c / 3][c % 3];
    const int r = uf.find(static_cast<int>(c));
    if (owner_root[uz(v)] < 0) {
      owner_root[uz(v)] = r;
      vertex_of_root[uz(r)] = v;
    } else if (vertex_of_root[uz(r)] < 0) {
      if (!is_split[uz(v)]) is_split[uz(v)] = 1, split_vertices.push_back(v);
      vertex_of_root[uz(r)] = static_cast<int>(vertices.size());
      vertices.push_back(pos[uz(v)]);
    }
    new_faces[c / 3][c % 3] = vertex_of_root[uz(r)];
  }
  if (split_vertices.empty()) return 0;

  // === Separation (step 3): each copy moves against its fan's area-weighted normal.
  // kSeparate: into the copy's own solid, against the normal. kJoin: a copy's fan wraps an
  // empty wedge (its normals point into it), so the copy moves into that wedge, along the
  // normal, and the solid between the two copies becomes the joining sliver.
  const double toward_normal = mode == PinchMode::kSeparate ? -1.0 : 1.0;
  const bool inside_fan = direction == PinchDirection::kInsideFan;
  std::vector<Vec3> normal(vertices.size(), Vec3::Zero());
  std::vector<char> touched(vertices.size(), 0);
  // kInsideFan: each copy's face normals too, unit, signed towards the side it moves to.
  std::vector<std::vector<Vec3>> fan_normals(inside_fan ? vertices.size() : 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const Face& t = faces[f];
    const Vec3 n = (pos[uz(t[1])] - pos[uz(t[0])]).cross(pos[uz(t[2])] - pos[uz(t[0])]);
    const double len = n.norm();
    const bool has_unit = inside_fan && len > 0.0 && std::isfinite(len);
    for (int k = 0; k < 3; ++k)
      if (is_split[uz(t[uz(k)])]) {
        const int w = new_faces[f][uz(k)];
        normal[uz(w)] += n;
        touched[uz(w)] = 1;
        if (has_unit) fan_normals[uz(w)].push_back((toward_normal / len) * n);
      }
  }
  // kInsideFan: where fan_cone_direction finds a direction strictly inside all of a copy's
  // faces, it replaces the normal (signed so that the loop below moves the copy along it).
  if (inside_fan)
    for (std::size_t w = 0; w < vertices.size(); ++w)
      if (touched[w])
        if (const Vec3 d = fan_cone_direction(fan_normals[w]); d != Vec3::Zero()) normal[w] = toward_normal * d;
  std::vector<int> out_moved;
  for (std::size_t w = 0; w < vertices.size(); ++w) {
    if (!touched[w]) continue;
    const double len = normal[w].norm();
    if (!(len > 0.0) || !std::isfinite(len)) return -1;
    vertices[w] += (toward_normal * gap / len) * normal[w];
    out_moved.push_back(static_cast<int>(w));
  }
  mesh.vertices = std::move(vertices);
  mesh.faces = std::move(new_faces);
  if (moved) *moved = std::move(out_moved);
  return static_cast<int>(split_vertices.size());
}

}  // namespace ps
