// Deformation tool (thesis 3.2.2, 3.3.3): handle projection, reference planes, target curves,
// ROI selection, and the whole chain into the deformer.
#include <gtest/gtest.h>

#include <filesystem>

#include "modeling/deform_tool.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"

using namespace ps;

namespace {
std::string cgal_mesh(const char* name) { return std::string(PLANESKETCH_CGAL_DATA) + "/" + name; }

Camera camera_for(const TriMesh& m) {
  const Box3 b = bounding_box(m.vertices);
  Camera c;
  c.target = b.center();
  c.eye = b.center() + Vec3(0, 0, 2.5 * b.diagonal());
  c.width = 800;
  c.height = 600;
  return c;
}
}  // namespace

TEST(DeformTool, LeastSquaresPlaneRecoversAPlane) {
  const Vec3 n = Vec3(0.3, -0.5, 0.8).normalized();
  Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  std::vector<Vec3> pts;
  for (int i = 0; i < 20; ++i) pts.push_back(Vec3(1, 2, 3) + u * std::cos(i) * 2.0 + v * std::sin(1.7 * i) + n * 0.0);
  auto pl = least_squares_plane(pts);
  ASSERT_TRUE(pl);
  EXPECT_NEAR(std::abs(pl->normal.dot(n)), 1.0, 1e-12);
  for (const auto& p : pts) EXPECT_NEAR(pl->signed_distance(p), 0.0, 1e-12);
  // Symmetric noise off the plane leaves the fit on the plane (Eq. 3.7: through the centroid).
  std::vector<Vec3> noisy;
  for (std::size_t i = 0; i < pts.size(); ++i) noisy.push_back(pts[i] + n * (i % 2 ? 0.01 : -0.01));
  auto pn = least_squares_plane(noisy);
  ASSERT_TRUE(pn);
  EXPECT_NEAR(std::abs(pn->normal.dot(n)), 1.0, 1e-3);
  EXPECT_FALSE(least_squares_plane({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)}));
  EXPECT_FALSE(least_squares_plane({Vec3(0, 0, 0), Vec3(1, 1, 1)}));
}

TEST(DeformTool, ReferencePlanesTurnAboutTheAxisAndStayOrthogonal) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= 10; ++i) pts.emplace_back(i * 0.1, 0.2 * std::sin(i * 0.5), 0.01 * (i % 3));
  for (double angle : {0.0, 0.3, -1.2}) {
    auto rp = reference_planes(pts, angle);
    ASSERT_TRUE(rp);
    EXPECT_NEAR(rp->base.normal.dot(rp->projection.normal), 0.0, 1e-12);
    EXPECT_NEAR(rp->base.normal.dot(rp->axis_direction), 0.0, 1e-12);
    // Both planes contain the axis line.
    for (double s : {0.0, 1.0, 2.5}) {
      const Vec3 p = rp->axis_point + s * rp->axis_direction;
      EXPECT_NEAR(rp->base.signed_distance(p), 0.0, 1e-12);
      EXPECT_NEAR(rp->projection.signed_distance(p), 0.0, 1e-12);
    }
  }
  auto r0 = reference_planes(pts, 0.0), r1 = reference_planes(pts, 0.3);
  EXPECT_NEAR(std::acos(std::clamp(r0->base.normal.dot(r1->base.normal), -1.0, 1.0)), 0.3, 1e-9);
}

TEST(DeformTool, TargetCurveOnTheBasePlaneAndWithAShadow) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= 10; ++i) pts.emplace_back(-0.5 + i * 0.1, 0.0, 0.05 * std::sin(i));
  auto rp = reference_planes(pts);
  ASSERT_TRUE(rp);
  Camera cam;
  cam.eye = Vec3(0.3, 2.0, 3.0);
  cam.target = Vec3(0, 0, 0);
  std::vector<Vec2> stroke;
  for (int i = 0; i < 12; ++i) stroke.emplace_back(300 + 30 * i, 400 - 5 * i);
  auto base = target_curve(cam, *rp, stroke);
  ASSERT_TRUE(base);
  ASSERT_EQ(base->size(), stroke.size());
  for (std::size_t i = 0; i < base->size(); ++i) {
    EXPECT_NEAR(rp->base.signed_distance((*base)[i]), 0.0, 1e-9);
    const auto px = cam.project((*base)[i]);
    EXPECT_NEAR((px->head<2>() - stroke[i]).norm(), 0.0, 1e-6);
  }
  // Shadow: P_i = P_i^b + (P_i^p - proj(P_i^b)); its projection on the projection plane is P^p.
  std::vector<Vec2> shadow;
  for (int i = 0; i < 30; ++i) shadow.emplace_back(310 + 11 * i, 380 - 3 * i);
  auto space = target_curve(cam, *rp, stroke, shadow);
  ASSERT_TRUE(space);
  ASSERT_EQ(space->size(), base->size());
  std::vector<Vec3> shadow3;
  for (const auto& s : shadow) shadow3.push_back(*cam.lift(s.x(), s.y(), rp->projection));
  const auto resampled = resample_by_arc_length(shadow3, static_cast<int>(base->size()));
  for (std::size_t i = 0; i < space->size(); ++i)
    EXPECT_NEAR((rp->projection.project((*space)[i]) - resampled[i]).norm(), 0.0, 1e-9);
}

TEST(DeformTool, HandleStrokeProjectsOntoTheMeshAndDrivesTheDeformer) {
  if (!std::filesystem::exists(cgal_mesh("elephant.off"))) GTEST_SKIP() << "missing elephant.off";
  auto mr = read_mesh(cgal_mesh("elephant.off"));
  ASSERT_TRUE(mr);
  const TriMesh& m = *mr;
  const Camera cam = camera_for(m);
  const MeshRayCaster caster(m);
  // A horizontal stroke through the middle of the view.
  std::vector<Vec2> stroke;
  for (int i = 0; i <= 20; ++i) stroke.emplace_back(360 + 4 * i, 300 + 0.5 * i);
  auto hc = project_handle_stroke(m, caster, cam, stroke);
  ASSERT_TRUE(hc) << hc.message();
  ASSERT_GE(hc->vertices.size(), 3u);
  EXPECT_LT(max_distance_to_surface(m, hc->points), 1e-9 * bounding_box(m.vertices).diagonal());
  EXPECT_TRUE(std::is_sorted(hc->parameters.begin(), hc->parameters.end()));
  // Every handle vertex belongs to a crossed face.
  for (int v : hc->vertices) {
    bool found = false;
    for (int f : hc->faces)
      for (int c : m.faces[static_cast<std::size_t>(f)]) found = found || c == v;
    EXPECT_TRUE(found);
  }
  // Missing the mesh is refused with a reason.
  EXPECT_FALSE(project_handle_stroke(m, caster, cam, {Vec2(1, 1), Vec2(5, 2)}));

  // Planes, a target stroke, ROI by radius, deform: handles land on their targets.
  // The fitted plane of a stroke drawn across the view tends to contain the view direction; turn
  // it about its axis to face the camera, as a user would.
  const Vec3 view = (cam.target - cam.eye).normalized();
  double best_angle = 0.0, best = -1.0;
  for (int k = 0; k < 36; ++k) {
    auto r = reference_planes(hc->points, k * M_PI / 36);
    ASSERT_TRUE(r);
    if (std::abs(r->base.normal.dot(view)) > best) best = std::abs(r->base.normal.dot(view)), best_angle = k * M_PI / 36;
  }
  auto rp = reference_planes(hc->points, best_angle);
  ASSERT_TRUE(rp);
  std::vector<Vec2> target_px;
  for (int i = 0; i <= 20; ++i) target_px.emplace_back(360 + 4 * i, 280 - 0.02 * (i - 10) * (i - 10));
  auto target = target_curve(cam, *rp, target_px);
  ASSERT_TRUE(target) << target.message();
  const auto targets = map_handles_to_target(m, *hc, *target);
  ASSERT_EQ(targets.size(), hc->vertices.size());
  const auto roi = roi_by_radius(m, hc->vertices, 0.15 * bounding_box(m.vertices).diagonal());
  ASSERT_FALSE(roi.empty());
  for (int v : roi) EXPECT_TRUE(std::find(hc->vertices.begin(), hc->vertices.end(), v) == hc->vertices.end());
  EdgeGraphDeformer def;
  ASSERT_TRUE(def.set_mesh(m));
  ASSERT_TRUE(def.set_region(roi, hc->vertices, {}));
  ASSERT_TRUE(def.deform(targets));
  for (std::size_t k = 0; k < targets.size(); ++k) EXPECT_EQ(def.vertices()[static_cast<std::size_t>(hc->vertices[k])], targets[k]);
  // Without offsets the handle vertices land on the target curve itself.
  const auto on_curve = map_handles_to_target(m, *hc, *target, false);
  for (const auto& p : on_curve) EXPECT_NEAR(rp->base.signed_distance(p), 0.0, 1e-9);
}

TEST(DeformTool, LassoAndBrushSelections) {
  if (!std::filesystem::exists(cgal_mesh("elephant.off"))) GTEST_SKIP() << "missing elephant.off";
  auto mr = read_mesh(cgal_mesh("elephant.off"));
  ASSERT_TRUE(mr);
  const TriMesh& m = *mr;
  const Camera cam = camera_for(m);
  // A lasso covering the whole window selects every vertex in front of the camera.
  const std::vector<Vec2> all = {Vec2(-1, -1), Vec2(801, -1), Vec2(801, 601), Vec2(-1, 601)};
  EXPECT_EQ(roi_by_lasso(m, cam, all).size(), m.vertices.size());
  // A small lasso selects exactly the vertices projecting inside its box; reversing it changes nothing.
  std::vector<Vec2> box = {Vec2(350, 250), Vec2(450, 250), Vec2(450, 350), Vec2(350, 350)};
  const auto sel = roi_by_lasso(m, cam, box);
  std::size_t expected = 0;
  for (const auto& v : m.vertices) {
    const auto p = cam.project(v);
    if (p && p->x() > 350 && p->x() < 450 && p->y() > 250 && p->y() < 350) ++expected;
  }
  EXPECT_EQ(sel.size(), expected);
  std::reverse(box.begin(), box.end());
  EXPECT_EQ(roi_by_lasso(m, cam, box), sel);
  // Brush: every selected vertex is within the radius of a brush point, and no other is.
  const MeshRayCaster caster(m);
  std::vector<Vec2> brush_px;
  for (int i = 0; i < 10; ++i) brush_px.emplace_back(380 + 5 * i, 310);
  const auto brush = project_stroke(caster, cam, brush_px);
  ASSERT_FALSE(brush.empty());
  const double r = 0.03 * bounding_box(m.vertices).diagonal();
  const auto bsel = roi_by_brush(m, brush, r);
  ASSERT_FALSE(bsel.empty());
  std::size_t count = 0;
  for (const auto& v : m.vertices) {
    double d = 1e300;
    for (const auto& b : brush) d = std::min(d, (v - b).norm());
    if (d < r) ++count;
  }
  EXPECT_EQ(bsel.size(), count);
}
