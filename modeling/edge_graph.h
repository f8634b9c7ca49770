#pragma once
// The graphs the flexible deformation energy (thesis Eq. 5.7) is formulated on:
//   - the edge-based graph (thesis 5.2): one node per primal edge, at its midpoint; node (a, b)
//     connects to the edges that share a or b inside the (one or two) triangles incident to
//     (a, b): valence 4 inside, 2 on a boundary edge of an open mesh;
//   - the primal graph: one node per vertex, connected to its one-ring (for comparison).
//
// Both are described the same way, so one solver serves both (edge_graph_deformer.h):
//   node i sits at y_i = sum_k node_coef[i][k] * x[node_vertices[i][k]]  (a row of D, n_e x n;
//   two entries of 1/2 for the edge graph, one entry 1 for the primal graph, the unused slot
//   has coefficient 0 and repeats the first vertex).
//
// Weights (Eq. 5.2): w_ij = cot_ij / area_i, where cot_ij = (cot alpha_ij + cot beta_ij) / 2.
//   Primal graph: alpha, beta are the angles opposite edge (i, j); area_i is the mixed Voronoi
//   area of vertex i (Meyer et al.).
//   Edge graph: the weights are those of the midpoint (1-to-4) subdivision of the mesh, which
//   contains every edge-graph edge: the graph edge between the midpoints of (a, b) and (a, c)
//   is shared by the sub-triangles (a, m_ab, m_ac) and (m_ab, m_bc, m_ac), whose angles
//   opposite it both equal the angle at a in triangle (a, b, c); so cot_ij = cot(angle at a).
//   area_i is the mixed Voronoi area of the midpoint in that subdivision, which sums exactly
//   to a quarter of the areas of the triangles incident to the edge (see docs/deformation.md).
//   Degenerate angles are clamped (cotan_weights.h) and counted.
#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// Edge connectivity of a triangle mesh.
struct MeshEdges {
  std::vector<std::array<int, 2>> edges;       // #E vertex pairs, first < second
  std::vector<std::array<int, 2>> edge_faces;  // #E incident faces; second is -1 on a boundary
  std::vector<std::array<int, 3>> face_edges;  // #F: edge k joins face corners k and k+1 (mod 3)
  int boundary_edges = 0;
};

// Refuses (naming the edge) meshes with an edge shared by more than two faces, degenerate faces
// that repeat a vertex, and out-of-range indices.
Result<MeshEdges> mesh_edges(const TriMesh& mesh);

struct DeformGraph {
  std::vector<std::array<int, 2>> node_vertices;
  std::vector<std::array<double, 2>> node_coef;
  std::vector<int> offsets;     // CSR: neighbours of node i are [offsets[i], offsets[i + 1])
  std::vector<int> neighbors;
  std::vector<double> cot;      // (cot alpha + cot beta) / 2 per directed graph edge (i -> j)
  std::vector<double> area;     // area_i per node, > 0 (floored for degenerate neighbourhoods)
  std::vector<int> face_offsets;  // CSR: faces incident to node i (its normal's support)
  std::vector<int> faces;
  int clamped_cotangents = 0;   // triangle corners whose cotangent was clamped
  int degenerate_triangles = 0; // zero-area triangles
  int floored_areas = 0;        // nodes whose area was zero and got floored

  std::size_t num_nodes() const { return node_vertices.size(); }
  double weight(std::size_t k, std::size_t i) const { return cot[k] / area[i]; }  // Eq. 5.2
};

DeformGraph build_edge_graph(const TriMesh& mesh, const MeshEdges& edges);
DeformGraph build_primal_graph(const TriMesh& mesh, const MeshEdges& edges);

// D: #nodes x #V, y = D x (two entries of 1/2 per row for the edge graph).
Eigen::SparseMatrix<double> node_matrix(const DeformGraph& graph, int num_vertices);
// L: #nodes x #nodes, (L y)_i = sum_j w_ij (y_i - y_j) (Eq. 5.1); each row sums to zero.
Eigen::SparseMatrix<double> graph_laplacian(const DeformGraph& graph);

}  // namespace ps
