// Sculpting operations through the screen (thesis 3.2.2; issue 6 points 3-5): cutting along an
// open stroke, tunnelling along a closed stroke, smoothing under a scratch-out. Invariants on
// every result: closed, 2-manifold, outward, free of self-intersections (check_guarantees), plus
// the expected change of genus, components, volume and where the material went.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "modeling/mesh_boolean.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_smooth.h"
#include "modeling/view_extrusion.h"
#include "tests/mesh_fixtures.h"

namespace ps {
namespace {

using testing::front_camera;

std::vector<Vec2> vertical_line(double x, double y0, double y1, int n = 40) {
  std::vector<Vec2> s;
  for (int i = 0; i <= n; ++i) s.emplace_back(x, y0 + (y1 - y0) * i / n);
  return s;
}

std::vector<Vec2> circle_px(const Vec2& c, double r, int n = 48) {
  std::vector<Vec2> s;
  for (int i = 0; i < n; ++i) s.push_back(c + r * Vec2(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n)));
  return s;
}

void expect_valid(const TriMesh& m) {
  const MeshGuarantees g = check_guarantees(m);
  EXPECT_TRUE(g.valid()) << g.problem();
}

const TriMesh& sphere() {
  static const TriMesh s = testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  return s;
}

// === Tool solid
TEST(ViewExtrusion, IsAClosedOutwardPrismAlongTheRays) {
  const Camera cam = front_camera();
  auto tool = extrude_window_polygon(circle_px(Vec2(320, 240), 50), cam, 2.0, 6.0);
  ASSERT_TRUE(tool) << tool.message();
  expect_valid(*tool);
  // Reversed corners give the same solid.
  auto circle = circle_px(Vec2(320, 240), 50);
  std::reverse(circle.begin(), circle.end());
  auto rev = extrude_window_polygon(circle, cam, 2.0, 6.0);
  ASSERT_TRUE(rev);
  EXPECT_NEAR(signed_volume(*rev), signed_volume(*tool), 1e-12);
  // Every corner projects back onto its pixel.
  for (const auto& v : tool->vertices) {
    const auto p = cam.project(v);
    ASSERT_TRUE(p);
    EXPECT_NEAR((Vec2(p->x(), p->y()) - Vec2(320, 240)).norm(), 50.0, 1e-6);
  }
}

TEST(ViewExtrusion, RefusesBadPolygons) {
  const Camera cam = front_camera();
  EXPECT_FALSE(extrude_window_polygon({{0, 0}, {1, 1}}, cam, 1, 2));
  EXPECT_FALSE(extrude_window_polygon({{0, 0}, {10, 0}, {20, 0}}, cam, 1, 2));
  const auto bow = extrude_window_polygon({{0, 0}, {20, 20}, {20, 0}, {0, 10}}, cam, 1, 2);
  ASSERT_FALSE(bow);
  EXPECT_NE(bow.message().find("crosses itself"), std::string::npos) << bow.message();
  EXPECT_FALSE(extrude_window_polygon(circle_px(Vec2(320, 240), 50), cam, 3, 2));
  EXPECT_FALSE(extrude_window_polygon({{0, 0}, {NAN, 0}, {0, 10}}, cam, 1, 2));
}

// === Booleans
TEST(MeshBoolean, UnionDifferenceIntersectionVolumesAgree) {
  const TriMesh a = testing::uv_sphere(Vec3::Zero(), 1.0, 16, 32);
  const TriMesh b = testing::uv_sphere(Vec3(0.8, 0, 0), 0.7, 16, 32);
  auto u = mesh_boolean(a, b, BooleanOp::kUnion);
  auto d = mesh_boolean(a, b, BooleanOp::kDifference);
  auto i = mesh_boolean(a, b, BooleanOp::kIntersection);
  ASSERT_TRUE(u && d && i);
  expect_valid(*u);
  expect_valid(*d);
  expect_valid(*i);
  // |A u B| = |A| + |B| - |A n B| and |A - B| = |A| - |A n B| (exact up to rounding).
  EXPECT_NEAR(signed_volume(*u), signed_volume(a) + signed_volume(b) - signed_volume(*i), 1e-9);
  EXPECT_NEAR(signed_volume(*d), signed_volume(a) - signed_volume(*i), 1e-9);
}

TEST(MeshBoolean, RefusesOperandsThatAreNotSolids) {
  TriMesh open = sphere();
  open.faces.pop_back();
  auto r = mesh_boolean(open, sphere(), BooleanOp::kUnion);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("the model"), std::string::npos) << r.message();
  TriMesh inside_out = sphere();
  for (auto& f : inside_out.faces) std::swap(f[1], f[2]);
  r = mesh_boolean(sphere(), inside_out, BooleanOp::kDifference);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("the tool solid"), std::string::npos) << r.message();
  EXPECT_FALSE(mesh_boolean(TriMesh{}, sphere(), BooleanOp::kUnion));
}

// Rounding the exact difference leaves a constructed point 1.8e-16 from a sphere vertex whose
// fans cross (a circle centred on the pole of a 100 x 100 UV sphere, seen along the pole: the
// tool's walls pass through the model's vertices up to rounding). The two are merged, keeping
// the model's vertex, instead of refusing the result.
TEST(MeshBoolean, MergesRoundedNeighboursKeepingTheOperandVertex) {
  const TriMesh model = testing::uv_sphere(Vec3::Zero(), 1.0, 100, 100);
  Camera cam = front_camera();
  cam.up = Vec3(0, 1, 0);
  Camera along_pole = cam;
  along_pole.eye = Vec3(0, 4, 0);
  along_pole.up = Vec3(0, 0, -1);
  for (const Camera& c : {cam, along_pole}) {
    const DepthRange d = depth_range(model, c);
    auto tool = extrude_window_polygon(circle_px(Vec2(320, 240), 50), c, d.min, d.max);
    ASSERT_TRUE(tool) << tool.message();
    auto out = mesh_boolean(model, *tool, BooleanOp::kDifference);
    ASSERT_TRUE(out) << out.message();
    expect_valid(*out);
    EXPECT_EQ(mesh_topology(*out).genus, 1);
    // No vertex of the result lies within rounding distance of an operand vertex without being
    // that vertex bit for bit.
    std::vector<Vec3> inputs = model.vertices;
    inputs.insert(inputs.end(), tool->vertices.begin(), tool->vertices.end());
    for (const Vec3& v : out->vertices)
      for (const Vec3& p : inputs) {
        const double dist = (v - p).norm();
        if (dist > 0 && dist < 1e-12) ADD_FAILURE() << "vertex " << v.transpose() << " is " << dist << " from an operand vertex";
      }
  }
}

// A solid remembered as checked is recognised bit for bit only: any other mesh, however close,
// is checked in full.
TEST(SolidCheck, TheMemoNeverChangesTheAnswer) {
  const TriMesh good = testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  ASSERT_GE(good.faces.size(), 1000u);
  ASSERT_TRUE(check_solid(good, "the model"));
  remember_checked_solid(good);
  ASSERT_TRUE(check_solid(good, "the model"));
  TriMesh pierced = good;
  pierced.vertices[200] = -1.6 * pierced.vertices[200];  // pushed through the far side
  const Status s = check_solid(pierced, "the model");
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("intersects itself"), std::string::npos) << s.message();
  TriMesh flipped = good;
  for (auto& f : flipped.faces) std::swap(f[1], f[2]);
  EXPECT_FALSE(check_solid(flipped, "the model"));
  forget_checked_solids();
  EXPECT_TRUE(check_solid(good, "the model"));
}

// === Cutting
TEST(SculptCut, KeepsOneComponentOnTheUnmarkedSide) {
  const Camera cam = front_camera();
  const double x_cut = 360;
  auto out = cut_by_stroke(sphere(), vertical_line(x_cut, 20, 460), Vec2(600, 240), cam);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  const MeshTopology t = mesh_topology(*out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  const double v0 = signed_volume(sphere());
  EXPECT_LT(t.signed_volume, 0.9 * v0);
  EXPECT_GT(t.signed_volume, 0.5 * v0);
  for (const auto& v : out->vertices) {
    const auto p = cam.project(v);
    ASSERT_TRUE(p);
    EXPECT_LE(p->x(), x_cut + 1e-6);
  }
}

TEST(SculptCut, ReversedStrokeAndOtherSideAddUp) {
  const Camera cam = front_camera();
  auto line = vertical_line(300, 460, 20);
  auto left = cut_by_stroke(sphere(), line, Vec2(40, 240), cam);
  std::reverse(line.begin(), line.end());
  auto right = cut_by_stroke(sphere(), line, Vec2(600, 240), cam);
  ASSERT_TRUE(left && right) << left.message() << right.message();
  // The two kept parts partition the sphere.
  EXPECT_NEAR(signed_volume(*left) + signed_volume(*right), signed_volume(sphere()), 1e-9);
}

TEST(SculptCut, TranslatingModelAndCameraTogetherChangesNothingButPosition) {
  Camera cam = front_camera();
  auto a = cut_by_stroke(sphere(), vertical_line(360, 20, 460), Vec2(600, 240), cam);
  const Vec3 d(0.25, -0.5, 0.125);
  TriMesh moved = sphere();
  for (auto& v : moved.vertices) v += d;
  cam.eye += d;
  cam.target += d;
  auto b = cut_by_stroke(moved, vertical_line(360, 20, 460), Vec2(600, 240), cam);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(signed_volume(*a), signed_volume(*b), 1e-9);
}

TEST(SculptCut, RefusesStrokesThatDoNotCrossTheModel) {
  const Camera cam = front_camera();
  const TriMesh before = sphere();
  auto inside = cut_by_stroke(sphere(), vertical_line(320, 200, 280), Vec2(600, 240), cam);
  ASSERT_FALSE(inside);
  EXPECT_NE(inside.message().find("start and end off the model"), std::string::npos) << inside.message();
  auto beside = cut_by_stroke(sphere(), vertical_line(630, 10, 470), Vec2(635, 240), cam);
  ASSERT_FALSE(beside);
  EXPECT_NE(beside.message().find("does not pass over"), std::string::npos) << beside.message();
  EXPECT_FALSE(cut_by_stroke(sphere(), {}, Vec2(600, 240), cam));
  EXPECT_FALSE(cut_by_stroke(sphere(), {{NAN, 0}, {1, 1}}, Vec2(600, 240), cam));
  EXPECT_FALSE(cut_by_stroke(sphere(), vertical_line(360, 20, 460), Vec2(NAN, 240), cam));
  Camera inside_cam = cam;
  inside_cam.eye = Vec3(0, 0, 0.5);
  EXPECT_FALSE(cut_by_stroke(sphere(), vertical_line(360, 20, 460), Vec2(600, 240), inside_cam));
  EXPECT_EQ(sphere().vertices, before.vertices);  // inputs are values: nothing changed
}

// === Tunnelling
TEST(SculptTunnel, AHoleThroughASphereRaisesTheGenusByOne) {
  const Camera cam = front_camera();
  auto out = tunnel_by_stroke(sphere(), circle_px(Vec2(320, 240), 50), cam);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  const MeshTopology t = mesh_topology(*out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 1);
  EXPECT_LT(t.signed_volume, signed_volume(sphere()));
}

TEST(SculptTunnel, AHoleThroughATorusTubeMakesGenusTwo) {
  Camera cam;
  cam.eye = Vec3(0, 4, 0);
  cam.target = Vec3::Zero();
  cam.up = Vec3(0, 0, -1);
  cam.width = 640;
  cam.height = 480;
  const TriMesh ring = testing::torus(Vec3::Zero(), 1.0, 0.4, 48, 24);
  const auto c = cam.project(Vec3(1.0, 0, 0));
  ASSERT_TRUE(c);
  ASSERT_TRUE(on_silhouette(ring, cam, Vec2(c->x(), c->y())));
  EXPECT_FALSE(on_silhouette(ring, cam, Vec2(320, 240)));  // the torus's hole
  auto out = tunnel_by_stroke(ring, circle_px(Vec2(c->x(), c->y()), 12), cam);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  EXPECT_EQ(mesh_topology(*out).genus, 2);
}

TEST(SculptTunnel, RefusesAStrokeLeavingTheSilhouette) {
  const Camera cam = front_camera();
  auto r = tunnel_by_stroke(sphere(), circle_px(Vec2(320, 240), 300), cam);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("leaves the model"), std::string::npos) << r.message();
  EXPECT_FALSE(tunnel_by_stroke(sphere(), {{300, 240}, {340, 240}}, cam));
}

// === Smoothing by scratch-out
TEST(SculptSmooth, SmoothsOnlyTheRegionUnderTheStroke) {
  const Camera cam = front_camera();
  TriMesh bumpy = testing::uv_sphere(Vec3::Zero(), 1.0, 32, 64);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  for (auto& v : bumpy.vertices) v *= 1.0 + noise(rng);
  ASSERT_TRUE(check_guarantees(bumpy).valid());
  // A scratch-out: back and forth over a small region in the middle.
  std::vector<Vec2> zigzag;
  for (int i = 0; i <= 8; ++i) zigzag.emplace_back(i % 2 ? 360 : 280, 210 + 7.5 * i);
  ScratchSmoothReport rep;
  auto out = smooth_by_scratch(bumpy, zigzag, cam, {}, &rep);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  EXPECT_GT(rep.region_vertices, 10);
  EXPECT_GE(rep.steps, 1);
  // Roughness: distance of a vertex from the mean of its neighbours.
  std::vector<std::vector<int>> ring(bumpy.vertices.size());
  for (const auto& f : bumpy.faces)
    for (std::size_t k = 0; k < 3; ++k) ring[static_cast<std::size_t>(f[k])].push_back(f[(k + 1) % 3]);
  auto roughness = [&](const TriMesh& m, std::size_t v) {
    Vec3 mean = Vec3::Zero();
    for (int n : ring[v]) mean += m.vertices[static_cast<std::size_t>(n)];
    return (m.vertices[v] - mean / static_cast<double>(ring[v].size())).norm();
  };
  int moved = 0;
  double rough_before = 0, rough_after = 0;
  for (std::size_t v = 0; v < bumpy.vertices.size(); ++v) {
    if (out->vertices[v] != bumpy.vertices[v]) {
      ++moved;
      // Only front vertices near the stroke move.
      EXPECT_GT(bumpy.vertices[v].z(), 0.5);
      rough_before += roughness(bumpy, v);
      rough_after += roughness(*out, v);
    }
  }
  EXPECT_EQ(moved, rep.region_vertices);
  EXPECT_LT(rough_after, 0.5 * rough_before) << "mean roughness " << rough_before / moved << " -> " << rough_after / moved;
}

TEST(SculptSmooth, RefusesAStrokeOffTheModel) {
  const Camera cam = front_camera();
  auto r = smooth_by_scratch(sphere(), {{5, 5}, {20, 5}, {5, 6}}, cam);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("not over the model"), std::string::npos) << r.message();
  EXPECT_FALSE(smooth_by_scratch(sphere(), {}, cam));
  EXPECT_FALSE(smooth_by_scratch(sphere(), {{NAN, 1}}, cam));
}

}  // namespace
}  // namespace ps
