#include "modeling/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace ps {
namespace {

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      auto& p = parent[static_cast<std::size_t>(x)];
      p = parent[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<std::size_t>(find(a))] = find(b); }
};

}  // namespace

double signed_volume(const TriMesh& mesh) {
  double v = 0.0;
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(f[2])];
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

int face_components(const TriMesh& mesh, std::vector<int>& component_of_face) {
  const std::size_t nf = mesh.faces.size();
  DisjointSets ds(nf);
  std::unordered_map<std::uint64_t, int> first_face_of_edge;
  first_face_of_edge.reserve(nf * 3);
  for (std::size_t fi = 0; fi < nf; ++fi) {
    const auto& f = mesh.faces[fi];
    for (int k = 0; k < 3; ++k) {
      int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      auto [it, inserted] = first_face_of_edge.emplace(edge_key(a, b), static_cast<int>(fi));
      if (!inserted) ds.unite(static_cast<int>(fi), it->second);
    }
  }
  component_of_face.assign(nf, -1);
  std::unordered_map<int, int> root_to_id;
  int count = 0;
  for (std::size_t fi = 0; fi < nf; ++fi) {
    const int r = ds.find(static_cast<int>(fi));
    auto [it, inserted] = root_to_id.emplace(r, count);
    if (inserted) ++count;
    component_of_face[fi] = it->second;
  }
  return count;
}

MeshTopology mesh_topology(const TriMesh& mesh) {
  MeshTopology t;
  std::ostringstream problem;
  const std::size_t nv = mesh.vertices.size();
  const std::size_t nf = mesh.faces.size();

  // === Index validity and degenerate faces
  for (std::size_t fi = 0; fi < nf; ++fi) {
    const auto& f = mesh.faces[fi];
    for (int v : f) {
      if (v < 0 || static_cast<std::size_t>(v) >= nv) {
        t.problem = "face " + std::to_string(fi) + " references vertex " + std::to_string(v) +
                    " out of range";
        return t;
      }
    }
  }
  const double diag = bounding_box(mesh.vertices).diagonal();
  const double area_eps = 1e-14 * diag * diag;
  for (std::size_t fi = 0; fi < nf; ++fi) {
    const auto& f = mesh.faces[fi];
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(f[2])];
    const double area2 = (b - a).cross(c - a).norm();
    t.area += 0.5 * area2;
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || !(area2 > area_eps)) ++t.degenerate_faces;
  }

  // === Edges: undirected incidence and directed uniqueness
  std::unordered_map<std::uint64_t, int> undirected;
  std::unordered_map<std::uint64_t, int> directed;
  undirected.reserve(nf * 3);
  directed.reserve(nf * 3);
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 3)];
      ++directed[edge_key(a, b)];
      ++undirected[edge_key(std::min(a, b), std::max(a, b))];
    }
  }
  bool dir_ok = true;
  for (const auto& [k, c] : directed)
    if (c > 1) dir_ok = false;
  for (const auto& [k, c] : undirected) {
    if (c == 1) ++t.boundary_edges;
    if (c > 2) ++t.nonmanifold_edges;
  }
  t.closed = t.boundary_edges == 0 && nf > 0;
  t.edge_manifold = t.nonmanifold_edges == 0;
  t.consistently_oriented = dir_ok;

  // === Vertex manifoldness: the faces around a vertex are connected through shared edges
  // into a single fan (checked with a union-find over the incident faces).
  std::vector<std::vector<int>> vf(nv);
  for (std::size_t fi = 0; fi < nf; ++fi)
    for (int v : mesh.faces[fi]) vf[static_cast<std::size_t>(v)].push_back(static_cast<int>(fi));
  std::vector<int> referenced_vertices;
  for (std::size_t v = 0; v < nv; ++v) {
    const auto& fs = vf[v];
    if (fs.empty()) {
      ++t.isolated_vertices;
      continue;
    }
    referenced_vertices.push_back(static_cast<int>(v));
    // other-vertex -> local face indices
    std::unordered_map<int, std::vector<int>> by_neighbor;
    for (std::size_t i = 0; i < fs.size(); ++i)
      for (int w : mesh.faces[static_cast<std::size_t>(fs[i])])
        if (w != static_cast<int>(v)) by_neighbor[w].push_back(static_cast<int>(i));
    DisjointSets ds(fs.size());
    for (const auto& [w, list] : by_neighbor)
      for (std::size_t i = 1; i < list.size(); ++i) ds.unite(list[0], list[i]);
    int roots = 0;
    for (std::size_t i = 0; i < fs.size(); ++i)
      if (ds.find(static_cast<int>(i)) == static_cast<int>(i)) ++roots;
    if (roots != 1) ++t.nonmanifold_vertices;
  }
  t.vertex_manifold = t.nonmanifold_vertices == 0;

  // === Components, Euler characteristic, genus
  std::vector<int> comp;
  t.components = face_components(mesh, comp);
  const long V = static_cast<long>(referenced_vertices.size());
  const long E = static_cast<long>(undirected.size());
  const long F = static_cast<long>(nf);
  t.euler_characteristic = static_cast<int>(V - E + F);
  if (t.closed && t.manifold() && t.consistently_oriented) {
    // chi = sum over components (2 - 2 g_c)  =>  total genus = (2C - chi) / 2
    t.genus = (2 * t.components - t.euler_characteristic) / 2;
  }
  t.signed_volume = signed_volume(mesh);

  // === First problem in words
  if (nf == 0)
    problem << "mesh has no faces";
  else if (!t.edge_manifold)
    problem << t.nonmanifold_edges << " non-manifold edge(s) (more than two faces)";
  else if (!t.vertex_manifold)
    problem << t.nonmanifold_vertices << " non-manifold vertex(es)";
  else if (!t.consistently_oriented)
    problem << "inconsistent face orientation";
  else if (!t.closed)
    problem << t.boundary_edges << " boundary edge(s): the mesh has holes";
  else if (!(t.signed_volume > 0.0))
    problem << "the mesh is oriented inward (negative volume)";
  t.problem = problem.str();
  return t;
}

}  // namespace ps
