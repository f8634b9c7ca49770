// Stroke preprocessing (thesis 3.3.1) and lifting onto planes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "modeling/polyline_crossing.h"
#include "modeling/stroke_preprocess.h"

using namespace ps;

namespace {

// A hand-like circle stroke: `turns` of a circle sampled every ~2 px with a little jitter.
std::vector<Vec2> circle_stroke(Vec2 c, double r, double turns, unsigned seed = 7, double start = 0.3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  const int n = static_cast<int>(std::ceil(2.0 * M_PI * r * turns / 2.0));
  std::vector<Vec2> pts;
  for (int i = 0; i <= n; ++i) {
    const double t = start + 2.0 * M_PI * turns * i / n;
    pts.emplace_back(c.x() + r * std::cos(t) + jitter(rng), c.y() + r * std::sin(t) + jitter(rng));
  }
  return pts;
}

std::vector<Vec2> transform(const std::vector<Vec2>& pts, double angle, double scale, Vec2 shift) {
  const Eigen::Rotation2Dd rot(angle);
  std::vector<Vec2> out;
  for (const auto& p : pts) out.push_back(scale * (rot * p) + shift);
  return out;
}

// Largest distance from any point of a to the closed polyline b.
double distance_to_polyline(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double worst = 0.0;
  for (const auto& p : a) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Vec2 u = b[i], v = b[(i + 1) % b.size()];
      const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
      best = std::min(best, (p - (u + t * (v - u))).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

Camera ortho_camera() {
  Camera c;
  c.eye = Vec3(0.3, 0.2, 5.0);
  c.target = Vec3(0.3, 0.2, 0.0);  // looking down -Z
  c.orthographic = true;
  c.ortho_height = 4.0;
  return c;
}

}  // namespace

// === Filtering
TEST(StrokesFilter, DropsPointsCloserThanThresholdAndKeepsEnds) {
  std::vector<Vec2> line;
  for (int i = 0; i <= 100; ++i) line.emplace_back(i, 0.0);
  const auto f = filter_close_points(line, 15.0);
  ASSERT_EQ(f.size(), 8u);  // 0, 15, ..., 90, then the pen-up point 100
  EXPECT_EQ(f.front(), line.front());
  EXPECT_EQ(f.back(), line.back());
  for (std::size_t i = 1; i + 1 < f.size(); ++i) EXPECT_GE((f[i] - f[i - 1]).norm(), 15.0);
  EXPECT_GE((f.back() - f[f.size() - 2]).norm(), 7.5);
  // The pen-up point replaces the last kept one when it is very close to it.
  line.emplace_back(92.0, 0.0);
  const auto g = filter_close_points(std::vector<Vec2>{{0, 0}, {20, 0}, {40, 0}, {45, 0}}, 15.0);
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g.back(), Vec2(45, 0));
}

TEST(StrokesFilter, WorksIn3D) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= 10; ++i) pts.emplace_back(0.1 * i, 0.0, 0.1 * i);
  const auto f = filter_close_points(pts, 0.3);
  for (std::size_t i = 1; i + 1 < f.size(); ++i) EXPECT_GE((f[i] - f[i - 1]).norm(), 0.3);
  EXPECT_EQ(f.back(), pts.back());
}

// === Resampling
TEST(StrokesResample, OpenPolylineGetsCountAndEqualArcSpacing) {
  // Irregular samples on a straight line: resampled points are exactly equally spaced.
  const std::vector<Vec2> pts{{0, 0}, {1, 0}, {1.5, 0}, {7, 0}, {7.25, 0}, {10, 0}};
  const auto r = resample_polyline(pts, 21, false);
  ASSERT_EQ(r.size(), 21u);
  EXPECT_EQ(r.front(), pts.front());
  EXPECT_EQ(r.back(), pts.back());
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_NEAR((r[i] - r[i - 1]).norm(), 0.5, 1e-12);
}

TEST(StrokesResample, ClosedSquareIsSampledAroundTheWholeLoop) {
  const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const auto r = resample_polyline(sq, 16, true);
  ASSERT_EQ(r.size(), 16u);
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_NEAR((r[(i + 1) % r.size()] - r[i]).norm(), 0.25, 1e-12) << i;  // closing gap bridged
    const Vec2 p = r[i];
    const double to_boundary = std::min({std::abs(p.x()), std::abs(p.y()), std::abs(1 - p.x()), std::abs(1 - p.y())});
    EXPECT_LT(to_boundary, 1e-12);
  }
  EXPECT_NEAR(polyline_length(r, true), 4.0, 1e-12);
}

TEST(StrokesResample, ThreeDimensional) {
  const std::vector<Vec3> pts{{0, 0, 0}, {0, 0, 3}, {0, 4, 3}};
  const auto r = resample_polyline(pts, 8, false);
  ASSERT_EQ(r.size(), 8u);
  EXPECT_NEAR((r[1] - r[0]).norm(), 1.0, 1e-12);
  EXPECT_EQ(r.back(), pts.back());
}

// === Smoothing (Eq. 3.1)
TEST(StrokesSmooth, Equation31OnAKnownPolyline) {
  const std::vector<Vec2> p{{0, 0}, {1, 0}, {2, 3}, {3, 0}, {4, 0}};
  const auto s = smooth_polyline(p, false);
  EXPECT_EQ(s[0], p[0]);
  EXPECT_EQ(s[4], p[4]);
  EXPECT_NEAR((s[1] - Vec2(1.0, 0.5)).norm(), 0, 1e-15);
  EXPECT_NEAR((s[2] - Vec2(2.0, 2.0)).norm(), 0, 1e-15);
  EXPECT_NEAR((s[3] - Vec2(3.0, 0.5)).norm(), 0, 1e-15);
  const auto c = smooth_polyline(p, true);  // wraps: P'_0 = (P_4 + 4 P_0 + P_1) / 6
  EXPECT_NEAR((c[0] - Vec2(5.0 / 6.0, 0.0)).norm(), 0, 1e-15);
  EXPECT_NEAR((c[4] - Vec2(19.0 / 6.0, 0.0)).norm(), 0, 1e-15);
  // A closed pass keeps the centroid (the weights sum to one over the cycle).
  Vec2 before = Vec2::Zero(), after = Vec2::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) before += p[i], after += c[i];
  EXPECT_NEAR((before - after).norm(), 0, 1e-13);
  // Straight lines are fixed points of the filter.
  const std::vector<Vec2> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  const auto l = smooth_polyline(line, false, 3);
  for (std::size_t i = 0; i < line.size(); ++i) EXPECT_NEAR((l[i] - line[i]).norm(), 0, 1e-15);
}

// === Closed detection and exact closing
TEST(StrokesPreprocess, CircleIsClosedExactlyWithUniformSpacing) {
  auto raw = circle_stroke(Vec2(400, 300), 100, 0.97);  // stops short: a small gap
  auto r = preprocess_stroke(raw);
  ASSERT_TRUE(r) << r.message();
  EXPECT_TRUE(r->closed);
  const auto& p = r->points;
  EXPECT_EQ(static_cast<int>(p.size()), static_cast<int>(std::round(r->length / 10.0)));
  double mean = polyline_length(p, true) / static_cast<double>(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double seg = (p[(i + 1) % p.size()] - p[i]).norm();
    EXPECT_NEAR(seg, mean, 0.25 * mean) << "segment " << i;  // including the bridged gap
    EXPECT_NEAR((p[i] - Vec2(400, 300)).norm(), 100, 6.0);
  }
  EXPECT_FALSE(first_self_crossing(p));
}

TEST(StrokesPreprocess, OpenArcStaysOpenWithFixedEnds) {
  auto raw = circle_stroke(Vec2(400, 300), 100, 0.5);
  auto r = preprocess_stroke(raw);
  ASSERT_TRUE(r) << r.message();
  EXPECT_FALSE(r->closed);
  EXPECT_EQ(r->points.front(), raw.front());
  EXPECT_EQ(r->points.back(), raw.back());
  EXPECT_FALSE(is_closed_stroke(filter_close_points(raw, 15.0)));
}

TEST(StrokesPreprocess, OvershootingLoopIsCutAtTheCrossing) {
  auto raw = circle_stroke(Vec2(400, 300), 100, 1.12);
  auto r = preprocess_stroke(raw);
  ASSERT_TRUE(r) << r.message();
  EXPECT_TRUE(r->closed);
  EXPECT_FALSE(first_self_crossing(r->points));
  EXPECT_NEAR(r->length, 2 * M_PI * 100, 0.05 * 2 * M_PI * 100);
}

TEST(StrokesPreprocess, FixedCountOption) {
  StrokeParams params;
  params.fixed_count = 10;  // the thesis's N_pre (Figure 3.4)
  auto r = preprocess_stroke(circle_stroke(Vec2(0, 0), 80, 0.98), params);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->points.size(), 10u);
}

TEST(StrokesPreprocess, ForceOpenAndForceClosed) {
  StrokeParams open;
  open.force_open = true;
  auto a = preprocess_stroke(circle_stroke(Vec2(0, 0), 80, 0.98), open);
  ASSERT_TRUE(a);
  EXPECT_FALSE(a->closed);
  StrokeParams closed;
  closed.force_closed = true;
  auto b = preprocess_stroke(circle_stroke(Vec2(0, 0), 80, 0.6), closed);
  ASSERT_TRUE(b) << b.message();
  EXPECT_TRUE(b->closed);
}

// === Refusals
TEST(StrokesPreprocess, RefusesNonFiniteSamples) {
  auto raw = circle_stroke(Vec2(0, 0), 80, 0.9);
  raw[12].y() = std::numeric_limits<double>::quiet_NaN();
  auto r = preprocess_stroke(raw);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("sample 12 is not finite"), std::string::npos) << r.message();
  raw[12].y() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(preprocess_stroke(raw));
}

TEST(StrokesPreprocess, RefusesDegenerateStrokes) {
  EXPECT_NE(preprocess_stroke({}).message().find("empty"), std::string::npos);
  auto tap = preprocess_stroke({{10, 10}, {11, 10}, {11.5, 10.2}});
  ASSERT_FALSE(tap);
  EXPECT_NE(tap.message().find("too short"), std::string::npos) << tap.message();
  // Long enough in pixels but under 2% of a 1280 x 800 viewport.
  StrokeParams vp;
  vp.viewport_px = Vec2(1280, 800);
  std::vector<Vec2> short_line;
  for (int i = 0; i <= 25; ++i) short_line.emplace_back(100 + i, 100);
  auto s = preprocess_stroke(short_line, vp);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("too short"), std::string::npos) << s.message();
  // Long but with only two points left after filtering (samples far apart are kept, so use a
  // large threshold).
  StrokeParams coarse;
  coarse.min_spacing_px = 200;
  auto c = preprocess_stroke(short_line, coarse);
  ASSERT_FALSE(c);
  EXPECT_NE(c.message().find("only 2 points"), std::string::npos) << c.message();
  // A closed stroke that goes back and forth along a line encloses no area.
  StrokeParams closed;
  closed.force_closed = true;
  std::vector<Vec2> back_forth;
  for (int i = 0; i <= 100; ++i) back_forth.emplace_back(100 + 2 * i, 100);
  for (int i = 100; i >= 0; --i) back_forth.emplace_back(100 + 2 * i + 0.5, 100.3);
  auto z = preprocess_stroke(back_forth, closed);
  ASSERT_FALSE(z);
  EXPECT_NE(z.message().find("encloses no area"), std::string::npos) << z.message();
}

// === Metamorphic: similarity transforms and reversal
TEST(StrokesPreprocess, CommutesWithTranslationRotationAndScale) {
  const auto raw = circle_stroke(Vec2(300, 200), 90, 0.95, 11);
  StrokeParams params;
  const auto base = preprocess_stroke(raw, params);
  ASSERT_TRUE(base);
  for (const auto& [angle, scale] : {std::pair{0.0, 1.0}, std::pair{0.7, 1.0}, std::pair{-2.1, 2.5}, std::pair{1.3, 0.4}}) {
    const Vec2 shift(37.25, -81.5);
    StrokeParams sp = params;
    sp.min_spacing_px *= scale;
    sp.target_spacing_px *= scale;
    sp.min_length_px *= scale;
    const auto moved = preprocess_stroke(transform(raw, angle, scale, shift), sp);
    ASSERT_TRUE(moved) << moved.message();
    ASSERT_EQ(moved->points.size(), base->points.size());
    EXPECT_EQ(moved->closed, base->closed);
    const auto expected = transform(base->points, angle, scale, shift);
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_NEAR((moved->points[i] - expected[i]).norm(), 0, 1e-9 * scale * 300) << i;
  }
}

TEST(StrokesPreprocess, ReversedClosedStrokeGivesTheSameShape) {
  const auto raw = circle_stroke(Vec2(300, 200), 90, 0.96, 5);
  std::vector<Vec2> rev(raw.rbegin(), raw.rend());
  const auto a = preprocess_stroke(raw);
  const auto b = preprocess_stroke(rev);
  ASSERT_TRUE(a && b);
  EXPECT_TRUE(a->closed && b->closed);
  EXPECT_LT(distance_to_polyline(a->points, b->points), 1.0);  // 1 px on a 180 px circle
  EXPECT_LT(distance_to_polyline(b->points, a->points), 1.0);
}

// === Lifting
TEST(StrokesLift, PerspectiveAndOrthographicLandOnThePlane) {
  Camera persp;  // default: eye (3, 2.5, 4) looking at the origin
  Camera ortho = persp;
  ortho.orthographic = true;
  for (const Camera& cam : {persp, ortho}) {
    for (const Plane& plane : {Plane{Vec3::UnitZ(), 0.0}, Plane{Vec3::UnitX(), 0.25},
                               Plane{Vec3(1, 1, 1).normalized(), 0.1}}) {
      // Points on the plane near the origin -> window -> lifted back.
      Vec3 u, v;
      plane.basis(u, v);
      std::vector<Vec3> truth;
      std::vector<Vec2> window;
      for (int i = 0; i < 12; ++i) {
        const double t = 2 * M_PI * i / 12;
        const Vec3 p = plane.offset * plane.normal + 0.6 * std::cos(t) * u + 0.4 * std::sin(t) * v;
        const auto w = cam.project(p);
        ASSERT_TRUE(w);
        truth.push_back(p);
        window.emplace_back(w->x(), w->y());
      }
      auto lifted = lift_stroke(window, cam, plane);
      ASSERT_TRUE(lifted) << lifted.message();
      for (std::size_t i = 0; i < truth.size(); ++i) {
        EXPECT_NEAR(((*lifted)[i] - truth[i]).norm(), 0, 1e-9);
        EXPECT_NEAR(plane.signed_distance((*lifted)[i]), 0, 1e-14);
      }
    }
  }
}

TEST(StrokesLift, RaysMissingThePlaneAreRefused) {
  const std::vector<Vec2> pts{{600, 400}, {640, 420}, {660, 380}};
  // Orthographic view down -Z: a plane containing the view direction is seen edge-on.
  auto edge_on = lift_stroke(pts, ortho_camera(), Plane{Vec3::UnitX(), 0.0});
  ASSERT_FALSE(edge_on);
  EXPECT_NE(edge_on.message().find("parallel"), std::string::npos) << edge_on.message();
  // A plane behind the eye.
  auto behind = lift_stroke(pts, ortho_camera(), Plane{Vec3::UnitZ(), 10.0});
  ASSERT_FALSE(behind);
  EXPECT_NE(behind.message().find("behind the eye"), std::string::npos) << behind.message();
  EXPECT_NE(behind.message().find("stroke point 0"), std::string::npos) << behind.message();
  // A nearly edge-on plane puts points beyond the far plane.
  Camera persp;
  persp.eye = Vec3(0, 0.5, 5);
  persp.target = Vec3(0, 0.5, 0);
  auto grazing = lift_stroke({{640, 401}, {640, 402}}, persp, Plane{Vec3::UnitY(), 0.0});
  ASSERT_FALSE(grazing);
  EXPECT_NE(grazing.message().find("far plane"), std::string::npos) << grazing.message();
  auto nan = lift_stroke({{std::nan(""), 1.0}}, persp, Plane{});
  EXPECT_FALSE(nan);
}

TEST(StrokesLift, PlaneStrokePipelineRefusesSelfCrossing) {
  const Camera cam = ortho_camera();
  std::vector<Vec2> eight;
  for (int i = 0; i <= 400; ++i) {  // a figure eight centred on (640, 400)
    const double t = 2 * M_PI * i / 400.0 + 0.2;
    eight.emplace_back(640 + 200 * std::sin(t), 400 + 120 * std::sin(2 * t));
  }
  auto r = prepare_plane_stroke(eight, cam, Plane{Vec3::UnitZ(), 0.0});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("stroke crosses itself at (640"), std::string::npos) << r.message();
  auto ok = prepare_plane_stroke(circle_stroke(Vec2(640, 400), 150, 0.97), cam, Plane{Vec3::UnitZ(), 0.0});
  ASSERT_TRUE(ok) << ok.message();
  EXPECT_TRUE(ok->closed);
  ASSERT_EQ(ok->points.size(), ok->window_points.size());
  for (const auto& p : ok->points) EXPECT_EQ(p.z(), 0.0);
}

// === Property test: random strokes are either accepted with valid output or refused with a
// message; nothing crashes (this also runs under ASan/UBSan in CI).
TEST(StrokesPreprocess, RandomStrokesAreAcceptedValidOrRefusedWithAMessage) {
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> count(0, 300);
  std::normal_distribution<double> step(0.0, 6.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Camera cam;
  const Plane plane{Vec3::UnitY(), 0.0};
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double scale = trial % 10 == 0 ? 1e6 : (trial % 10 == 1 ? 1e-3 : 1.0);
    std::vector<Vec2> raw;
    Vec2 p(640 * unit(rng), 400 + 400 * unit(rng));
    const int n = count(rng);
    for (int i = 0; i < n; ++i) {
      p += scale * Vec2(step(rng), step(rng));
      raw.push_back(p);
    }
    if (trial % 3 == 0 && raw.size() > 10) raw.push_back(raw.front());  // try to close it
    auto r = prepare_plane_stroke(raw, cam, plane);
    if (!r) {
      ++refused;
      EXPECT_FALSE(r.message().empty());
      continue;
    }
    ++accepted;
    ASSERT_GE(r->window_points.size(), 3u);
    ASSERT_EQ(r->points.size(), r->window_points.size());
    for (const auto& q : r->points) {
      ASSERT_TRUE(q.allFinite());
      ASSERT_NEAR(plane.signed_distance(q), 0.0, 1e-9 * (1.0 + q.norm()));
    }
    if (r->closed) {
      EXPECT_FALSE(first_self_crossing(r->window_points));
      EXPECT_NE(r->window_points.front(), r->window_points.back());
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}
