#pragma once
// Smoothing step of thesis Eq. 4.3, p' = p + tau N + eps T, read as (docs/mesh-improvement.md):
//
//   delta_i = (mean of the one-ring neighbours' positions) - p_i      (uniform umbrella)
//   N_i     = normalised area-weighted sum of the incident face normals
//   kappa_i = delta_i . N_i     (normal part of the umbrella: a mean-curvature estimate,
//                                kappa ~ H h^2 for local edge length h, in length units)
//   T_i     = delta_i - kappa_i N_i                 (tangential part of the umbrella)
//   tau N_i = lambda kappa_i N_i                          NormalFlow::kMeanCurvature
//           = lambda l_i^2 (kappa_i / l_i^2 - mean_j kappa_j / l_j^2) N_i
//                                                         NormalFlow::kCurvatureEvening
//   with l_i^2 the mean squared length of the edges at i (kappa_i / l_i^2 ~ -H_i / 2, so the
//   evening compares curvatures and an unevenly sampled sphere is still a fixed point)
//   p'_i    = p_i + tau N_i + eps T_i
//
// Both normal flows are explicit and stable for the default steps: the umbrella operator's
// eigenvalues lie in [0, 2], so lambda <= 1 for the mean-curvature flow and lambda < 1/2 for
// the fourth-order evening flow. Fixed vertices never move; the step is a Jacobi update (all new
// positions from the old ones), so the result does not depend on vertex order.
#include <cstdint>
#include <vector>

#include "modeling/halfedge_mesh.h"

namespace ps {

enum class NormalFlow {
  kMeanCurvature,     // second order: moves against mean curvature (shrinks, like curve-shortening)
  kCurvatureEvening,  // fourth order: evens out curvature (a sphere is a fixed point)
};

struct SmoothOptions {
  NormalFlow flow = NormalFlow::kCurvatureEvening;
  double normal_step = 0.4;      // lambda
  double tangential_step = 0.5;  // eps of Eq. 4.3
  // kCurvatureEvening only: the evening's normal move is kept within the mean-curvature move's
  // size, |tau| <= lambda |kappa_i|. On rough meshes (needles, creases: curvature estimates that
  // are mostly noise) the unlimited evening folds faces at a high rate and leaves the surface
  // crinkled; on clean ones it slows the rounding of flat parts (docs/mesh-improvement.md,
  // "Limiting the evening flow on rough meshes"). ImproveOptions::evening_limit turns it on.
  bool limit_evening = false;
};

// The collapse test of the fold checks: twice the face's area (the length of `twice_area_normal`,
// its unnormalised normal) is below 1e-10 times its squared longest edge, angles of about 1e-10
// rad, in `positions`. Refinement uses it too: such a sliver is not split (mesh_refine.h).
bool degenerate_face(const Vec3& twice_area_normal, const Face& f, const std::vector<Vec3>& positions);

// One step of Eq. 4.3: returns the new positions (#V; fixed and isolated vertices unchanged).
std::vector<Vec3> smooth_step(const HalfedgeMesh& mesh, const std::vector<std::uint8_t>& fixed,
                              const SmoothOptions& options = {});

// Puts vertices back to their positions in `before` (#V) until no face has turned over (its
// normal opposes its normal in `before`) or collapsed (twice its area below 1e-10 times its
// squared longest edge); faces already degenerate in `before` may move freely, so smoothing can
// repair them. Returns the number of reverted moves.
int revert_folded_faces(HalfedgeMesh& mesh, const std::vector<Vec3>& before);

// Repeated steps on a mesh whose connectivity stays fixed: the one-rings are gathered once.
// step() moves the free vertices of `mesh` (the one given to the constructor, same faces) and
// then undoes moves that turned a face over; it returns the number of undone moves.
class Smoother {
 public:
  Smoother(const HalfedgeMesh& mesh, const std::vector<std::uint8_t>& fixed, const SmoothOptions& options);
  int step(HalfedgeMesh& mesh);
  // Positions after one step, without the fold check (what smooth_step returns).
  std::vector<Vec3> next_positions(const HalfedgeMesh& mesh);

 private:
  SmoothOptions options_;
  std::vector<std::uint8_t> fixed_;
  std::vector<int> ring_start_, ring_;  // CSR: neighbours of v are ring_[ring_start_[v] ..]
  std::vector<int> fan_start_, fan_;    // CSR: faces around v
  std::vector<Vec3> face_normal_, delta_, normal_;
  std::vector<double> kappa_, edge2_;
};

}  // namespace ps
