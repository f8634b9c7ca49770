#include "modeling/anderson_acceleration.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>

namespace ps {

AndersonAcceleration::AndersonAcceleration(int window) : window_(std::max(window, 1)) {}

void AndersonAcceleration::reset() {
  count_ = 0;
  head_ = 0;
  has_prev_ = false;
}

bool AndersonAcceleration::next(const Eigen::Ref<const Eigen::VectorXd>& u,
                                const Eigen::Ref<const Eigen::VectorXd>& g, Eigen::VectorXd& out) {
  const Eigen::Index n = u.size();
  if (has_prev_ && f_prev_.size() != n) reset();
  if (!has_prev_) {
    f_prev_ = g - u;
    g_prev_ = g;
    has_prev_ = true;
    out = g;
    return false;
  }
  if (df_.rows() != n || df_.cols() != window_) {
    df_.resize(n, window_);
    dg_.resize(n, window_);
    gram_.setZero(window_, window_);
  }
  // === New differences into the ring's column head_; f_prev_ becomes f_k on the way.
  // df = f_k - f_{k-1} = (g - u) - f_prev.
  auto df = df_.col(head_);
  df = g - u - f_prev_;
  dg_.col(head_) = g - g_prev_;
  f_prev_ += df;  // = f_k
  g_prev_ = g;
  count_ = std::min(count_ + 1, window_);
  // Gram matrix dF^T dF, updated in the row and column of the new difference only (the ring
  // fills columns 0..window-1 in order, so the valid columns are always 0..count-1).
  for (int j = 0; j < count_; ++j) gram_(head_, j) = gram_(j, head_) = df.dot(df_.col(j));
  head_ = (head_ + 1) % window_;

  // === theta = argmin |f_k - dF theta|^2 from the normal equations, columns scaled to unit
  // norm; the complete orthogonal decomposition drops directions below its threshold, so a
  // rank-deficient history (repeated differences) gives the least-norm theta, not a blow-up.
  const int m = count_;
  Eigen::VectorXd scale(m);
  for (int j = 0; j < m; ++j) {
    const double d = gram_(j, j);
    if (!(d > 0.0) || !std::isfinite(d)) {
      reset();
      out = g;
      return false;
    }
    scale(j) = 1.0 / std::sqrt(d);
  }
  const Eigen::MatrixXd normal = scale.asDiagonal() * gram_.topLeftCorner(m, m) * scale.asDiagonal();
  const Eigen::VectorXd rhs = scale.asDiagonal() * (df_.leftCols(m).transpose() * f_prev_);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  // Normal equations square the condition number: a relative pivot of 1e-10 is a singular value
  // ratio of about 1e-5 in dF.
  cod.setThreshold(1e-10);
  cod.compute(normal);
  const Eigen::VectorXd theta = scale.asDiagonal() * cod.solve(rhs);
  if (!theta.allFinite()) {
    reset();
    out = g;
    return false;
  }
  out = g - dg_.leftCols(m) * theta;
  return true;
}

}  // namespace ps
