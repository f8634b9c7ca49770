#include "modeling/halfedge_mesh.h"

#include <algorithm>
#include <utility>

namespace ps {
namespace {

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace

Result<HalfedgeMesh> HalfedgeMesh::build(const TriMesh& mesh) {
  HalfedgeMesh m;
  const int nv = static_cast<int>(mesh.vertices.size());
  const int nf = static_cast<int>(mesh.faces.size());
  if (nf == 0) return Result<HalfedgeMesh>::error("mesh has no faces");
  m.positions = mesh.vertices;
  m.faces = mesh.faces;
  m.twins.assign(idx(3 * nf), -1);
  m.constrained.assign(idx(3 * nf), 0);
  m.out.assign(idx(nv), -1);

  // === Index validity
  for (int f = 0; f < nf; ++f) {
    const Face& fc = mesh.faces[idx(f)];
    for (int v : fc)
      if (v < 0 || v >= nv)
        return Result<HalfedgeMesh>::error("face " + std::to_string(f) + " references vertex " +
                                           std::to_string(v) + " out of range (" +
                                           std::to_string(nv) + " vertices)");
    if (fc[0] == fc[1] || fc[1] == fc[2] || fc[0] == fc[2])
      return Result<HalfedgeMesh>::error("face " + std::to_string(f) + " repeats a vertex");
  }

  // === Twins: sort directed edges; each must appear once and its reverse once
  std::vector<std::pair<std::uint64_t, int>> directed;
  directed.reserve(idx(3 * nf));
  for (int h = 0; h < 3 * nf; ++h) directed.emplace_back(edge_key(m.source(h), m.target(h)), h);
  std::sort(directed.begin(), directed.end());
  for (std::size_t i = 1; i < directed.size(); ++i)
    if (directed[i].first == directed[i - 1].first)
      return Result<HalfedgeMesh>::error(
          "edge (" + std::to_string(m.source(directed[i].second)) + ", " +
          std::to_string(m.target(directed[i].second)) +
          ") is used twice in the same direction: the mesh is non-manifold or inconsistently oriented");
  for (int h = 0; h < 3 * nf; ++h) {
    const std::uint64_t rk = edge_key(m.target(h), m.source(h));
    auto it = std::lower_bound(directed.begin(), directed.end(), std::make_pair(rk, -1));
    if (it == directed.end() || it->first != rk)
      return Result<HalfedgeMesh>::error("edge (" + std::to_string(m.source(h)) + ", " +
                                         std::to_string(m.target(h)) +
                                         ") has one face: the mesh is not closed");
    m.twins[idx(h)] = it->second;
  }

  // === Vertex manifoldness: walking the fan from one outgoing halfedge meets every face
  std::vector<int> incident(idx(nv), 0);
  for (int h = 0; h < 3 * nf; ++h) {
    m.out[idx(m.source(h))] = h;
    ++incident[idx(m.source(h))];
  }
  for (int v = 0; v < nv; ++v) {
    if (m.out[idx(v)] < 0) continue;  // isolated vertex: kept, never touched
    int count = 0;
    const int start = m.out[idx(v)];
    int h = start;
    do {
      ++count;
      h = m.twin(prev(h));
    } while (h != start && count <= incident[idx(v)]);
    if (count != incident[idx(v)])
      return Result<HalfedgeMesh>::error("vertex " + std::to_string(v) +
                                         " is non-manifold (its faces form more than one fan)");
  }
  return m;
}

TriMesh HalfedgeMesh::to_trimesh() const {
  TriMesh t;
  t.vertices = positions;
  t.faces = faces;
  return t;
}

int HalfedgeMesh::find_halfedge(int a, int b) const {
  if (out[idx(a)] < 0) return -1;
  int found = -1;
  for_each_outgoing(a, [&](int h) {
    if (target(h) == b) found = h;
  });
  return found;
}

int HalfedgeMesh::valence(int v) const {
  if (out[idx(v)] < 0) return 0;
  int n = 0;
  for_each_outgoing(v, [&](int) { ++n; });
  return n;
}

bool HalfedgeMesh::constrain_edge(int a, int b) {
  const int h = find_halfedge(a, b);
  if (h < 0) return false;
  constrained[idx(h)] = 1;
  constrained[idx(twin(h))] = 1;
  return true;
}

int HalfedgeMesh::split_face(int f, const Vec3& p) {
  const int c = num_vertices();
  positions.push_back(p);
  const Face old = faces[idx(f)];
  const int f1 = num_faces(), f2 = f1 + 1;
  // Outer halfedges: 3f (v0->v1) stays; v1->v2 moves to 3 f1; v2->v0 moves to 3 f2.
  const int t1 = twins[idx(3 * f + 1)], t2 = twins[idx(3 * f + 2)];
  const std::uint8_t c1 = constrained[idx(3 * f + 1)], c2 = constrained[idx(3 * f + 2)];
  faces[idx(f)] = {old[0], old[1], c};
  faces.push_back({old[1], old[2], c});
  faces.push_back({old[2], old[0], c});
  twins.resize(idx(3 * num_faces()));
  constrained.resize(idx(3 * num_faces()), 0);
  constrained[idx(3 * f + 1)] = 0;
  constrained[idx(3 * f + 2)] = 0;
  constrained[idx(3 * f1)] = c1;
  constrained[idx(3 * f2)] = c2;
  auto link = [&](int a, int b) {
    twins[idx(a)] = b;
    twins[idx(b)] = a;
  };
  link(3 * f1, t1);
  link(3 * f2, t2);
  link(3 * f + 1, 3 * f1 + 2);   // v1->c  /  c->v1
  link(3 * f1 + 1, 3 * f2 + 2);  // v2->c  /  c->v2
  link(3 * f2 + 1, 3 * f + 2);   // v0->c  /  c->v0
  out.push_back(3 * f + 2);      // c->v0
  out[idx(old[1])] = 3 * f1;     // v1->v2 (its old halfedge 3f+1 now ends at c: still valid,
  out[idx(old[2])] = 3 * f2;     // but keep every vertex's entry on a live outer halfedge)
  out[idx(old[0])] = 3 * f;
  return c;
}

bool HalfedgeMesh::can_flip(int h) const {
  if (is_constrained(h)) return false;
  const int c = target(next(h));
  const int d = target(next(twin(h)));
  if (c == d) return false;
  return find_halfedge(c, d) < 0;
}

void HalfedgeMesh::flip(int h) {
  // Faces f = (a, b, c) with h = a->b, g = (b, a, d) with t = b->a.
  const int t = twin(h);
  const int f = face_of(h), g = face_of(t);
  const int a = source(h), b = target(h);
  const int c = target(next(h)), d = target(next(t));
  // Outer halfedges and their twins / flags before rewiring.
  const int hbc = next(h), hca = prev(h);  // b->c, c->a
  const int had = next(t), hdb = prev(t);  // a->d, d->b
  const int obc = twin(hbc), oca = twin(hca), oad = twin(had), odb = twin(hdb);
  const std::uint8_t cbc = constrained[idx(hbc)], cca = constrained[idx(hca)];
  const std::uint8_t cad = constrained[idx(had)], cdb = constrained[idx(hdb)];
  // New faces: f = (d, c, a) with h = d->c; g = (c, d, b) with t = c->d.
  const int kh = h % 3, kt = t % 3;
  Face nf, ng;
  nf[idx(kh)] = d;
  nf[idx((kh + 1) % 3)] = c;
  nf[idx((kh + 2) % 3)] = a;
  ng[idx(kt)] = c;
  ng[idx((kt + 1) % 3)] = d;
  ng[idx((kt + 2) % 3)] = b;
  faces[idx(f)] = nf;
  faces[idx(g)] = ng;
  auto link = [&](int x, int y, std::uint8_t flag) {
    twins[idx(x)] = y;
    twins[idx(y)] = x;
    constrained[idx(x)] = flag;
    constrained[idx(y)] = flag;
  };
  // In f: next(h) = c->a, prev(h) = a->d. In g: next(t) = d->b, prev(t) = b->c.
  link(next(h), oca, cca);
  link(prev(h), oad, cad);
  link(next(t), odb, cdb);
  link(prev(t), obc, cbc);
  twins[idx(h)] = t;
  twins[idx(t)] = h;
  constrained[idx(h)] = 0;
  constrained[idx(t)] = 0;
  out[idx(a)] = prev(h);  // a->d
  out[idx(b)] = prev(t);  // b->c
  out[idx(c)] = next(h);  // c->a
  out[idx(d)] = next(t);  // d->b
}

Vec3 HalfedgeMesh::face_normal(int f) const {
  const Face& fc = faces[idx(f)];
  const Vec3& a = positions[idx(fc[0])];
  return (positions[idx(fc[1])] - a).cross(positions[idx(fc[2])] - a);
}

}  // namespace ps
