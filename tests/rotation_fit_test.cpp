// The local step's rotation fit (modeling/rotation_fit.h): the warm-started Newton iteration
// gives the closed form's rotation, falls back where it must, and never returns a reflection.
#include "modeling/rotation_fit.h"

#include <gtest/gtest.h>

#include <random>

namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

Quaterniond random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// S = Rt^T-ish covariance: sum_j w_j e_j e'_j^T with e' = R e plus noise; `planar` puts the
// rest edges in a plane (the case of a boundary node), `flip` mirrors the deformed edges so
// the unconstrained optimum is a reflection.
Matrix3d covariance(std::mt19937& rng, const Matrix3d& r, double noise, bool planar, bool flip) {
  std::normal_distribution<double> n;
  Matrix3d s = Matrix3d::Zero();
  for (int j = 0; j < 6; ++j) {
    Vector3d e(n(rng), n(rng), planar ? 0.0 : n(rng));
    Vector3d d = r * e + noise * Vector3d(n(rng), n(rng), n(rng));
    if (flip) d.z() = -d.z();
    s += (0.5 + std::abs(n(rng))) * e * d.transpose();
  }
  return s;
}

double objective(const Matrix3d& r, const Matrix3d& s) { return (r * s).trace(); }

TEST(RotationFit, ClosedFormMaximisesTheTraceOverRotations) {
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Matrix3d truth = random_rotation(rng).toRotationMatrix();
    const Matrix3d s = covariance(rng, truth, 0.3, i % 3 == 0, i % 4 == 0);
    const Matrix3d r = ps::fit_rotation(s);
    EXPECT_NEAR((r.transpose() * r - Matrix3d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    // No nearby rotation does better.
    for (int k = 0; k < 20; ++k) {
      const Matrix3d other = (Quaterniond(Eigen::AngleAxisd(0.05, Vector3d::Random().normalized())) * Quaterniond(r)).toRotationMatrix();
      EXPECT_LE(objective(other, s), objective(r, s) + 1e-12);
    }
  }
}

TEST(RotationFit, WarmStartedNewtonAgreesWithTheClosedForm) {
  std::mt19937 rng(11);
  int refined = 0;
  for (int i = 0; i < 500; ++i) {
    const Matrix3d truth = random_rotation(rng).toRotationMatrix();
    const Matrix3d s = covariance(rng, truth, 0.2, i % 5 == 0, i % 7 == 0);
    const Matrix3d exact = ps::fit_rotation(s);
    // Start a small turn away (the previous local step's rotation).
    Quaterniond q = Quaterniond(Eigen::AngleAxisd(0.05, Vector3d::Random().normalized())) * Quaterniond(exact);
    if (ps::refine_rotation(s, q)) ++refined;
    Quaterniond q2 = q;
    const Matrix3d r = ps::fit_rotation_from(s, q2);
    EXPECT_LT((r - exact).cwiseAbs().maxCoeff(), 1e-10) << "case " << i;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  }
  EXPECT_GT(refined, 450);  // the fallback is the exception
}

TEST(RotationFit, ColdStartsAndDegenerateInputsFallBackToTheClosedForm) {
  std::mt19937 rng(3);
  for (int i = 0; i < 300; ++i) {
    const Matrix3d truth = random_rotation(rng).toRotationMatrix();
    const Matrix3d s = covariance(rng, truth, 0.1, false, false);
    const Matrix3d exact = ps::fit_rotation(s);
    // From identity, whatever the distance (up to a half turn).
    Quaterniond q = Quaterniond::Identity();
    const Matrix3d r = ps::fit_rotation_from(s, q);
    EXPECT_LT((r - exact).cwiseAbs().maxCoeff(), 1e-10) << "case " << i;
    EXPECT_LT((q.toRotationMatrix() - exact).cwiseAbs().maxCoeff(), 1e-10);
  }
  // Started at the minimum of tr(R S) (a half turn from the optimum about an axis of S's
  // frame), the gradient vanishes: refine_rotation must refuse, not stop there.
  const Matrix3d s = Eigen::Vector3d(3.0, 2.0, 1.0).asDiagonal();  // optimum: identity
  Quaterniond bad(Eigen::AngleAxisd(M_PI, Vector3d::UnitX()));
  const Quaterniond before = bad;
  EXPECT_FALSE(ps::refine_rotation(s, bad));
  EXPECT_TRUE(bad.coeffs() == before.coeffs());  // unchanged on refusal
  Quaterniond q = before;
  EXPECT_LT((ps::fit_rotation_from(s, q) - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  // Rank 1 and zero covariances.
  const Matrix3d rank1 = Vector3d(1, 2, 3) * Vector3d(0.5, -1, 2).transpose();
  Quaterniond q1 = Quaterniond::Identity();
  const Matrix3d r1 = ps::fit_rotation_from(rank1, q1);
  EXPECT_NEAR(r1.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(objective(r1, rank1), objective(ps::fit_rotation(rank1), rank1), 1e-9);
  Quaterniond q0 = Quaterniond::Identity();
  EXPECT_TRUE(ps::fit_rotation_from(Matrix3d::Zero(), q0).isIdentity(0.0));
}

TEST(RotationFit, ScaleInvariant) {
  std::mt19937 rng(5);
  const Matrix3d s = covariance(rng, random_rotation(rng).toRotationMatrix(), 0.2, false, false);
  Quaterniond a = Quaterniond::Identity(), b = Quaterniond::Identity();
  const Matrix3d ra = ps::fit_rotation_from(s, a), rb = ps::fit_rotation_from(1e-9 * s, b);
  EXPECT_LT((ra - rb).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
