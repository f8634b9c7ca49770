#pragma once
// Flexible mesh deformation via the edge-based graph (thesis chapter 5).
//
// Energy (Eq. 5.7), summed over the graph nodes i whose stencil touches a free vertex:
//   E = sum_i lambda_i       sum_j w+_ij |e'_ij - R_i e_ij|^2            (1-form, "hard")
//     + sum_i (1 - lambda_i) A_mean |L(y'_i) - s_i R_i delta_i|^2         (Laplacian, "soft")
//   y = D x are node positions (D: edge midpoints, or the identity for the primal domain),
//   e_ij = y_i - y_j, L(y)_i = sum_j w_ij (y_i - y_j), delta_i = L(y)_i on the rest shape,
//   w_ij = cot_ij / area_i (Eq. 5.2; edge_graph.h), w+_ij = max(w_ij, 0) (see below).
// The unknowns are the free primal vertices x (D folded in, 5.3.3). Handles are hard
// constraints and static vertices are fixed; both are eliminated to the right-hand side, so
// handles land exactly on their targets and static vertices keep their bits.
//
// Choices the thesis leaves open (docs/deformation.md):
//   - R_i: SVD of the weighted 1-form covariance S_i = sum_j w+_ij e_ij e'_ij^T + w_n n_i n'_i^T,
//     R = V U^T, with the sign of U's column for the smallest singular value flipped when
//     det < 0 (5.5). n_i is the unit normal of the faces incident to the node and w_n the mean
//     of w+_ij |e_ij|^2: without it, a boundary node whose 1-form is one vector has no unique
//     rotation. Rigid motions are still reproduced exactly.
//   - s_i: the optimal isotropic scale of the node's 1-form given R_i,
//     s_i = sum w+ e'.(R e) / sum w+ |e|^2 (the neighbourhood fit of Eq. 3.4), clamped to
//     [0.01, 100]; T_i = s_i R_i.
//   - The 1-form term uses w+ (negative cotangents of obtuse angles clamped to 0) so the system
//     matrix stays positive definite; the Laplacian keeps the signed weights.
//   - The Laplacian term is multiplied by A_mean (mean node area of the region), which makes
//     both terms dimensionless: the result is invariant to uniform scaling for every lambda.
//
// Solver (5.3.3): the normal equations A x_f = J_f^T W t - A_fk x_k are built straight into
// compressed storage and factored (Eigen SimplicialLDLT, AMD ordering) once per
// region/handles/lambda; each local/global iteration only rebuilds the targets t (local step in
// parallel with TBB) and back-substitutes the three coordinates in one pass over the factor.
// The first solve uses identity transforms (naive Laplacian editing). Each node keeps its R_i
// between local steps, and the next fit starts from it (Newton on SO(3), rotation_fit.h); deform()
// starts from identity, drag() from the previous frame's rotations. deform() accelerates the
// iterations (Anderson acceleration on the free vertices, safeguarded by the energy where the
// alternation is a descent and by the fixed-point residual elsewhere; docs/deformation.md).
#include <memory>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

enum class DeformDomain { kEdgeGraph, kPrimal };

struct DeformParameters {
  DeformDomain domain = DeformDomain::kEdgeGraph;
  double lambda = 0.5;               // global balance parameter in [0, 1] (5.4)
  std::vector<double> vertex_lambda; // empty, or #V stiffness values; NaN entries use `lambda`
  int max_iterations = 10;           // local/global iterations after the initial solve
  double tolerance = 1e-5;           // stop when |E_prev - E| / E_prev < tolerance (see stats)
  // deform(): Anderson acceleration of the local/global iterations with this many differences
  // kept (anderson_acceleration.h); 0 runs the plain alternation. drag() is never accelerated.
  int anderson_window = 5;
};

struct DeformStats {
  int free_vertices = 0, known_vertices = 0, nodes = 0, rows = 0;
  long long matrix_nonzeros = 0, factor_nonzeros = 0;
  int clamped_cotangents = 0, degenerate_triangles = 0, floored_areas = 0;
  double mesh_ms = 0;       // connectivity + graph weights (set_mesh; once per mesh and domain)
  double build_ms = 0;      // region, rows, normal matrix
  double factor_ms = 0;
  double initial_solve_ms = 0;
  std::vector<double> iteration_ms;  // one entry per local/global iteration of the last call
  double local_ms = 0, solve_ms = 0;  // deform(): summed over the iterations
  double energy_ms = 0;               // deform(): the final exact energy
  // deform(): the energy after the initial solve (identity transforms), then per iteration the
  // energy of the previous positions with that iteration's new transforms (what the
  // convergence test compares), then the exact energy of the result.
  std::vector<double> energies;
  int iterations = 0;
  bool converged = false;
  // deform() with Anderson acceleration: iterations that took the accelerated iterate, and
  // those that did not. At lambda = 1 (a descent) an accelerated iterate is taken only if it
  // lowers the energy; otherwise the plain iterate is taken (one more local step) and the
  // history restarts. Below 1 every accelerated iterate is taken, and rejected_accelerations
  // counts the restarts of the history (the fixed-point residual grew past twice its minimum).
  int accelerated_iterations = 0, rejected_accelerations = 0;
  double max_handle_residual = 0;  // largest |x_h - target_h| (0 by construction)
  double total_ms = 0;             // of the last deform()/drag() call
};

class EdgeGraphDeformer {
 public:
  EdgeGraphDeformer();
  ~EdgeGraphDeformer();
  EdgeGraphDeformer(EdgeGraphDeformer&&) noexcept;
  EdgeGraphDeformer& operator=(EdgeGraphDeformer&&) noexcept;

  // Connectivity and graph weights; refuses edges with more than two faces.
  Status set_mesh(const TriMesh& mesh);
  // Free vertices `roi`, constrained `handles` (a handle listed in roi is still a handle); all
  // other vertices are static. Builds and factors the system. Refuses out-of-range or repeated
  // indices, lambda outside [0, 1], and a free part of the mesh touching no fixed vertex.
  Status set_region(const std::vector<int>& roi, const std::vector<int>& handles,
                    const DeformParameters& parameters);
  // Cold solve from the rest shape: naive Laplacian, then iterate to convergence.
  // handle_positions[k] is the target of handles[k].
  Status deform(const std::vector<Vec3>& handle_positions);
  // Warm start from the current solution: `iterations` local/global iterations.
  Status drag(const std::vector<Vec3>& handle_positions, int iterations = 1);

  const std::vector<Vec3>& vertices() const;  // #V current positions
  TriMesh result() const;
  const DeformStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct HandleTarget {
  int vertex = -1;
  Vec3 position = Vec3::Zero();
};

// One-shot: set_mesh + set_region + deform.
Result<TriMesh> deform_mesh(const TriMesh& mesh, const std::vector<int>& roi,
                            const std::vector<HandleTarget>& handles,
                            const DeformParameters& parameters, DeformStats* stats = nullptr);

}  // namespace ps
