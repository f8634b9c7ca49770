// Curve sewing (stroke rule 4, thesis 3.3.2, Eqs. 3.2-3.4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "modeling/curve_sewing.h"

using namespace ps;

namespace {

// An ellipse o + (c1 + ra cos t) e1 + (c2 + rb sin t) e2, t = phase + 2 pi k / n.
CrossSection ellipse(int plane, Vec3 o, Vec3 e1, Vec3 e2, Vec2 c, double ra, double rb, int n, double phase) {
  CrossSection s;
  s.plane = plane;
  for (int k = 0; k < n; ++k) {
    const double t = phase + 2 * M_PI * k / n;
    s.points.push_back(o + (c.x() + ra * std::cos(t)) * e1 + (c.y() + rb * std::sin(t)) * e2);
  }
  return s;
}

// An annular sector (a "C"): outer arc from a0 to a1 degrees, inner arc back.
CrossSection sector(int plane, Vec3 e1, Vec3 e2, double r_in, double r_out, double a0, double a1, int m) {
  CrossSection s;
  s.plane = plane;
  for (int k = 0; k < m; ++k) {
    const double a = (a0 + (a1 - a0) * k / (m - 1)) * M_PI / 180;
    s.points.push_back(r_out * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  for (int k = m - 1; k >= 0; --k) {
    const double a = (a0 + (a1 - a0) * k / (m - 1)) * M_PI / 180;
    s.points.push_back(r_in * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  return s;
}

std::vector<Vec3> crossings_of_plane_curves(const SectionSet& s, int plane, const Plane& other) {
  SectionSet sub;
  sub.planes = s.planes;
  for (const auto& c : s.curves)
    if (c.plane == plane) sub.curves.push_back(c);
  return required_crossings(sub, other);
}

// Largest distance between matched crossings over all plane pairs (rule 4); infinity when a
// pair of planes has different crossing counts.
double max_crossing_gap(const SectionSet& s) {
  double worst = 0.0;
  for (int a = 0; a < static_cast<int>(s.planes.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(s.planes.size()); ++b) {
      const Plane& A = s.planes[static_cast<std::size_t>(a)];
      const Plane& B = s.planes[static_cast<std::size_t>(b)];
      if (A.normal.cross(B.normal).norm() < 1e-9) continue;
      auto xa = crossings_of_plane_curves(s, a, B);
      auto xb = crossings_of_plane_curves(s, b, A);
      bool has_a = false, has_b = false;
      for (const auto& c : s.curves) has_a = has_a || c.plane == a, has_b = has_b || c.plane == b;
      if (!has_a || !has_b) continue;
      if (xa.size() != xb.size()) return std::numeric_limits<double>::infinity();
      const Vec3 dir = A.normal.cross(B.normal).normalized();
      auto by = [&](const Vec3& p, const Vec3& q) { return dir.dot(p) < dir.dot(q); };
      std::sort(xa.begin(), xa.end(), by);
      std::sort(xb.begin(), xb.end(), by);
      for (std::size_t i = 0; i < xa.size(); ++i) worst = std::max(worst, (xa[i] - xb[i]).norm());
    }
  return worst;
}

double diag(const SectionSet& s) { return bounding_box(s.all_points()).diagonal(); }

void expect_on_planes(const SectionSet& s, double tol) {
  for (std::size_t c = 0; c < s.curves.size(); ++c)
    for (const auto& p : s.curves[c].points)
      ASSERT_LE(std::abs(s.planes[static_cast<std::size_t>(s.curves[c].plane)].signed_distance(p)), tol) << "curve " << c;
}

const Vec3 X = Vec3::UnitX(), Y = Vec3::UnitY(), Z = Vec3::UnitZ(), O = Vec3::Zero();

SectionSet two_ellipses(double rb_a, double ra_b) {
  SectionSet s;
  s.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  s.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, rb_a, 80, 0.013));
  s.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, ra_b, 0.8, 70, 0.021));
  return s;
}

}  // namespace

TEST(StrokesSewing, TwoMismatchedEllipsesShareExactCrossings) {
  const SectionSet in = two_ellipses(0.6, 0.5);
  ASSERT_GT(max_crossing_gap(in), 0.09);
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  // Exactly on their (axis-aligned) planes.
  for (const auto& p : out->curves[0].points) EXPECT_EQ(p.z(), 0.0);
  for (const auto& p : out->curves[1].points) EXPECT_EQ(p.x(), 0.0);
  // The shared points are the midpoints, (0, +-0.55, 0) up to the polygons' chord error.
  const auto req = required_crossings(*out, out->planes[1]);
  ASSERT_EQ(req.size(), 2u);
  for (const auto& p : req) EXPECT_NEAR(std::abs(p.y()), 0.55, 2e-3);
  ASSERT_EQ(rep.crossings.size(), 2u);
  // Each crossing moved half the mismatch; no point moved much more; far points hardly.
  ASSERT_EQ(rep.handles.size(), 4u);
  EXPECT_NEAR(rep.max_moved, 0.05, 2e-3);
  EXPECT_LE(rep.max_displacement, 1.05 * rep.max_moved);
  // The top of the ellipse stays its top: no dent next to the handle (the handle is the
  // crossing with x = 0, where the input was highest).
  double top = -1, at_handle = 0;
  for (const auto& p : out->curves[0].points) {
    if (p.y() > 0 && std::abs(p.x()) < 0.5) top = std::max(top, p.y());
    if (p.x() == 0.0 && p.y() > 0) at_handle = p.y();
  }
  EXPECT_LT(top - at_handle, 0.02 * rep.max_moved);
  double far_move = 0;
  for (std::size_t i = 0; i < in.curves[0].points.size(); ++i) {
    const Vec3 p = in.curves[0].points[i];
    if (std::abs(p.x()) > 0.9) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& q : out->curves[0].points) best = std::min(best, (q - p).norm());
      far_move = std::max(far_move, best);
    }
  }
  EXPECT_LT(far_move, 0.5 * rep.max_moved);
  EXPECT_EQ(rep.iterations, 1);
}

TEST(StrokesSewing, ThreeMutuallyOrthogonalCurves) {
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}, Plane{Y, 0.0}};
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.7, 90, 0.01));
  in.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, 0.75, 0.5, 75, 0.02));
  in.curves.push_back(ellipse(2, O, X, Z, {0, 0}, 0.95, 0.55, 85, 0.03));
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  expect_on_planes(*out, 0.0);
  EXPECT_EQ(rep.crossings.size(), 6u);
  EXPECT_LE(rep.max_displacement, 2.0 * rep.max_moved);
}

TEST(StrokesSewing, ThreeCurvesNearThePlanesCommonPoint) {
  // Circles through (nearly) the origin on x = 0, y = 0 and z = 0: each pair of curves meets
  // near the common point of the three planes, where every curve has two handles close together.
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}, Plane{Y, 0.0}};
  const double r = std::sqrt(0.5);
  in.curves.push_back(ellipse(0, O, X, Y, {0.52, 0.49}, r, r, 90, 0.01));
  in.curves.push_back(ellipse(1, O, Y, Z, {0.48, 0.5}, r, r, 80, 0.02));
  in.curves.push_back(ellipse(2, O, X, Z, {0.5, 0.53}, r, r, 70, 0.03));
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  expect_on_planes(*out, 0.0);
  ASSERT_EQ(rep.crossings.size(), 6u);
  // The three pairs meet at the planes' common point; the far crossings stay apart.
  int at_origin = 0;
  for (const auto& p : rep.crossings) at_origin += p.norm() == 0.0;
  EXPECT_EQ(at_origin, 3);
  for (const auto& c : out->curves) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& p : c.points) nearest = std::min(nearest, p.norm());
    EXPECT_EQ(nearest, 0.0);
  }
  EXPECT_LT(rep.max_displacement, 0.05);
}

TEST(StrokesSewing, CurvesWithFourCrossings) {
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  in.curves.push_back(sector(0, X, Y, 0.6, 1.0, -150, 150, 60));   // crosses the y axis 4 times
  in.curves.push_back(sector(1, Y, Z, 0.62, 0.98, -60, 240, 60));  // crosses z = 0 4 times
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  expect_on_planes(*out, 0.0);
  // The shared points are the midpoints of the input crossings paired in order along y.
  auto by_y = [](const Vec3& a, const Vec3& b) { return a.y() < b.y(); };
  auto before_a = crossings_of_plane_curves(in, 0, in.planes[1]);
  auto before_b = crossings_of_plane_curves(in, 1, in.planes[0]);
  auto after = crossings_of_plane_curves(*out, 0, in.planes[1]);
  ASSERT_EQ(before_a.size(), 4u);
  ASSERT_EQ(before_b.size(), 4u);
  ASSERT_EQ(after.size(), 4u);
  std::sort(before_a.begin(), before_a.end(), by_y);
  std::sort(before_b.begin(), before_b.end(), by_y);
  std::sort(after.begin(), after.end(), by_y);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_LE((after[i] - 0.5 * (before_a[i] + before_b[i])).norm(), 1e-12);
    EXPECT_NEAR(std::abs(after[i].y()), i == 0 || i == 3 ? 0.99 : 0.61, 2e-3);  // chord error
  }
}

TEST(StrokesSewing, CountMismatchIsRefusedNamingBothCurves) {
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.6, 60, 0.01));
  in.curves.push_back(ellipse(1, O, Y, Z, {0, 2.0}, 0.5, 0.5, 60, 0.01));  // above z = 0
  auto r = sew_curves(in);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("curve 0 crosses the line shared with curve 1's plane at 2 points, curve 1 at 0 points"),
            std::string::npos)
      << r.message();
  SectionSet four;
  four.planes = in.planes;
  four.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, 0.6, 0.5, 60, 0.01));
  four.curves.push_back(sector(0, X, Y, 0.6, 1.0, -150, 150, 60));
  auto f = sew_curves(four);
  ASSERT_FALSE(f);
  EXPECT_NE(f.message().find("curve 1 crosses the line shared with curve 0's plane at 4 points, curve 0 at 2 points"),
            std::string::npos)
      << f.message();
}

TEST(StrokesSewing, ConsistentCurvesAreUnchanged) {
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  // Both curves have a point exactly at (0, +-0.6, 0).
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.6, 80, 0.0));
  in.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, 0.6, 0.8, 64, 0.0));
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  ASSERT_EQ(out->curves.size(), in.curves.size());
  for (std::size_t c = 0; c < in.curves.size(); ++c) {
    ASSERT_EQ(out->curves[c].points.size(), in.curves[c].points.size());
    for (std::size_t i = 0; i < in.curves[c].points.size(); ++i)
      EXPECT_LE((out->curves[c].points[i] - in.curves[c].points[i]).norm(), 1e-12);
  }
  EXPECT_TRUE(rep.handles.empty());
  EXPECT_EQ(rep.iterations, 0);
  // Sewing an already sewn set changes nothing either.
  auto once = sew_curves(two_ellipses(0.6, 0.5));
  ASSERT_TRUE(once);
  auto twice = sew_curves(*once);
  ASSERT_TRUE(twice);
  for (std::size_t c = 0; c < once->curves.size(); ++c) {
    ASSERT_EQ(once->curves[c].points.size(), twice->curves[c].points.size());
    for (std::size_t i = 0; i < once->curves[c].points.size(); ++i)
      EXPECT_LE((once->curves[c].points[i] - twice->curves[c].points[i]).norm(), 1e-12);
  }
}

TEST(StrokesSewing, CommutesWithTranslationAndScale) {
  const SectionSet in = two_ellipses(0.6, 0.5);
  auto base = sew_curves(in);
  ASSERT_TRUE(base);
  for (const auto& [shift, scale] : {std::pair{Vec3(0.3, -1.2, 2.5), 1.0}, std::pair{Vec3(100, 7, -3), 1e3},
                                     std::pair{Vec3(0, 0, 0), 1e-3}}) {
    SectionSet moved = in;
    for (auto& pl : moved.planes) pl.offset = scale * pl.offset + pl.normal.dot(shift);
    for (auto& c : moved.curves)
      for (auto& p : c.points) p = scale * p + shift;
    auto out = sew_curves(moved);
    ASSERT_TRUE(out) << out.message();
    for (std::size_t c = 0; c < base->curves.size(); ++c) {
      ASSERT_EQ(out->curves[c].points.size(), base->curves[c].points.size());
      for (std::size_t i = 0; i < base->curves[c].points.size(); ++i)
        EXPECT_LE((out->curves[c].points[i] - (scale * base->curves[c].points[i] + shift)).norm(),
                  1e-9 * scale + 1e-12 * shift.norm());
    }
  }
}

TEST(StrokesSewing, CommutesWithRotation) {
  // Rotated planes have other 2D frames (Plane::basis), but the result must be the same shape.
  const SectionSet in = two_ellipses(0.6, 0.5);
  auto base = sew_curves(in);
  ASSERT_TRUE(base);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-1.9, Vec3(0.3, -1, 0.2).normalized())).toRotationMatrix();
  SectionSet rotated = in;
  for (auto& pl : rotated.planes) pl.normal = R * pl.normal;
  for (auto& c : rotated.curves)
    for (auto& p : c.points) p = R * p;
  auto out = sew_curves(rotated);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  for (std::size_t c = 0; c < base->curves.size(); ++c) {
    ASSERT_EQ(out->curves[c].points.size(), base->curves[c].points.size());
    for (std::size_t i = 0; i < base->curves[c].points.size(); ++i)
      EXPECT_LE((out->curves[c].points[i] - R * base->curves[c].points[i]).norm(), 1e-9);
  }
}

TEST(StrokesSewing, ReversedAndReorderedCurvesGiveTheSameResult) {
  const SectionSet in = two_ellipses(0.62, 0.5);
  auto base = sew_curves(in);
  ASSERT_TRUE(base);
  SectionSet other = in;
  std::swap(other.curves[0], other.curves[1]);
  std::reverse(other.curves[0].points.begin(), other.curves[0].points.end());
  auto out = sew_curves(other);
  ASSERT_TRUE(out) << out.message();
  // Same point sets (reversed order for the reversed curve).
  auto same = [](std::vector<Vec3> a, std::vector<Vec3> b) {
    auto lex = [](const Vec3& p, const Vec3& q) {
      return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    };
    std::sort(a.begin(), a.end(), lex);
    std::sort(b.begin(), b.end(), lex);
    double worst = a.size() == b.size() ? 0.0 : 1.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
    return worst;
  };
  EXPECT_LT(same(base->curves[0].points, out->curves[1].points), 1e-9);
  EXPECT_LT(same(base->curves[1].points, out->curves[0].points), 1e-9);
}

TEST(StrokesSewing, NonOrthogonalPlanes) {
  SectionSet in;
  const Vec3 n2 = Vec3(std::cos(M_PI / 6), 0.0, std::sin(M_PI / 6));
  in.planes = {Plane{Z, 0.0}, Plane{n2, 0.0}};
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.6, 80, 0.013));
  in.curves.push_back(ellipse(1, O, Y, n2.cross(Y).normalized(), {0.02, 0}, 0.5, 0.8, 70, 0.021));
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  expect_on_planes(*out, 1e-14 * diag(*out));
}

TEST(StrokesSewing, NearTangentCrossingsArePushedOffThePlane) {
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.6, 80, 0.013));
  in.curves.push_back(ellipse(0, O, X, Y, {0.199, 1.5}, 0.2, 0.2, 40, 0.0));  // dips 0.001 past x = 0
  in.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, 0.62, 0.8, 70, 0.021));
  SectionSet only_dip;
  only_dip.planes = in.planes;
  only_dip.curves = {in.curves[1]};
  ASSERT_EQ(required_crossings(only_dip, in.planes[1]).size(), 2u);
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_EQ(rep.tangents_removed, 1);
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  only_dip.curves = {out->curves[1]};
  EXPECT_TRUE(required_crossings(only_dip, in.planes[1]).empty());
  for (std::size_t i = 0; i < in.curves[1].points.size(); ++i)
    EXPECT_LE((out->curves[1].points[i] - in.curves[1].points[i]).norm(), 0.003);
  // With a zero tolerance the same input is refused.
  SewingParams strict;
  strict.tangent_tolerance = 0.0;
  EXPECT_FALSE(sew_curves(in, strict));
}

TEST(StrokesSewing, TwentyCurveOrthogonalGrid) {
  // Slices of an ellipsoid on 10 planes z = const and 10 planes x = const, each slice scaled by
  // a random factor so that no two agree.
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> noise(0.96, 1.04);
  const double a = 1.0, b = 0.8, c = 0.6;
  SectionSet in;
  for (int i = 0; i < 10; ++i) {
    const double z = c * (-0.6 + 1.2 * i / 9.0);
    in.planes.push_back(Plane{Z, z});
    const double f = std::sqrt(1 - z * z / (c * c));
    in.curves.push_back(ellipse(i, z * Z, X, Y, {0, 0}, a * f * noise(rng), b * f * noise(rng), 64, 0.01 * i));
  }
  for (int i = 0; i < 10; ++i) {
    const double x = a * (-0.6 + 1.2 * i / 9.0);
    in.planes.push_back(Plane{X, x});
    const double f = std::sqrt(1 - x * x / (a * a));
    in.curves.push_back(ellipse(10 + i, x * X, Y, Z, {0, 0}, b * f * noise(rng), c * f * noise(rng), 64, 0.013 * i));
  }
  SewingReport rep;
  auto out = sew_curves(in, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out));
  expect_on_planes(*out, 0.0);
  EXPECT_EQ(rep.crossings.size(), 200u);
}

TEST(StrokesSewing, RefusesWhenSewingWouldMakeCurvesCross) {
  // Two nested curves on z = 0 close to each other; the outer one must move inwards by 0.1 to
  // meet the curve on x = 0, which pushes it across the inner one.
  SectionSet in;
  in.planes = {Plane{Z, 0.0}, Plane{X, 0.0}};
  in.curves.push_back(ellipse(0, O, X, Y, {0, 0}, 1.0, 0.6, 80, 0.013));
  in.curves.push_back(ellipse(0, O, X, Y, {0.13, 0.53}, 0.04, 0.04, 24, 0.01));  // under the top
  in.curves.push_back(ellipse(1, O, Y, Z, {0, 0}, 0.4, 0.8, 70, 0.021));
  auto r = sew_curves(in);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("sewing would make curves 0 and 1 cross"), std::string::npos) << r.message();
  // A smaller inner curve is passed over entirely: nesting would change.
  in.curves[1] = ellipse(0, O, X, Y, {0.13, 0.54}, 0.025, 0.025, 24, 0.01);
  auto n = sew_curves(in);
  ASSERT_FALSE(n);
  EXPECT_NE(n.message().find("would change whether curves 0 and 1 are nested"), std::string::npos) << n.message();
  // Far enough inside, sewing is fine.
  in.curves[1] = ellipse(0, O, X, Y, {0.3, 0.0}, 0.1, 0.1, 24, 0.01);
  EXPECT_TRUE(sew_curves(in));
}

TEST(StrokesSewing, BadInputIsRefused) {
  SectionSet s = two_ellipses(0.6, 0.5);
  s.curves[1].plane = 5;
  auto r = sew_curves(s);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("curve 1 refers to plane 5"), std::string::npos) << r.message();
  s = two_ellipses(0.6, 0.5);
  s.curves[0].points[3].x() = std::nan("");
  auto n = sew_curves(s);
  ASSERT_FALSE(n);
  EXPECT_NE(n.message().find("curve 0 point 3 is not finite"), std::string::npos) << n.message();
}

// Property test: random ellipses on random axis planes are either sewn (rule 4 holds, points on
// their planes) or refused with a message naming curves; nothing crashes.
TEST(StrokesSewing, RandomSetsAreSewnOrRefusedWithAMessage) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int sewn = 0, refused = 0;
  for (int trial = 0; trial < 60; ++trial) {
    SectionSet s;
    const int planes = 2 + trial % 3;
    for (int p = 0; p < planes; ++p) s.planes.push_back(Plane{p % 3 == 0 ? Z : (p % 3 == 1 ? X : Y), 0.3 * u(rng)});
    for (int c = 0; c < planes + trial % 2; ++c) {
      const int p = c % planes;
      const Plane& pl = s.planes[static_cast<std::size_t>(p)];
      Vec3 e1, e2;
      pl.basis(e1, e2);
      s.curves.push_back(ellipse(p, pl.offset * pl.normal, e1, e2, {0.2 * u(rng), 0.2 * u(rng)}, 0.8 + 0.2 * u(rng),
                                 0.6 + 0.2 * u(rng), 30 + trial % 40, u(rng)));
    }
    auto out = sew_curves(s);
    if (!out) {
      ++refused;
      EXPECT_NE(out.message().find("curve"), std::string::npos) << out.message();
      if (std::getenv("STROKES_VERBOSE")) std::printf("trial %d: %s\n", trial, out.message().c_str());
      continue;
    }
    ++sewn;
    EXPECT_LE(max_crossing_gap(*out), 1e-9 * diag(*out)) << "trial " << trial;
    expect_on_planes(*out, 0.0);
  }
  EXPECT_GT(sewn, 0);
  std::printf("random sets: %d sewn, %d refused\n", sewn, refused);
}
