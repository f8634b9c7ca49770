#pragma once
// The rotation of the local step of the deformation (thesis Eq. 5.5): the R in SO(3) that
// maximises tr(R S) for a 3x3 covariance S = sum_j w_j e_j e'_j^T (rest edge e, deformed e').
// With S = U Sigma V^T that is R = V U^T, with the sign of U's column for the smallest singular
// value flipped when det(V U^T) < 0 (the reflection fix). Two ways to get it:
//
//   fit_rotation(S): closed form, from the eigen decomposition of S^T S (Jacobi SVD where S is
//     close to rank 1). About 240 ns per matrix on the CI machine.
//
//   refine_rotation(S, q): Newton's method on SO(3), started from the rotation q (the node's
//     rotation of the previous local step). With R = cay(theta) R0 (the Cayley map: quaternion
//     (1, theta / 2), normalised), f(theta) = tr(R S) has, at theta = 0 and C = R0 S,
//       gradient  g = (C_12 - C_21, C_20 - C_02, C_01 - C_10),
//       Hessian  -H, H = tr(C) I - (C + C^T) / 2,
//     and the step is theta = H^-1 g. Near the maximum the convergence is quadratic: a rotation
//     that moved by 0.02 rad since the last step takes three iterations (about 3x faster than
//     the closed form). H is positive definite exactly at the local maxima of f, and on SO(3)
//     f has one local maximum, the global one (every other critical point U D V^T has a pair
//     sigma_i d_i + sigma_j d_j < 0, a direction of ascent). So an iteration that finds H not
//     safely positive definite, or a step over 1 rad, gives up: refine_rotation returns false
//     and leaves q unchanged; the caller then uses fit_rotation. It returns true once a step is
//     below 1e-7 rad (what remains is O(step^2), below double precision of R).
//
// Both are invariant to the scale of S: fit_rotation works on S scaled to unit max-norm,
// refine_rotation on S itself with its thresholds scaled (its step does not depend on the scale).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ps {

Eigen::Matrix3d fit_rotation(const Eigen::Matrix3d& s);

bool refine_rotation(const Eigen::Matrix3d& s, Eigen::Quaterniond& q);

// refine_rotation from q, falling back to fit_rotation; q is set to the result.
Eigen::Matrix3d fit_rotation_from(const Eigen::Matrix3d& s, Eigen::Quaterniond& q);

}  // namespace ps
