#include "modeling/edge_graph.h"

#include <algorithm>
#include <string>

#include "modeling/cotan_weights.h"
#include "modeling/radix_sort.h"

namespace ps {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// Directed weighted graph edges collected per node, then merged into CSR form.
struct Arc {
  int from, to;
  double cot;
};

void to_csr(std::vector<Arc>& arcs, std::size_t num_nodes, DeformGraph& g) {
  std::sort(arcs.begin(), arcs.end(),
            [](const Arc& x, const Arc& y) { return x.from != y.from ? x.from < y.from : x.to < y.to; });
  g.offsets.assign(num_nodes + 1, 0);
  g.neighbors.clear();
  g.cot.clear();
  for (std::size_t k = 0; k < arcs.size(); ++k) {
    if (k > 0 && arcs[k].from == arcs[k - 1].from && arcs[k].to == arcs[k - 1].to) {
      g.cot.back() += arcs[k].cot;  // duplicate (same pair through two faces): sum
      continue;
    }
    g.neighbors.push_back(arcs[k].to);
    g.cot.push_back(arcs[k].cot);
    ++g.offsets[static_cast<std::size_t>(arcs[k].from) + 1];
  }
  for (std::size_t i = 0; i < num_nodes; ++i) g.offsets[i + 1] += g.offsets[i];
}

void floor_areas(DeformGraph& g) {
  double sum = 0.0;
  std::size_t n = 0;
  for (double a : g.area)
    if (a > 0.0) sum += a, ++n;
  const double floor = n > 0 ? 1e-12 * sum / static_cast<double>(n) : 1.0;
  for (double& a : g.area)
    if (!(a > 0.0)) a = floor, ++g.floored_areas;
}

}  // namespace

Result<MeshEdges> mesh_edges(const TriMesh& mesh) {
  MeshEdges out;
  const int nv = static_cast<int>(mesh.vertices.size());
  const std::size_t nf = mesh.faces.size();
  out.face_edges.resize(nf);
  // Half-edges sorted by their undirected key (faster than hashing on large meshes).
  struct Half {
    std::uint64_t key;
    int face, corner;
  };
  std::vector<Half> halves;
  halves.reserve(nf * 3);
  for (std::size_t f = 0; f < nf; ++f) {
    const Face& t = mesh.faces[f];
    for (std::size_t k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= nv)
        return Result<MeshEdges>::error("face " + std::to_string(f) + ": vertex index " + std::to_string(t[k]) +
                                        " out of range");
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return Result<MeshEdges>::error("face " + std::to_string(f) + " repeats a vertex");
    for (std::size_t k = 0; k < 3; ++k)
      halves.push_back({edge_key(t[k], t[(k + 1) % 3]), static_cast<int>(f), static_cast<int>(k)});
  }
  // Order: by key, then by face. Radix sort of (key, half-edge index) packed into 64 bits when
  // they fit (meshes under about 2^20 vertices): about 4x faster than std::sort here, and
  // set_mesh runs for every new mesh the deformation tool sees.
  const int vbits = bits_for(static_cast<std::uint64_t>(nv)), hbits = bits_for(nf * 3);
  if (2 * vbits + hbits <= 64) {
    std::vector<std::uint64_t> packed(halves.size());
    for (std::size_t h = 0; h < halves.size(); ++h) {
      const auto lo = static_cast<std::uint64_t>(halves[h].key & 0xffffffffu), hi = halves[h].key >> 32;
      packed[h] = (((hi << vbits) | lo) << hbits) | h;  // h = 3 * face + corner, increasing with face
    }
    radix_sort(packed, 2 * vbits + hbits);
    std::vector<Half> sorted(halves.size());
    const std::uint64_t hmask = (std::uint64_t{1} << hbits) - 1;
    for (std::size_t i = 0; i < packed.size(); ++i) sorted[i] = halves[static_cast<std::size_t>(packed[i] & hmask)];
    halves.swap(sorted);
  } else {
    std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
      return x.key != y.key ? x.key < y.key : x.face < y.face;
    });
  }
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i + 1;
    while (j < halves.size() && halves[j].key == halves[i].key) ++j;
    const Face& t = mesh.faces[static_cast<std::size_t>(halves[i].face)];
    const int a = t[static_cast<std::size_t>(halves[i].corner)], b = t[static_cast<std::size_t>((halves[i].corner + 1) % 3)];
    if (j - i > 2)
      return Result<MeshEdges>::error("edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                      ") is shared by more than two faces (non-manifold)");
    const int e = static_cast<int>(out.edges.size());
    out.edges.push_back({std::min(a, b), std::max(a, b)});
    out.edge_faces.push_back({halves[i].face, j - i == 2 ? halves[i + 1].face : -1});
    for (std::size_t k = i; k < j; ++k)
      out.face_edges[static_cast<std::size_t>(halves[k].face)][static_cast<std::size_t>(halves[k].corner)] = e;
    if (j - i == 1) ++out.boundary_edges;
    i = j;
  }
  return out;
}

DeformGraph build_edge_graph(const TriMesh& mesh, const MeshEdges& me) {
  DeformGraph g;
  const std::size_t ne = me.edges.size();
  g.node_vertices = me.edges;
  g.node_coef.assign(ne, {0.5, 0.5});
  g.area.assign(ne, 0.0);
  // Node e has two neighbours per incident face: slots [4e, 4e+2) for edge_faces[e][0],
  // [4e+2, 4e+4) for edge_faces[e][1]; compacted below for boundary edges.
  std::vector<int> nbr(ne * 4, -1);
  std::vector<double> cot(ne * 4, 0.0);
  auto slot = [&](int e, int f) {
    const auto& ef = me.edge_faces[static_cast<std::size_t>(e)];
    return static_cast<std::size_t>(e) * 4 + (ef[0] == f ? 0u : 2u);
  };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Vec3* p[3] = {&mesh.vertices[static_cast<std::size_t>(t[0])], &mesh.vertices[static_cast<std::size_t>(t[1])],
                        &mesh.vertices[static_cast<std::size_t>(t[2])]};
    const double area = 0.5 * (*p[1] - *p[0]).cross(*p[2] - *p[0]).norm();
    if (!(area > 0.0)) ++g.degenerate_triangles;
    const int fi = static_cast<int>(f);
    // Edge k joins corners k and k+1; edges k and k-1 (mod 3) share corner k, and the graph
    // edge between their midpoints has cot(angle at corner k) as its weight.
    for (std::size_t k = 0; k < 3; ++k) {
      bool clamped = false;
      const double c = clamped_cot(*p[k], *p[(k + 1) % 3], *p[(k + 2) % 3], &clamped);
      if (clamped) ++g.clamped_cotangents;
      const int e_next = me.face_edges[f][k];            // (k, k+1)
      const int e_prev = me.face_edges[f][(k + 2) % 3];  // (k-1, k)
      const std::size_t sn = slot(e_next, fi), sp = slot(e_prev, fi);
      nbr[sn] = e_prev, cot[sn] = c;          // first slot of e_next in f: neighbour across corner k
      nbr[sp + 1] = e_next, cot[sp + 1] = c;  // second slot of e_prev in f
      g.area[static_cast<std::size_t>(e_next)] += 0.25 * area;
    }
  }
  g.offsets.assign(ne + 1, 0);
  g.neighbors.reserve(ne * 4);
  g.cot.reserve(ne * 4);
  for (std::size_t e = 0; e < ne; ++e) {
    for (std::size_t k = 4 * e; k < 4 * e + 4; ++k)
      if (nbr[k] >= 0) g.neighbors.push_back(nbr[k]), g.cot.push_back(cot[k]);
    g.offsets[e + 1] = static_cast<int>(g.neighbors.size());
  }
  floor_areas(g);
  g.face_offsets.assign(ne + 1, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    for (int f : me.edge_faces[e])
      if (f >= 0) g.faces.push_back(f);
    g.face_offsets[e + 1] = static_cast<int>(g.faces.size());
  }
  return g;
}

DeformGraph build_primal_graph(const TriMesh& mesh, const MeshEdges& me) {
  (void)me;
  DeformGraph g;
  const std::size_t nv = mesh.vertices.size();
  g.node_vertices.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) g.node_vertices[v] = {static_cast<int>(v), static_cast<int>(v)};
  g.node_coef.assign(nv, {1.0, 0.0});
  g.area.assign(nv, 0.0);
  std::vector<Arc> arcs;
  arcs.reserve(mesh.faces.size() * 6);
  for (const Face& t : mesh.faces) {
    const Vec3* p[3] = {&mesh.vertices[static_cast<std::size_t>(t[0])],
                        &mesh.vertices[static_cast<std::size_t>(t[1])],
                        &mesh.vertices[static_cast<std::size_t>(t[2])]};
    if (!(0.5 * (*p[1] - *p[0]).cross(*p[2] - *p[0]).norm() > 0.0)) ++g.degenerate_triangles;
    const auto shares = mixed_areas(*p[0], *p[1], *p[2]);
    for (std::size_t k = 0; k < 3; ++k) {
      bool clamped = false;
      // The angle at corner k is opposite edge (k+1, k+2).
      const double c = 0.5 * clamped_cot(*p[k], *p[(k + 1) % 3], *p[(k + 2) % 3], &clamped);
      if (clamped) ++g.clamped_cotangents;
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      arcs.push_back({a, b, c});
      arcs.push_back({b, a, c});
      g.area[static_cast<std::size_t>(t[k])] += shares[k];
    }
  }
  to_csr(arcs, nv, g);
  floor_areas(g);
  g.face_offsets.assign(nv + 1, 0);
  for (const Face& t : mesh.faces)
    for (int v : t) ++g.face_offsets[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) g.face_offsets[v + 1] += g.face_offsets[v];
  g.faces.resize(static_cast<std::size_t>(g.face_offsets[nv]));
  std::vector<int> fill(g.face_offsets.begin(), g.face_offsets.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) g.faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(f);
  return g;
}

Eigen::SparseMatrix<double> node_matrix(const DeformGraph& g, int num_vertices) {
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t i = 0; i < g.num_nodes(); ++i)
    for (std::size_t k = 0; k < 2; ++k)
      if (g.node_coef[i][k] != 0.0)
        trip.emplace_back(static_cast<int>(i), g.node_vertices[i][k], g.node_coef[i][k]);
  Eigen::SparseMatrix<double> d(static_cast<Eigen::Index>(g.num_nodes()), num_vertices);
  d.setFromTriplets(trip.begin(), trip.end());
  return d;
}

Eigen::SparseMatrix<double> graph_laplacian(const DeformGraph& g) {
  std::vector<Eigen::Triplet<double>> trip;
  const int n = static_cast<int>(g.num_nodes());
  for (int i = 0; i < n; ++i) {
    double diag = 0.0;
    for (int k = g.offsets[static_cast<std::size_t>(i)]; k < g.offsets[static_cast<std::size_t>(i) + 1]; ++k) {
      const double w = g.weight(static_cast<std::size_t>(k), static_cast<std::size_t>(i));
      trip.emplace_back(i, g.neighbors[static_cast<std::size_t>(k)], -w);
      diag += w;
    }
    trip.emplace_back(i, i, diag);
  }
  Eigen::SparseMatrix<double> l(n, n);
  l.setFromTriplets(trip.begin(), trip.end());
  return l;
}

}  // namespace ps
