#pragma once
// Anderson acceleration of a fixed-point iteration u_{k+1} = G(u_k) (type II, as in Walker and
// Ni 2011, "Anderson acceleration for fixed-point iterations", and Peng et al. 2018, "Anderson
// acceleration for geometry optimization and physics simulation", which applies it to the
// local/global solvers of ARAP-like energies).
//
// With f_k = G(u_k) - u_k (the residual) and the last m differences
//   dF_j = f_{j+1} - f_j,  dG_j = G(u_{j+1}) - G(u_j),
// the next iterate is
//   u_{k+1} = G(u_k) - dG theta,  theta = argmin |f_k - dF theta|^2.
// With no history it is the plain iterate G(u_k). The accelerated iterate is not guaranteed to
// lower the energy the iteration minimises: the caller checks that and, when it does not, takes
// the plain iterate G(u_k) instead and calls reset() (Peng et al.'s safeguard).
//
// Shapes: u and g are flat vectors of one fixed length n (e.g. an n/3 x 3 row-major block of
// vertex positions seen as one vector). Everything is linear in u, so the accelerated iterate
// moves with any rigid motion or uniform scaling applied to the whole iteration.
#include <Eigen/Core>

namespace ps {

class AndersonAcceleration {
 public:
  // window: the number m of differences kept (m >= 1).
  explicit AndersonAcceleration(int window = 5);

  // Forget the history (after a rejected accelerated iterate, or for a new problem).
  void reset();

  // u: the iterate G was applied to; g = G(u), of the same length as every earlier call since
  // the last reset. Writes the next iterate to `next` and returns true when it is an accelerated
  // one (false: next = g, the first call after a reset, or a degenerate least-squares problem).
  bool next(const Eigen::Ref<const Eigen::VectorXd>& u, const Eigen::Ref<const Eigen::VectorXd>& g,
            Eigen::VectorXd& next);

  int history() const { return count_; }

 private:
  int window_;
  int count_ = 0;  // columns of df_/dg_ in use
  int head_ = 0;   // column the next difference goes to
  bool has_prev_ = false;
  Eigen::MatrixXd df_, dg_, gram_;  // n x m differences; m x m Gram matrix of df_
  Eigen::VectorXd f_prev_, g_prev_;
};

}  // namespace ps
