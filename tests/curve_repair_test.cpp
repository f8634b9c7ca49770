// Repair of curves that touch or cross themselves (modeling/curve_repair.h).
#include "modeling/curve_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "modeling/polyline_crossing.h"
#include "modeling/section_validate.h"

namespace ps {
namespace {

double area(const std::vector<Vec2>& p) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    s += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * s;
}

bool inside(const std::vector<Vec2>& poly, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

// Every loop simple, no two touching: what validation will ask of them.
void expect_simple_and_apart(const std::vector<std::vector<Vec2>>& loops) {
  for (const auto& l : loops) EXPECT_FALSE(first_self_crossing(l).has_value());
  for (std::size_t i = 0; i < loops.size(); ++i)
    for (std::size_t j = i + 1; j < loops.size(); ++j) EXPECT_FALSE(first_crossing_between(loops[i], loops[j]).has_value());
}

std::vector<double> sorted_areas(const std::vector<std::vector<Vec2>>& loops) {
  std::vector<double> a;
  for (const auto& l : loops) a.push_back(std::abs(area(l)));
  std::sort(a.begin(), a.end());
  return a;
}

// A 10 x 10 square whose boundary runs, at (5, 0), once around a diamond hole of area 6.
std::vector<Vec2> pinched_hole() {
  return {{0, 0}, {5, 0}, {4, 3}, {5, 6}, {6, 3}, {5, 0}, {10, 0}, {10, 10}, {0, 10}};
}

TEST(CurveRepair, SimpleCurveComesBackUnchanged) {
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto r = repair_closed_curve(square);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0], square);
}

TEST(CurveRepair, PinchedHoleBecomesAHoleInside) {
  auto r = repair_closed_curve(pinched_hole());
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 2u);
  expect_simple_and_apart(*r);
  // The hole moved off the boundary into itself, by at most 1e-4 of the diagonal.
  EXPECT_NEAR(std::abs(area((*r)[0])), 100.0 - 0.0, 1e-12);  // the outer loop keeps the square
  EXPECT_LT(std::abs(area((*r)[1])), 6.0);
  EXPECT_GT(std::abs(area((*r)[1])), 6.0 - 1e-2);
  for (const Vec2& q : (*r)[1]) EXPECT_TRUE(inside((*r)[0], q)) << q.transpose();
}

TEST(CurveRepair, FigureEightBecomesTwoLobes) {
  // A bow tie: the edges (0,0)-(2,2) and (2,0)-(0,2) cross at (1, 1).
  auto r = repair_closed_curve({{0, 0}, {2, 2}, {2, 0}, {0, 2}});
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 2u);
  expect_simple_and_apart(*r);
  const auto a = sorted_areas(*r);
  EXPECT_NEAR(a[0], 1.0, 1e-3);
  EXPECT_NEAR(a[1], 1.0, 1e-12);
  // Side by side, not nested.
  for (const Vec2& q : (*r)[1]) EXPECT_FALSE(inside((*r)[0], q));
}

TEST(CurveRepair, SpikeIsRemoved) {
  auto r = repair_closed_curve({{0, 0}, {10, 0}, {10, 5}, {15, 5}, {10, 5}, {10, 10}, {0, 10}});
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 1u);
  EXPECT_DOUBLE_EQ(area((*r)[0]), 100.0);
  for (const Vec2& q : (*r)[0]) EXPECT_LE(q.x(), 10.0);
}

TEST(CurveRepair, TinyTwistIsDropped) {
  // A circle whose boundary makes a loop of about 1e-8 of its area between two samples.
  std::vector<Vec2> c;
  for (int i = 0; i < 64; ++i) {
    const double t = 2.0 * M_PI * i / 64.0;
    c.emplace_back(std::cos(t), std::sin(t));
    if (i == 10) {
      const Vec2 p = c.back(), q(std::cos(2.0 * M_PI * 11 / 64.0), std::sin(2.0 * M_PI * 11 / 64.0));
      const Vec2 d = (q - p) * 0.5, n(-d.y(), d.x());
      c.push_back(p + 0.6 * d + 1e-4 * n);
      c.push_back(p + 0.5 * d + 2e-4 * n);
      c.push_back(p + 0.4 * d + 1e-4 * n);
    }
  }
  ASSERT_TRUE(first_self_crossing(c).has_value());
  auto r = repair_closed_curve(c);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 1u);
  expect_simple_and_apart(*r);
  EXPECT_NEAR(std::abs(area((*r)[0])), std::abs(area(c)), 1e-6);
}

TEST(CurveRepair, LoopWoundTwiceKeepsOnlyTheOuterBoundary) {
  // Around a circle of radius 10, then around one of radius 9, joined by two crossing segments.
  std::vector<Vec2> c;
  for (double radius : {10.0, 9.0})
    for (int i = 0; i < 48; ++i) {
      const double t = 2.0 * M_PI * i / 48.0;
      c.emplace_back(radius * std::cos(t), radius * std::sin(t));
    }
  auto r = repair_closed_curve(c);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 1u);  // the inner circle has the region on both sides
  expect_simple_and_apart(*r);
  EXPECT_GT(std::abs(area((*r)[0])), 300.0);
}

TEST(CurveRepair, SameResultForReversedAndRotatedInput) {
  const auto base = repair_closed_curve(pinched_hole());
  ASSERT_TRUE(base);
  auto reversed = pinched_hole();
  std::reverse(reversed.begin(), reversed.end());
  auto rotated = pinched_hole();
  std::rotate(rotated.begin(), rotated.begin() + 3, rotated.end());
  for (const auto& input : {reversed, rotated}) {
    auto r = repair_closed_curve(input);
    ASSERT_TRUE(r) << r.message();
    expect_simple_and_apart(*r);
    const auto a = sorted_areas(*r), b = sorted_areas(*base);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-3);
  }
}

TEST(CurveRepair, LongCurveWithOnePinchIsSplitWithoutComparingEveryPair) {
  // 200k points around a circle, through the centre's neighbourhood once: a pinched hole. The
  // contact search sweeps boxes, so this takes milliseconds (every pair would be 2e10 tests).
  const int n = 200000;
  std::vector<Vec2> c;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    c.emplace_back(std::cos(t), std::sin(t));
    if (i == 0) {  // out to a small triangle inside and back to (1, 0)
      c.emplace_back(0.5, -0.1);
      c.emplace_back(0.5, 0.1);
      c.emplace_back(1.0, 0.0);
    }
  }
  auto r = repair_closed_curve(c);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->size(), 2u);
  expect_simple_and_apart(*r);
  EXPECT_NEAR(std::abs(area((*r)[1])), 0.5 * 0.2 * 0.5, 1e-3);
}

TEST(CurveRepair, NonFiniteCurveIsAnError) {
  auto r = repair_closed_curve({{0, 0}, {1, 0}, {std::nan(""), 1}});
  EXPECT_FALSE(r);
}

// One plane n . x = offset holding the loops, lifted through the plane's 2D frame.
SectionSet plane_with(const std::vector<std::vector<Vec2>>& loops, const Vec3& normal = Vec3::UnitZ(),
                      double offset = 0.5) {
  SectionSet s;
  Plane p;
  p.normal = normal;
  p.offset = offset;
  s.planes.push_back(p);
  const PlaneFrame frame = plane_frame(p);
  for (const auto& l : loops) {
    CrossSection c{0, {}};
    for (const Vec2& q : l) c.points.push_back(frame.to_3d(q));
    s.curves.push_back(c);
  }
  return s;
}

TEST(CurveRepair, SectionSetKeepsInputPointsAndValidates) {
  // Plane x = 2 (oblique frames round; an axis frame copies coordinates exactly).
  SectionSet s = plane_with({pinched_hole(), {{20, 0}, {25, 0}, {25, 5}, {20, 5}}}, Vec3::UnitX(), 2.0);
  const CrossSection pinched = s.curves[0], other = s.curves[1];
  ASSERT_FALSE(validate_sections(s));  // refused as it is (rule 3)

  std::vector<std::string> warnings;
  EXPECT_EQ(repair_section_curves(s, &warnings), 1);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("curve 0"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("added as curve 2"), std::string::npos) << warnings[0];
  ASSERT_EQ(s.curves.size(), 3u);
  EXPECT_EQ(s.curves[1].points, other.points);  // untouched
  // Input points are kept bit for bit; the only new point is the moved contact vertex.
  int copied = 0;
  for (int c : {0, 2})
    for (const Vec3& q : s.curves[static_cast<std::size_t>(c)].points)
      copied += std::find(pinched.points.begin(), pinched.points.end(), q) != pinched.points.end();
  EXPECT_EQ(copied, 8);  // outer 5 + hole 3: (5, 0) is in both loops and moved in the hole
  auto v = validate_sections(s);
  ASSERT_TRUE(v) << v.message();
  EXPECT_EQ(v->depth[0], 0);
  EXPECT_EQ(v->depth[2], 1);  // the hole
  EXPECT_EQ(v->depth[1], 0);
}

double total_abs_area(const SectionSet& s, const std::vector<int>& depth) {
  // Area of the section region: outer curves add, holes (odd depth) subtract.
  const PlaneFrame frame = plane_frame(s.planes[0]);
  double a = 0.0;
  for (std::size_t c = 0; c < s.curves.size(); ++c) {
    std::vector<Vec2> l;
    for (const Vec3& p : s.curves[c].points) l.push_back(frame.to_2d(p));
    a += (depth[c] % 2 == 0 ? 1.0 : -1.0) * std::abs(area(l));
  }
  return a;
}

TEST(CurveRepair, OverlappingCurvesOfAPlaneBecomeTheirUnion) {
  // Two squares overlapping in a 1 x 2 strip, and a third curve away from them.
  SectionSet s = plane_with({{{0, 0}, {3, 0}, {3, 2}, {0, 2}},
                             {{2, 0.5}, {5, 0.5}, {5, 2.5}, {2, 2.5}},
                             {{10, 0}, {11, 0}, {11, 1}, {10, 1}}});
  ASSERT_FALSE(validate_sections(s));
  std::vector<std::string> warnings;
  EXPECT_EQ(repair_section_curves(s, &warnings), 1);
  ASSERT_EQ(warnings.size(), 2u);  // the merge, and the renumbering
  EXPECT_NE(warnings[0].find("curves 0 and 1 on plane 0"), std::string::npos) << warnings[0];
  ASSERT_EQ(s.curves.size(), 2u);
  auto v = validate_sections(s);
  ASSERT_TRUE(v) << v.message();
  EXPECT_NEAR(total_abs_area(s, v->depth), 6.0 + 6.0 - 1.5 + 1.0, 1e-12);
}

TEST(CurveRepair, HoleCrossingItsBoundaryIsTakenAway) {
  // A hole (inside the 10 x 10 square by most of its vertices) that pokes out through x = 10.
  SectionSet s = plane_with({{{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                             {{4, 4}, {8, 4}, {9, 5}, {11, 5}, {11, 6}, {8, 6}, {4, 6}}});
  ASSERT_FALSE(validate_sections(s));
  std::vector<std::string> warnings;
  EXPECT_EQ(repair_section_curves(s, &warnings), 1);
  auto v = validate_sections(s);
  ASSERT_TRUE(v) << v.message();
  // The square minus the part of the hole inside it: a notch, one curve, no hole.
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_NEAR(total_abs_area(s, v->depth), 100.0 - (8.0 + 0.5 * 1.0 * 1.0 + 1.0 + 1.0), 1e-9);
}

TEST(CurveRepair, CurvesTouchingAtACornerArePulledApart) {
  SectionSet s = plane_with({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  ASSERT_FALSE(validate_sections(s));
  std::vector<std::string> warnings;
  EXPECT_EQ(repair_section_curves(s, &warnings), 1);
  ASSERT_EQ(s.curves.size(), 2u);
  auto v = validate_sections(s);
  ASSERT_TRUE(v) << v.message();
  EXPECT_NEAR(total_abs_area(s, v->depth), 2.0, 1e-3);  // the moved corner costs delta / sqrt(2)
}

}  // namespace
}  // namespace ps
