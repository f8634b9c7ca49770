// Extrusion by strokes (thesis 3.2.2; issue 6 point 2): a closed stroke on the surface, the
// automatic reference plane, a silhouette on it, the swept part joined by exact union and the join
// smoothed. Invariants on every result: closed, 2-manifold, outward, free of self-intersections
// (check_guarantees), one component, genus unchanged, volume grows, the new material where the
// strokes put it; refusals leave the model alone and say why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdio>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/sculpt_extrude.h"
#include "tests/mesh_fixtures.h"

namespace ps {
namespace {

using testing::front_camera;

std::vector<Vec2> circle_px(const Vec2& c, double r, int n = 48) {
  std::vector<Vec2> s;
  for (int i = 0; i < n; ++i) s.push_back(c + r * Vec2(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n)));
  return s;
}

const TriMesh& sphere() {
  static const TriMesh s = testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  return s;
}

// A camera looking straight at the reference plane, its up along the region's normal axis.
Camera side_camera(const ExtrudePlane& p) {
  Camera c;
  c.eye = p.centre + 4.0 * p.plane.normal;
  c.target = p.centre;
  c.up = p.normal_axis;
  c.width = 640;
  c.height = 480;
  return c;
}

// Plane coordinates (u along `across`, v along `normal_axis`) to a 3D point on the plane.
Vec3 on_plane(const ExtrudePlane& p, double u, double v) { return p.centre + u * p.across + v * p.normal_axis; }

// Half the base curve's width along `across`, and the centre of that extent.
void base_extent(const ExtrudePlane& p, double& half, double& mid) {
  double lo = 1e300, hi = -1e300;
  for (const auto& q : p.base_curve) {
    lo = std::min(lo, (q - p.centre).dot(p.across));
    hi = std::max(hi, (q - p.centre).dot(p.across));
  }
  half = 0.5 * (hi - lo);
  mid = 0.5 * (hi + lo);
}

// A bump silhouette: half an ellipse from one side of the base to the other, `height` high,
// drawn (as pixels) under `cam`.
std::vector<Vec2> bump_px(const ExtrudePlane& p, const Camera& cam, double height, double width_factor = 0.95,
                          double lift = 0.0, int n = 40) {
  double half = 0, mid = 0;
  base_extent(p, half, mid);
  std::vector<Vec2> px;
  for (int i = 0; i <= n; ++i) {
    const double t = M_PI * i / n;
    const auto w = cam.project(on_plane(p, mid - width_factor * half * std::cos(t), lift + height * std::sin(t)));
    px.emplace_back(w->x(), w->y());
  }
  return px;
}

struct Strokes {
  Camera cam = front_camera();
  std::vector<Vec2> base;
  ExtrudePlane plane;
  ExtrudeOptions options;
  std::vector<Vec2> silhouette;
};

Strokes sphere_bump(const Vec2& centre_px = Vec2(350, 220), double radius_px = 50, double height = 0.5) {
  Strokes s;
  s.base = circle_px(centre_px, radius_px);
  auto plane = extrusion_reference_plane(sphere(), s.base, s.cam);
  EXPECT_TRUE(plane) << plane.message();
  s.plane = *plane;
  s.options.silhouette_camera = side_camera(s.plane);
  s.silhouette = bump_px(s.plane, *s.options.silhouette_camera, height);
  return s;
}

void expect_valid(const TriMesh& m) {
  const MeshGuarantees g = check_guarantees(m);
  EXPECT_TRUE(g.valid()) << g.problem();
}

// === Reference plane
TEST(ExtrudePlane, ContainsTheRegionNormalThroughTheStrokeCentre) {
  const Camera cam = front_camera();
  auto p = extrusion_reference_plane(sphere(), circle_px(Vec2(320, 240), 50), cam);
  ASSERT_TRUE(p) << p.message();
  // A centred circle on the unit sphere seen from +z: region normal +z, centre on the z axis.
  EXPECT_GT(p->region_normal.z(), 0.99);
  EXPECT_NEAR(p->centre.x(), 0.0, 1e-2);
  EXPECT_NEAR(p->centre.y(), 0.0, 1e-2);
  EXPECT_GT(p->centre.z(), 0.9);
  EXPECT_NEAR(p->plane.signed_distance(p->centre), 0.0, 1e-12);
  EXPECT_NEAR(p->plane.normal.dot(p->region_normal), 0.0, 1e-12);
  EXPECT_NEAR(p->plane.normal.dot(p->across), 0.0, 1e-12);
  EXPECT_NEAR(p->across.dot(p->region_normal), 0.0, 1e-12);
  // Every base-curve point projects back near the stroke (the curve lies on the sphere).
  for (const auto& q : p->base_curve) {
    EXPECT_NEAR(q.norm(), 1.0, 1e-2);
    const auto w = cam.project(q);
    ASSERT_TRUE(w);
    EXPECT_NEAR((Vec2(w->x(), w->y()) - Vec2(320, 240)).norm(), 50.0, 1.0);
  }
}

TEST(ExtrudePlane, SpinAndTiltTurnThePlaneAboutTheTwoAxes) {
  const Camera cam = front_camera();
  const auto stroke = circle_px(Vec2(320, 240), 50);
  auto p0 = extrusion_reference_plane(sphere(), stroke, cam);
  ExtrudeOptions spin;
  spin.spin = M_PI / 2;
  auto p1 = extrusion_reference_plane(sphere(), stroke, cam, spin);
  ExtrudeOptions tilt;
  tilt.tilt = 0.3;
  auto p2 = extrusion_reference_plane(sphere(), stroke, cam, tilt);
  ASSERT_TRUE(p0 && p1 && p2);
  // Spin: about the normal axis, which stays in the plane; the plane normal turns by 90 degrees.
  EXPECT_NEAR(p1->normal_axis.dot(p0->normal_axis), 1.0, 1e-12);
  EXPECT_NEAR(p1->plane.normal.dot(p0->plane.normal), 0.0, 1e-9);
  EXPECT_NEAR(p1->plane.normal.dot(p0->across), 1.0, 1e-9);  // (n x a) x n = a
  // Tilt: about the diameter, which stays; the normal axis leaves the region normal by 0.3 rad.
  EXPECT_NEAR(p2->across.dot(p0->across), 1.0, 1e-12);
  EXPECT_NEAR(std::acos(std::clamp(p2->normal_axis.dot(p2->region_normal), -1.0, 1.0)), 0.3, 1e-9);
  EXPECT_NEAR(p2->plane.signed_distance(p2->centre), 0.0, 1e-12);
}

TEST(ExtrudePlane, RefusesATiltOfNinetyDegreesOrAnInfiniteSpin) {
  const auto stroke = circle_px(Vec2(320, 240), 50);
  ExtrudeOptions o;
  o.tilt = M_PI / 2;
  auto p = extrusion_reference_plane(sphere(), stroke, front_camera(), o);
  ASSERT_FALSE(p);
  EXPECT_NE(p.message().find("tilt must lie strictly between -90 and 90 degrees (found 90 degrees)"), std::string::npos)
      << p.message();
  o.tilt = -1.5;
  EXPECT_TRUE(extrusion_reference_plane(sphere(), stroke, front_camera(), o));
  o.spin = INFINITY;
  p = extrusion_reference_plane(sphere(), stroke, front_camera(), o);
  ASSERT_FALSE(p);
  EXPECT_NE(p.message().find("spin is not a finite angle"), std::string::npos) << p.message();
}

// === Extrusion
TEST(Extrude, BumpOnASphereIsAValidSolidWithTheMaterialOutsideNearTheStroke) {
  Strokes s = sphere_bump();
  ExtrudeReport rep;
  auto out = extrude_by_strokes(sphere(), s.base, s.silhouette, s.cam, s.options, &rep);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  expect_valid(rep.part);
  const MeshTopology t = mesh_topology(*out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  const double v0 = signed_volume(sphere());
  EXPECT_GT(t.signed_volume, v0 + 0.02);
  EXPECT_NEAR(rep.added_volume, t.signed_volume - v0, 1e-12);
  // About the half ellipsoid the silhouette describes (round base, 0.95 of its width, 0.5 high),
  // less the sphere cap it swallows and what the join smoothing takes off.
  double half = 0, mid = 0;
  base_extent(s.plane, half, mid);
  const double half_ellipsoid = 2.0 / 3.0 * M_PI * std::pow(0.95 * half, 2) * 0.5;
  EXPECT_GT(rep.added_volume, 0.8 * half_ellipsoid);
  EXPECT_LT(rep.added_volume, 1.05 * half_ellipsoid);
  EXPECT_GT(rep.join_vertices, 0);
  EXPECT_GT(rep.smooth_steps, 0);
  std::printf("part %zu faces, result %zu faces, join %d vertices, smoothed %d in %d steps, %d attempt(s), added volume %.4f\n",
              rep.part.faces.size(), out->faces.size(), rep.join_vertices, rep.smoothed_vertices, rep.smooth_steps,
              rep.boolean_attempts, rep.added_volume);
  // Where the new material is: every vertex outside the original sphere lies near the stroke's
  // region, and the tip (0.5 above the centre along the normal axis) is on the result.
  const Vec3 tip = s.plane.centre + 0.5 * s.plane.normal_axis;
  double tip_distance = 1e300, outside = 0;
  for (const auto& v : out->vertices) {
    tip_distance = std::min(tip_distance, (v - tip).norm());
    if (v.norm() > 1.0 + 1e-9) {
      ++outside;
      EXPECT_LT((v - s.plane.centre).norm(), 0.65) << v.transpose();
      EXPECT_GT((v - s.plane.centre).dot(s.plane.region_normal), -0.05) << v.transpose();
    }
  }
  EXPECT_GT(outside, 100);
  EXPECT_LT(tip_distance, 1e-3);
  // Far from the stroke the sphere is untouched: the back pole is still there.
  bool back_pole = false;
  for (const auto& v : out->vertices) back_pole |= (v - Vec3(0, 0, -1)).norm() < 0.2;
  EXPECT_TRUE(back_pole);
}

// The sharpest dihedral angle (radians between the two face normals) over the edges whose
// midpoint lies within `radius` of the base curve: the crease where the part meets the model.
double sharpest_near(const TriMesh& m, const std::vector<Vec3>& base, double radius) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces[f][static_cast<std::size_t>(k)], b = m.faces[f][static_cast<std::size_t>((k + 1) % 3)];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  auto normal = [&](int f) {
    const Face& t = m.faces[static_cast<std::size_t>(f)];
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    return Vec3((m.vertices[static_cast<std::size_t>(t[1])] - a).cross(m.vertices[static_cast<std::size_t>(t[2])] - a).normalized());
  };
  double sharpest = 0;
  for (const auto& [e, fs] : edge_faces) {
    if (fs.size() != 2) continue;
    const Vec3 mid = 0.5 * (m.vertices[static_cast<std::size_t>(e.first)] + m.vertices[static_cast<std::size_t>(e.second)]);
    double d = 1e300;
    for (const auto& q : base) d = std::min(d, (q - mid).norm());
    if (d > radius) continue;
    sharpest = std::max(sharpest, std::acos(std::clamp(normal(fs[0]).dot(normal(fs[1])), -1.0, 1.0)));
  }
  return sharpest;
}

TEST(Extrude, SmoothingSoftensTheJoin) {
  Strokes s = sphere_bump();
  ExtrudeOptions raw = s.options;
  raw.smooth_steps = 0;
  ExtrudeReport rep_raw, rep;
  auto a = extrude_by_strokes(sphere(), s.base, s.silhouette, s.cam, raw, &rep_raw);
  auto b = extrude_by_strokes(sphere(), s.base, s.silhouette, s.cam, s.options, &rep);
  ASSERT_TRUE(a && b) << a.message() << b.message();
  expect_valid(*a);
  EXPECT_EQ(rep_raw.smooth_steps, 0);
  EXPECT_GT(rep.smooth_steps, 0);
  const double crease_raw = sharpest_near(*a, s.plane.base_curve, 0.05);
  const double crease = sharpest_near(*b, s.plane.base_curve, 0.05);
  std::printf("sharpest edge at the join: %.1f deg unsmoothed, %.1f deg smoothed\n", crease_raw * 180 / M_PI,
              crease * 180 / M_PI);
  EXPECT_LT(crease, 0.75 * crease_raw);
  // Local: the smoothing changes the volume by little.
  EXPECT_NEAR(rep.added_volume, rep_raw.added_volume, 0.1 * rep_raw.added_volume);
}

TEST(Extrude, TiltedPlaneAndBentSilhouetteGiveAValidSolid) {
  const Camera cam = front_camera();
  const auto base = circle_px(Vec2(350, 220), 50);
  ExtrudeOptions o;
  o.tilt = 0.4;
  o.spin = 0.5;
  auto plane = extrusion_reference_plane(sphere(), base, cam, o);
  ASSERT_TRUE(plane) << plane.message();
  o.silhouette_camera = side_camera(*plane);
  // A finger leaning to the +across side: the centre line bends by 0.3 over a height of 0.6.
  double half = 0, mid = 0;
  base_extent(*plane, half, mid);
  std::vector<Vec2> sil;
  for (int i = 0; i <= 40; ++i) {
    const double t = M_PI * i / 40, h = 0.6 * std::sin(t);
    const auto w = o.silhouette_camera->project(
        on_plane(*plane, mid - 0.9 * half * std::cos(t) + 0.3 * (h / 0.6) * (h / 0.6), h));
    sil.emplace_back(w->x(), w->y());
  }
  ExtrudeReport rep;
  auto out = extrude_by_strokes(sphere(), base, sil, cam, o, &rep);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  const MeshTopology t = mesh_topology(*out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  EXPECT_GT(rep.added_volume, 0.02);
  // The part leans as drawn: its highest point along the normal axis is the tip, 0.6 up and
  // 0.3 over to the +across side (within the sampling: the apex is the silhouette point farthest
  // from the ends' midpoint, not the highest one).
  Vec3 top = plane->centre;
  for (const auto& v : out->vertices)
    if ((v - plane->centre).dot(plane->normal_axis) > (top - plane->centre).dot(plane->normal_axis)) top = v;
  EXPECT_NEAR((top - plane->centre).dot(plane->normal_axis), 0.6, 0.02);
  EXPECT_NEAR((top - plane->centre).dot(plane->across), mid + 0.3, 0.02);
}

TEST(Extrude, TranslatingModelAndCamerasTogetherGivesTheSameVolume) {
  Strokes s = sphere_bump();
  auto a = extrude_by_strokes(sphere(), s.base, s.silhouette, s.cam, s.options);
  ASSERT_TRUE(a) << a.message();
  const Vec3 d(0.7, -0.3, 1.1);
  TriMesh moved = sphere();
  for (auto& v : moved.vertices) v += d;
  Camera cam = s.cam;
  cam.eye += d;
  cam.target += d;
  ExtrudeOptions o = s.options;
  o.silhouette_camera->eye += d;
  o.silhouette_camera->target += d;
  auto b = extrude_by_strokes(moved, s.base, s.silhouette, cam, o);
  ASSERT_TRUE(b) << b.message();
  expect_valid(*b);
  EXPECT_NEAR(signed_volume(*b), signed_volume(*a), 1e-6 * signed_volume(*a));
}

TEST(Extrude, KeepsTheGenusOfATorus) {
  const TriMesh tor = testing::torus(Vec3::Zero(), 1.0, 0.4, 48, 24);
  const Camera cam = front_camera();
  const auto base = circle_px(Vec2(320, 240), 30);
  auto plane = extrusion_reference_plane(tor, base, cam);
  ASSERT_TRUE(plane) << plane.message();
  ExtrudeOptions o;
  o.silhouette_camera = side_camera(*plane);
  auto out = extrude_by_strokes(tor, base, bump_px(*plane, *o.silhouette_camera, 0.3), cam, o);
  ASSERT_TRUE(out) << out.message();
  expect_valid(*out);
  const MeshTopology t = mesh_topology(*out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 1);
  EXPECT_GT(t.signed_volume, signed_volume(tor));
}

// === Digging (thesis 3.2.2: a silhouette drawn into the model digs; out at the back: a tunnel)

// Generalised winding number of a closed mesh about p: about 1 inside, 0 outside.
double winding(const TriMesh& m, const Vec3& p) {
  double sum = 0;
  for (const auto& f : m.faces) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(f[0])] - p, b = m.vertices[static_cast<std::size_t>(f[1])] - p,
               c = m.vertices[static_cast<std::size_t>(f[2])] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4 * M_PI);
}

// A U into the model: straight sides 0.9 of the base's width apart down to `depth`, a round
// bottom, every point shifted along `across` by lean * (its depth / depth)^2 (a bent skeleton).
std::vector<Vec2> u_px(const ExtrudePlane& p, const Camera& cam, double depth, double lean) {
  double half = 0, mid = 0;
  base_extent(p, half, mid);
  const double r = 0.9 * half;
  std::vector<Vec2> uv;
  for (int i = 0; i <= 20; ++i) uv.emplace_back(mid - r, -(depth - r) * i / 20.0);
  for (int i = 1; i < 20; ++i) {
    const double t = M_PI * i / 20;
    uv.emplace_back(mid - r * std::cos(t), -(depth - r) - r * std::sin(t));
  }
  for (int i = 20; i >= 0; --i) uv.emplace_back(mid + r, -(depth - r) * i / 20.0);
  std::vector<Vec2> px;
  for (const auto& q : uv) {
    const double f = -q.y() / depth;
    const auto w = cam.project(on_plane(p, q.x() + lean * f * f, q.y()));
    px.emplace_back(w->x(), w->y());
  }
  return px;
}

// A dig into the sphere: valid, one component, the genus (and the report's change) as given.
void expect_dug(const TriMesh& out, const ExtrudeReport& rep, int genus) {
  expect_valid(out);
  const MeshTopology t = mesh_topology(out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, genus);
  EXPECT_TRUE(rep.dug);
  EXPECT_EQ(rep.genus_change, genus);
}

TEST(Dig, SilhouetteIntoTheModelDigsAPocket) {
  Strokes s = sphere_bump(Vec2(350, 220), 50, -0.5);
  ExtrudeReport rep;
  auto out = extrude_by_strokes(sphere(), s.base, s.silhouette, s.cam, s.options, &rep);
  ASSERT_TRUE(out) << out.message();
  expect_dug(*out, rep, 0);
  double half = 0, mid = 0;
  base_extent(s.plane, half, mid);
  const double half_ellipsoid = 2.0 / 3.0 * M_PI * std::pow(0.95 * half, 2) * 0.5;
  std::printf("pocket: removed %.4f (half ellipsoid %.4f), join %d vertices, %d smoothing steps\n", -rep.added_volume,
              half_ellipsoid, rep.join_vertices, rep.smooth_steps);
  EXPECT_LT(rep.added_volume, -0.8 * half_ellipsoid);
  EXPECT_GT(rep.added_volume, -1.2 * half_ellipsoid);
  // Hollow 0.3 below the centre, solid 0.7 below (past the pocket's bottom).
  EXPECT_LT(winding(*out, s.plane.centre - 0.3 * s.plane.normal_axis), 0.05);
  EXPECT_GT(winding(*out, s.plane.centre - 0.7 * s.plane.normal_axis), 0.95);
}

TEST(Dig, SilhouetteOutAtTheBackDigsABentTunnel) {
  const Camera cam = front_camera();
  const auto base = circle_px(Vec2(350, 220), 50);
  auto plane = extrusion_reference_plane(sphere(), base, cam);
  ASSERT_TRUE(plane) << plane.message();
  ExtrudeOptions o;
  o.silhouette_camera = side_camera(*plane);
  const double depth = 2.4, lean = 0.8;
  ExtrudeReport rep;
  auto out = extrude_by_strokes(sphere(), base, u_px(*plane, *o.silhouette_camera, depth, lean), cam, o, &rep);
  ASSERT_TRUE(out) << out.message();
  expect_dug(*out, rep, 1);
  EXPECT_LT(rep.added_volume, -0.2);
  // It folds when smoothed at the full join radius; half the radius smooths it.
  EXPECT_GT(rep.smooth_steps, 0);
  std::printf("bent tunnel: removed %.4f, %zu faces, join %d vertices, %d smoothing steps, %d attempt(s)\n",
              -rep.added_volume, out->faces.size(), rep.join_vertices, rep.smooth_steps, rep.boolean_attempts);
  // Along the bent skeleton the hole is open; on the straight line from the base, deep down
  // where the skeleton has moved aside by more than the tunnel's radius, material is left.
  const Vec3 c = plane->centre, n = plane->normal_axis, a = plane->across;
  double half = 0, mid = 0;
  base_extent(*plane, half, mid);
  for (double f : {0.2, 0.4, 0.7}) {
    const Vec3 bent = c + (mid + lean * f * f) * a - f * depth * n;
    ASSERT_LT(bent.norm(), 0.95);
    EXPECT_GT(winding(sphere(), bent), 0.95);
    EXPECT_LT(winding(*out, bent), 0.05) << f;
  }
  const Vec3 straight = c + mid * a - 0.7 * depth * n;
  EXPECT_GT(winding(*out, straight), 0.95);
}

// === Refusals: a message, and the model (a value) untouched.
void expect_refused(const Result<TriMesh>& r, const std::string& words) {
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find(words), std::string::npos) << r.message();
}

TEST(Extrude, RefusesBadBaseStrokes) {
  const TriMesh before = sphere();
  Strokes s = sphere_bump();
  // Misses the model.
  expect_refused(extrude_by_strokes(sphere(), circle_px(Vec2(60, 60), 30), s.silhouette, s.cam, s.options),
                 "misses the model");
  // Partly off the model.
  expect_refused(extrude_by_strokes(sphere(), circle_px(Vec2(320, 240), 200), s.silhouette, s.cam, s.options),
                 "misses the model");
  // Not closed: three quarters of a circle.
  auto arc = circle_px(Vec2(350, 220), 50);
  arc.resize(36);
  expect_refused(extrude_by_strokes(sphere(), arc, s.silhouette, s.cam, s.options), "not closed");
  // Self-crossing: a figure eight.
  std::vector<Vec2> eight;
  for (int i = 0; i < 64; ++i) {
    const double t = 2 * M_PI * i / 64;
    eight.emplace_back(320 + 60 * std::sin(t), 240 + 40 * std::sin(t) * std::cos(t));
  }
  expect_refused(extrude_by_strokes(sphere(), eight, s.silhouette, s.cam, s.options), "crosses itself");
  // Too few points, non-finite.
  expect_refused(extrude_by_strokes(sphere(), {{300, 200}, {310, 200}}, s.silhouette, s.cam, s.options),
                 "at least 3");
  expect_refused(extrude_by_strokes(sphere(), {{300, 200}, {310, NAN}, {300, 210}}, s.silhouette, s.cam, s.options),
                 "not finite");
  EXPECT_EQ(sphere().vertices, before.vertices);
}

TEST(Extrude, RefusesBadSilhouettes) {
  Strokes s = sphere_bump();
  const Camera& sc = *s.options.silhouette_camera;
  auto run = [&](const std::vector<Vec2>& sil) { return extrude_by_strokes(sphere(), s.base, sil, s.cam, s.options); };
  // Degenerate: one repeated point; a straight line along the base (does not rise).
  expect_refused(run({{300, 200}, {300, 200}, {300, 200}}), "degenerate");
  expect_refused(run(bump_px(s.plane, sc, 0.0)), "degenerate");
  // Not starting / ending near the base: the whole bump lifted 0.4 above it.
  expect_refused(run(bump_px(s.plane, sc, 0.5, 0.95, 0.4)), "near the base curve");
  // Ends too close together across the base: a small arch at one side of the loop.
  {
    double half = 0, mid = 0;
    base_extent(s.plane, half, mid);
    std::vector<Vec2> arch;
    for (int i = 0; i <= 20; ++i) {
      const double t = M_PI * i / 20;
      const auto w = sc.project(on_plane(s.plane, mid - 0.9 * half - 0.05 * half * std::cos(t), 0.3 * std::sin(t)));
      arch.emplace_back(w->x(), w->y());
    }
    expect_refused(run(arch), "too close together");
  }
  // Along the surface: a flat arc that runs sideways (its tip beside the ends, barely above).
  {
    double half = 0, mid = 0;
    base_extent(s.plane, half, mid);
    std::vector<Vec2> flat;
    for (int i = 0; i <= 20; ++i) {
      const double t = M_PI * i / 20;
      const auto w = sc.project(on_plane(s.plane, mid - 0.95 * half * std::cos(t) + 0.8 * std::sin(t), 0.01 * std::sin(t)));
      flat.emplace_back(w->x(), w->y());
    }
    expect_refused(run(flat), "runs along the surface");
  }
  // The plane seen edge-on by the base camera (centred stroke: the plane contains the view axis).
  const auto centred = circle_px(Vec2(320, 240), 50);
  auto p = extrusion_reference_plane(sphere(), centred, s.cam);
  ASSERT_TRUE(p);
  ExtrudeOptions edge_on;
  edge_on.silhouette_camera = s.cam;
  edge_on.silhouette_camera->eye = p->centre + 4.0 * p->across;
  edge_on.silhouette_camera->target = p->centre;
  auto r = extrude_by_strokes(sphere(), centred, {{300, 100}, {320, 50}, {340, 100}}, s.cam, edge_on);
  expect_refused(r, "edge-on");
}

}  // namespace
}  // namespace ps
