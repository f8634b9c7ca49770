// Exact orientation, segment intersection and self-crossing of closed polylines (rule 3).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "modeling/polyline_crossing.h"

using namespace ps;

namespace {
std::vector<Vec2> circle(Vec2 c, double r, int n, double start = 0.1) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = start + 2 * M_PI * i / n;
    p.emplace_back(c.x() + r * std::cos(t), c.y() + r * std::sin(t));
  }
  return p;
}
std::vector<Vec2> figure_eight(int n, double start) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = start + 2 * M_PI * i / n;
    p.emplace_back(std::sin(t), 0.6 * std::sin(2 * t));
  }
  return p;
}
std::vector<Vec2> transformed(const std::vector<Vec2>& pts, double angle, double scale, Vec2 shift) {
  const Eigen::Rotation2Dd rot(angle);
  std::vector<Vec2> out;
  for (const auto& p : pts) out.push_back(scale * (rot * p) + shift);
  return out;
}
}  // namespace

TEST(StrokesOrient, ExactNearCollinearSigns) {
  // p = (0.5 + i ulp, 0.5 + j ulp) against the diagonal through (12, 12) and (24, 24): the
  // exact sign is sign(j - i); naive evaluation gets many of these wrong.
  const Vec2 b(12, 12), c(24, 24);
  double x = 0.5;
  for (int i = 0; i < 48; ++i, x = std::nextafter(x, 1.0)) {
    double y = 0.5;
    for (int j = 0; j < 48; ++j, y = std::nextafter(y, 1.0)) {
      const int expect = (j > i) - (j < i);
      ASSERT_EQ(orient2d(Vec2(x, y), b, c), expect) << i << " " << j;
      ASSERT_EQ(orient2d(b, c, Vec2(x, y)), expect);   // cyclic permutation
      ASSERT_EQ(orient2d(c, b, Vec2(x, y)), -expect);  // swap flips the sign
    }
  }
  EXPECT_EQ(orient2d(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)), 1);
}

TEST(StrokesOrient, SegmentIntersectionCases) {
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));     // proper crossing
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {2, 0}, {3, 5}));     // shared endpoint
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {1, 5}));     // T junction
  EXPECT_TRUE(segments_intersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));     // collinear overlap
  EXPECT_FALSE(segments_intersect({0, 0}, {1, 0}, {2, 0}, {3, 0}));    // collinear, apart
  EXPECT_FALSE(segments_intersect({0, 0}, {2, 0}, {0, 1}, {2, 1}));    // parallel
  EXPECT_FALSE(segments_intersect({0, 0}, {2, 2}, {3, 0}, {2.1, 1.9}));  // near miss
}

TEST(StrokesSelfCrossing, FigureEightDetectedSimplePolygonsAccepted) {
  for (double start : {0.05, 0.4, 1.3, 2.9}) {
    const auto x = first_self_crossing(figure_eight(200, start));
    ASSERT_TRUE(x) << start;
    EXPECT_LT(x->norm(), 1e-2) << x->transpose();
  }
  EXPECT_FALSE(first_self_crossing(circle({0, 0}, 1, 100)));
  EXPECT_FALSE(first_self_crossing({{0, 0}, {1, 0}, {0, 1}}));
  // A concave star and a random star-shaped polygon (simple by construction).
  std::vector<Vec2> star;
  for (int i = 0; i < 20; ++i) {
    const double r = i % 2 ? 0.3 : 1.0;
    star.emplace_back(r * std::cos(M_PI * i / 10), r * std::sin(M_PI * i / 10));
  }
  EXPECT_FALSE(first_self_crossing(star));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> rad(0.2, 1.0);
  std::vector<Vec2> blob;
  for (int i = 0; i < 2000; ++i) {
    const double r = rad(rng), t = 2 * M_PI * i / 2000;
    blob.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  EXPECT_FALSE(first_self_crossing(blob));
  blob[1000] = Vec2(0.0, 1.1);  // a spike past the far side: now it crosses
  blob[1001] = Vec2(-0.05, -1.5);
  EXPECT_TRUE(first_self_crossing(blob));
}

TEST(StrokesSelfCrossing, TouchesFoldsAndDuplicatesCount) {
  // A vertex touching another edge.
  EXPECT_TRUE(first_self_crossing({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));
  // A spike folding back on itself.
  const auto fold = first_self_crossing({{0, 0}, {2, 0}, {4, 0}, {3, 0}, {3, 3}});
  ASSERT_TRUE(fold);
  // Consecutive duplicates are ignored.
  EXPECT_FALSE(first_self_crossing({{0, 0}, {0, 0}, {1, 0}, {1, 1}, {1, 1}, {0, 1}, {0, 0}}));
  // Two distinct points: the two segments coincide.
  EXPECT_TRUE(first_self_crossing({{0, 0}, {1, 0}}));
  EXPECT_FALSE(first_self_crossing({{0, 0}}));
}

TEST(StrokesSelfCrossing, ReportsTheFirstCrossingAlongTheDrawing) {
  // An open zig-zag crossing its first segment twice: the first reached is reported.
  const std::vector<Vec2> zig{{0, 0}, {10, 0}, {10, 2}, {7, 2}, {7, -2}, {3, -2}, {3, 2}};
  const auto x = first_self_crossing_open(zig);
  ASSERT_TRUE(x);
  EXPECT_NEAR((*x - Vec2(7, 0)).norm(), 0, 1e-12);
}

TEST(StrokesSelfCrossing, CommutesWithSimilarityTransforms) {
  const auto eight = figure_eight(150, 0.7);
  const auto base = first_self_crossing(eight);
  ASSERT_TRUE(base);
  for (const auto& [a, s] : {std::pair{0.3, 1.0}, std::pair{2.0, 1e-6}, std::pair{-1.0, 1e6}}) {
    const Vec2 shift(1e3 * s, -7 * s);
    const auto x = first_self_crossing(transformed(eight, a, s, shift));
    ASSERT_TRUE(x);
    const Vec2 expect = s * (Eigen::Rotation2Dd(a) * *base) + shift;
    EXPECT_NEAR((*x - expect).norm(), 0, 1e-9 * s);
  }
}

TEST(StrokesSelfCrossing, BetweenTwoCurves) {
  EXPECT_TRUE(first_crossing_between(circle({0, 0}, 1, 64), circle({1.5, 0}, 1, 64)));
  EXPECT_FALSE(first_crossing_between(circle({0, 0}, 1, 64), circle({3, 0}, 1, 64)));
  EXPECT_FALSE(first_crossing_between(circle({0, 0}, 1, 64), circle({0.1, 0}, 0.5, 64)));  // nested
}
