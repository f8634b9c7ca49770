#include "modeling/rotation_fit.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace ps {

// === Closed form (Eq. 5.5)
// The SVD is computed from the closed-form eigen decomposition of S^T S = V Sigma^2 V^T
// (U = S V Sigma^-1, re-orthonormalised), which is several times faster than Eigen's Jacobi SVD
// on 3x3 matrices; Jacobi SVD takes over when S is close to rank 1, where the squared
// condition number would cost precision.
Eigen::Matrix3d fit_rotation(const Eigen::Matrix3d& s) {
  const double scale = s.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sn = s / scale;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(sn.transpose() * sn);  // eigenvalues ascending
  const Eigen::Vector3d ev = eig.eigenvalues();
  Eigen::Matrix3d u, v;
  if (eig.info() == Eigen::Success && ev(1) > 1e-8 * ev(2)) {
    v.col(0) = eig.eigenvectors().col(2);
    v.col(1) = eig.eigenvectors().col(1);
    v.col(2) = v.col(0).cross(v.col(1));  // right-handed; its sign is irrelevant below
    const Eigen::Vector3d u0 = (sn * v.col(0)).normalized();
    Eigen::Vector3d u1 = sn * v.col(1);
    u1 = (u1 - u1.dot(u0) * u0).normalized();
    u.col(0) = u0;
    u.col(1) = u1;
    // Third column: orthogonal to the first two with the sign that S v2 has (sigma_3 >= 0).
    Eigen::Vector3d u2 = u0.cross(u1);
    if (u2.dot(sn * v.col(2)) < 0.0) u2 = -u2;
    u.col(2) = u2;
  } else {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(sn, Eigen::ComputeFullU | Eigen::ComputeFullV);
    u = svd.matrixU();
    v = svd.matrixV();
  }
  Eigen::Matrix3d r = v * u.transpose();
  if (r.determinant() < 0.0) {
    u.col(2) *= -1.0;
    r = v * u.transpose();
  }
  return r;
}

// === Newton's method on SO(3), warm-started (see the header for the derivation)
bool refine_rotation(const Eigen::Matrix3d& s, Eigen::Quaterniond& q) {
  // The step theta = H^-1 g does not depend on the scale of S (g scales like S, H^-1 like
  // 1 / S), so S is used as it is and only the thresholds, stated for |S| = 1, are scaled:
  // h00 by |S|, the 2x2 minor by |S|^2, det H by |S|^3.
  const double scale = s.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return false;
  const double min_h = 1e-4 * scale, min_minor = 1e-8 * scale * scale, min_det = 1e-12 * scale * scale * scale;
  Eigen::Quaterniond cur = q;
  constexpr int kMaxIterations = 8;
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::Matrix3d c = cur.toRotationMatrix() * s;
    const Eigen::Vector3d g(c(1, 2) - c(2, 1), c(2, 0) - c(0, 2), c(0, 1) - c(1, 0));
    const double tr = c.trace();
    const double h00 = tr - c(0, 0), h11 = tr - c(1, 1), h22 = tr - c(2, 2);
    const double h01 = -0.5 * (c(0, 1) + c(1, 0)), h02 = -0.5 * (c(0, 2) + c(2, 0)),
                 h12 = -0.5 * (c(1, 2) + c(2, 1));
    // Adjugate of the symmetric H; H is positive definite iff its leading minors are positive.
    const double a00 = h11 * h22 - h12 * h12, a01 = h02 * h12 - h01 * h22, a02 = h01 * h12 - h02 * h11;
    const double a11 = h00 * h22 - h02 * h02, a12 = h01 * h02 - h00 * h12, a22 = h00 * h11 - h01 * h01;
    const double det = h00 * a00 + h01 * a01 + h02 * a02;
    // Thresholds relative to |S| = 1: H's eigenvalues are sums of two singular values, so this
    // refuses S whose two smallest singular values sum to about 1e-4 (near rank 1).
    if (!(h00 > min_h && a22 > min_minor && det > min_det)) return false;
    const double inv_det = 1.0 / det;
    const Eigen::Vector3d theta = Eigen::Vector3d(a00 * g.x() + a01 * g.y() + a02 * g.z(),
                                                  a01 * g.x() + a11 * g.y() + a12 * g.z(),
                                                  a02 * g.x() + a12 * g.y() + a22 * g.z()) *
                                  inv_det;
    const double t2 = theta.squaredNorm();
    if (!(t2 <= 1.0)) return false;
    cur = (Eigen::Quaterniond(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()) * cur).normalized();
    if (t2 < 1e-14) {
      q = cur;
      return true;
    }
  }
  return false;
}

Eigen::Matrix3d fit_rotation_from(const Eigen::Matrix3d& s, Eigen::Quaterniond& q) {
  if (refine_rotation(s, q)) return q.toRotationMatrix();
  const Eigen::Matrix3d r = fit_rotation(s);
  q = Eigen::Quaterniond(r);
  return r;
}

}  // namespace ps
