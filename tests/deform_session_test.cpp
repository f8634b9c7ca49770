// Deformation and stiffness painting inside the sketch session (issue 5 point 6 "the tool in the
// app", point 5 stiffness painting; issue 6 point 6): a handle stroke over the reconstructed model
// and a target stroke on the base plane move the handle region, undo restores the model bit for
// bit, section edits apply the deformation again, and refusals change nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "modeling/deform_tool.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/sketch_session.h"
#include "tests/section_fixtures.h"

namespace ps {
namespace {

using testing::axis_plane;
using testing::circle;
using testing::window_circle;

// Three horizontal slices of the unit sphere (z = -0.6, 0, 0.6), reconstructed by the session
// with the preview's refinement and smoothing: a closed, smooth, capped stack, about 800 vertices.
SketchSession blob() {
  SketchSession s;
  for (double z : {-0.6, 0.0, 0.6}) {
    const Status st = s.add_section(axis_plane(2, z), circle(2, z, std::sqrt(1 - z * z)));
    EXPECT_TRUE(st) << st.message();
  }
  return s;
}

// The handle is drawn looking down -z across the top of the model; the target looking down -y,
// so the base plane fitted to the handle (nearly a plane y = c, containing the first view's
// direction) faces the second view.
constexpr double kLift = 0.3;

Camera look(const Vec3& eye, const Vec3& target, const Vec3& up) { return testing::look_at(eye, target, up, 640, 480); }

Camera handle_camera() { return look(Vec3(0, 0, 9), Vec3::Zero(), Vec3::UnitY()); }
Camera target_camera() { return look(Vec3(0, 9, 0.5), Vec3(0, 0, 0.5), Vec3::UnitZ()); }

std::vector<Vec2> project_all(const Camera& cam, const std::vector<Vec3>& pts) {
  std::vector<Vec2> out;
  for (const auto& p : pts) out.push_back(cam.project(p)->head<2>());
  return out;
}

// A deformation whose target is the surface under `handle_px` moved by `offset`: the handle
// stroke's hits on `model`, moved, seen from `target_cam`.
DeformOp move_op(const TriMesh& model, const Camera& handle_cam, const std::vector<Vec2>& handle_px,
                 const Camera& target_cam, const Vec3& offset, double roi_radius) {
  const MeshRayCaster caster(model);
  std::vector<Vec3> moved = project_stroke(caster, handle_cam, handle_px);
  EXPECT_EQ(moved.size(), handle_px.size()) << "the handle stroke leaves the model";
  for (auto& p : moved) p += offset;
  DeformOp op;
  op.handle_camera = handle_cam;
  op.handle = handle_px;
  op.target_camera = target_cam;
  op.target = project_all(target_cam, moved);
  op.roi.method = VertexSelection::Method::kRadius;
  op.roi.radius = roi_radius;
  return op;
}

// A stroke across the top of the stack (window row 200 of 480, 100 px long), raised by kLift.
std::vector<Vec2> handle_stroke() {
  std::vector<Vec2> px;
  for (int i = 0; i <= 25; ++i) px.emplace_back(270.0 + 4.0 * i, 200.0);
  return px;
}
DeformOp lift_op(const TriMesh& model) {
  return move_op(model, handle_camera(), handle_stroke(), target_camera(), Vec3(0, 0, kLift), 0.1);
}

void expect_solid(const TriMesh& m) {
  const MeshTopology t = mesh_topology(m);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.edge_manifold);
  EXPECT_TRUE(t.vertex_manifold);
  EXPECT_EQ(t.genus, 0);
  const MeshGuarantees g = check_guarantees(m);
  EXPECT_TRUE(g.valid()) << g.problem();
}

// The highest vertex facing the handle camera under the middle of the handle stroke.
double top_under_handle(const TriMesh& m) {
  double z = -1e300;
  for (const auto& v : m.vertices) {
    const auto p = handle_camera().project(v);
    if (v.z() > 0 && p->x() > 270 && p->x() < 370 && std::abs(p->y() - 200) < 12) z = std::max(z, v.z());
  }
  return z;
}

void expect_same_state(const SessionState& a, const SessionState& b) {
  EXPECT_EQ(a.model.vertices, b.model.vertices);
  EXPECT_EQ(a.model.faces, b.model.faces);
  EXPECT_EQ(a.ops.size(), b.ops.size());
  EXPECT_EQ(a.stiffness.size(), b.stiffness.size());
  EXPECT_EQ(a.sections.curves.size(), b.sections.curves.size());
}

TEST(DeformSession, HandleAndTargetStrokesMoveTheHandleRegion) {
  SketchSession s = blob();
  const TriMesh before = s.state().model;
  DeformOpReport report;
  DeformOp op = lift_op(before);
  op.lambda = s.params().lambda;
  auto direct = apply_deform(before, {}, op, &report);
  ASSERT_TRUE(direct) << direct.message();
  ASSERT_TRUE(s.deform(lift_op(before)));
  const TriMesh& after = s.state().model;
  // The session records its own lambda with the operation and gets the same model.
  EXPECT_EQ(after.vertices, direct->vertices);
  ASSERT_EQ(s.state().ops.size(), 1u);
  EXPECT_EQ(std::get<DeformOp>(s.state().ops[0]).lambda, s.params().lambda);
  ASSERT_EQ(after.faces, before.faces);
  expect_solid(after);

  // Handle vertices follow the target: raised by about kLift along z. Along the curve they
  // shift a little: they map to the target by arc length, and the raised curve's length is
  // distributed differently from the surface curve's.
  ASSERT_GT(report.handles.size(), 10u);
  double mean_dz = 0;
  for (int h : report.handles) {
    const Vec3 d = after.vertices[static_cast<std::size_t>(h)] - before.vertices[static_cast<std::size_t>(h)];
    EXPECT_GT(d.z(), 0.5 * kLift) << "handle vertex " << h;
    EXPECT_LT(std::abs(d.x()), 0.35 * kLift) << "handle vertex " << h;
    mean_dz += d.z();
  }
  mean_dz /= static_cast<double>(report.handles.size());
  EXPECT_NEAR(mean_dz, kLift, 0.2 * kLift);
  EXPECT_GT(top_under_handle(after), top_under_handle(before) + 0.5 * kLift);

  // Static vertices (neither ROI nor handle) keep their bits, and every vertex farther than the
  // ROI radius from the handle is static; the ROI moves, but less than the handles do.
  const double radius = 0.1 * bounding_box(before.vertices).diagonal();
  std::set<int> moving(report.roi.begin(), report.roi.end());
  moving.insert(report.handles.begin(), report.handles.end());
  int far = 0;
  for (std::size_t v = 0; v < before.vertices.size(); ++v) {
    double d = 1e300;
    for (int h : report.handles) d = std::min(d, (before.vertices[v] - before.vertices[static_cast<std::size_t>(h)]).norm());
    if (d > radius) {
      EXPECT_FALSE(moving.count(static_cast<int>(v))) << v;
      ++far;
    }
    if (!moving.count(static_cast<int>(v))) {
      EXPECT_EQ(after.vertices[v], before.vertices[v]) << "static vertex " << v;
    }
  }
  EXPECT_GT(far, static_cast<int>(before.vertices.size()) / 2);
  double roi_max = 0, roi_mean = 0;
  for (int v : report.roi) {
    const double d = (after.vertices[static_cast<std::size_t>(v)] - before.vertices[static_cast<std::size_t>(v)]).norm();
    roi_max = std::max(roi_max, d);
    roi_mean += d / static_cast<double>(report.roi.size());
  }
  EXPECT_GT(roi_max, 0.3 * kLift);
  EXPECT_LT(roi_mean, mean_dz);
  EXPECT_LT(roi_max, 1.5 * kLift);

  // Deterministic: the same operation on a fresh session gives the same bits.
  SketchSession again = blob();
  ASSERT_TRUE(again.deform(lift_op(before)));
  EXPECT_EQ(again.state().model.vertices, after.vertices);
}

TEST(DeformSession, LassoAndBrushRegionsOfInterest) {
  SketchSession s = blob();
  const TriMesh rest = s.state().model;
  // A lasso about the handle (any depth inside it is free) and a brush along it.
  DeformOp lasso = lift_op(rest);
  lasso.roi.method = VertexSelection::Method::kLasso;
  lasso.roi.camera = handle_camera();
  lasso.roi.stroke = window_circle(Vec2(320, 200), 80.0, 48);
  DeformOp brush = lift_op(rest);
  brush.roi.method = VertexSelection::Method::kBrush;
  brush.roi.camera = handle_camera();
  brush.roi.radius = 0.1;
  brush.roi.stroke = handle_stroke();
  const std::vector<DeformOp> ops = {lasso, brush};
  for (const DeformOp& op : ops) {
    DeformOpReport report;
    DeformOp o = op;
    o.lambda = 0.5;
    auto out = apply_deform(rest, {}, o, &report);
    ASSERT_TRUE(out) << selection_method_name(op.roi.method) << ": " << out.message();
    expect_solid(*out);
    std::set<int> free(report.roi.begin(), report.roi.end()), handles(report.handles.begin(), report.handles.end());
    for (int h : report.handles) EXPECT_FALSE(free.count(h)) << h;
    for (std::size_t v = 0; v < rest.vertices.size(); ++v) {
      const Vec2 p = handle_camera().project(rest.vertices[v])->head<2>();
      bool selected;
      if (op.roi.method == VertexSelection::Method::kLasso) {
        selected = (p - Vec2(320, 200)).norm() < 79.0;  // inside the 48-gon
      } else {
        double d = 1e300;
        for (int h : report.handles) d = std::min(d, (rest.vertices[v] - rest.vertices[static_cast<std::size_t>(h)]).norm());
        selected = d < 0.05;  // a vertex this close to a handle is within the brush radius of the stroke
      }
      const int i = static_cast<int>(v);
      if (handles.count(i)) continue;
      if (selected) {
        EXPECT_TRUE(free.count(i)) << selection_method_name(op.roi.method) << " " << v;
      }
      if (!free.count(i)) {
        EXPECT_EQ(out->vertices[v], rest.vertices[v]) << v;
      }
    }
    EXPECT_GT(top_under_handle(*out), top_under_handle(rest) + 0.5 * kLift);
  }
  // The session takes the same operation (and records it).
  ASSERT_TRUE(s.deform(lasso));
  EXPECT_EQ(std::get<DeformOp>(s.state().ops[0]).roi.method, VertexSelection::Method::kLasso);
}

TEST(DeformSession, AShadowOnTheProjectionPlaneBendsTheTargetOutOfTheBasePlane) {
  // The projection plane contains the handle's axis and is orthogonal to the base plane (nearly
  // horizontal here), so the view from above faces it. A shadow that is the handle's own window
  // curve pushed down the window (towards -y) by up to 24 px in the middle makes the target a
  // space curve: the middle of the handle moves towards -y as well as up.
  SketchSession s = blob();
  const TriMesh rest = s.state().model;
  DeformOp plain = lift_op(rest);
  plain.lambda = 0.5;
  DeformOp bent = plain;
  bent.shadow_camera = handle_camera();
  const auto n = static_cast<double>(bent.handle.size() - 1);
  for (std::size_t i = 0; i < bent.handle.size(); ++i)
    bent.shadow.push_back(bent.handle[i] + Vec2(0, 24.0 * std::sin(M_PI * static_cast<double>(i) / n)));
  const auto middle_shift = [&](const DeformOp& op) {
    DeformOpReport report;
    auto out = apply_deform(rest, {}, op, &report);
    EXPECT_TRUE(out) << out.message();
    if (!out) return Vec3(Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    expect_solid(*out);
    // Handle vertices whose closest point on the handle curve is in its middle fifth.
    const MeshRayCaster caster(rest);
    auto handle = project_handle_stroke(rest, caster, op.handle_camera, op.handle);
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (std::size_t k = 0; k < handle->vertices.size(); ++k) {
      if (std::abs(handle->parameters[k] - 0.5) > 0.1) continue;
      const auto v = static_cast<std::size_t>(handle->vertices[k]);
      sum += out->vertices[v] - rest.vertices[v];
      ++count;
    }
    EXPECT_GT(count, 2);
    return Vec3(sum / std::max(count, 1));
  };
  const Vec3 flat = middle_shift(plain), curved = middle_shift(bent);
  EXPECT_LT(std::abs(flat.y()), 0.05) << flat.transpose();
  EXPECT_LT(curved.y(), -0.15) << curved.transpose();
  EXPECT_GT(curved.z(), 0.5 * kLift) << curved.transpose();
  // The session keeps the shadow with the operation.
  ASSERT_TRUE(s.deform(bent));
  EXPECT_EQ(std::get<DeformOp>(s.state().ops[0]).shadow.size(), bent.shadow.size());
  // Drawn looking along the projection plane, the shadow is refused.
  DeformOp edge_on = bent;
  edge_on.shadow_camera = target_camera();
  const Status st = SketchSession(blob()).deform(edge_on);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("shadow stroke: the projection plane is seen edge-on"), std::string::npos) << st.message();
}

TEST(DeformSession, UndoRestoresTheModelBitForBitAndRedoReapplies) {
  SketchSession s = blob();
  const SessionState before = s.state();
  ASSERT_TRUE(s.deform(lift_op(before.model)));
  const TriMesh deformed = s.state().model;
  ASSERT_NE(deformed.vertices, before.model.vertices);
  ASSERT_TRUE(s.undo());
  expect_same_state(s.state(), before);
  EXPECT_TRUE(s.state().ops.empty());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.state().model.vertices, deformed.vertices);
}

TEST(DeformSession, SectionEditAppliesTheDeformationAgain) {
  SketchSession s = blob();
  const TriMesh three = s.state().model;
  const DeformOp op = lift_op(three);
  ASSERT_TRUE(s.deform(op));
  const double raised = top_under_handle(s.state().model);
  ASSERT_GT(raised, top_under_handle(three) + 0.5 * kLift);
  // A new section away from the handle (on the far side): the model is rebuilt from four
  // sections and the deformation applied again to the new reconstruction.
  const Status st = s.add_section(axis_plane(2, -0.9), circle(2, -0.9, 0.43));
  ASSERT_TRUE(st) << st.message();
  ASSERT_EQ(s.state().ops.size(), 1u);
  expect_solid(s.state().model);
  // The same as deforming the four-section reconstruction directly, and raised there too.
  SketchSession four = blob();
  ASSERT_TRUE(four.add_section(axis_plane(2, -0.9), circle(2, -0.9, 0.43)));
  const TriMesh rebuilt = four.state().model;
  EXPECT_NE(rebuilt.vertices, three.vertices);
  ASSERT_TRUE(four.deform(op));
  EXPECT_EQ(four.state().model.vertices, s.state().model.vertices);
  EXPECT_GT(top_under_handle(s.state().model), top_under_handle(rebuilt) + 0.5 * kLift);
  // Undo the section: back to the three-section deformed model.
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.state().sections.curves.size(), 3u);
  EXPECT_EQ(top_under_handle(s.state().model), raised);
}

TEST(DeformSession, SectionEditThatBreaksTheDeformationIsRefused) {
  SketchSession s = blob();
  const double top = bounding_box(s.state().model.vertices).max.z();
  // A section high above the stack extends the model upwards; the handle is drawn on that
  // extension, seen from the side, and pulled outwards along x.
  ASSERT_TRUE(s.add_section(axis_plane(2, top + 0.8), circle(2, top + 0.8, 0.5)));
  const double z = top + 0.6;
  ASSERT_GT(bounding_box(s.state().model.vertices).max.z(), z + 0.1);
  const Camera side = look(Vec3(9, 0, z), Vec3(0, 0, z), Vec3::UnitZ());
  const Camera above = look(Vec3(0, 0, z + 9), Vec3(0, 0, z), Vec3::UnitX());
  std::vector<Vec2> px;
  for (int i = 0; i <= 10; ++i) px.push_back(side.project(Vec3(0, -0.2 + 0.04 * i, z))->head<2>());
  const DeformOp op = move_op(s.state().model, side, px, above, Vec3(0.15, 0, 0), 0.05);
  const Status deformed = s.deform(op);
  ASSERT_TRUE(deformed) << deformed.message();
  const SessionState before = s.state();
  // Deleting that section would leave the handle stroke over nothing.
  const Status del = s.delete_section(3);
  ASSERT_FALSE(del);
  EXPECT_NE(del.message().find("operation 1 (deform)"), std::string::npos) << del.message();
  EXPECT_NE(del.message().find("handle stroke"), std::string::npos) << del.message();
  expect_same_state(s.state(), before);
}

TEST(DeformSession, BadInputIsRefusedNamingTheProblemAndChangesNothing) {
  SketchSession s = blob();
  ASSERT_TRUE(s.add_section(axis_plane(2, -0.9), circle(2, -0.9, 0.43)));
  ASSERT_TRUE(s.undo());  // a redo entry, which a refusal must keep too
  const SessionState before = s.state();
  const auto refused = [&](DeformOp op, const std::string& words) {
    const Status st = s.deform(std::move(op));
    ASSERT_FALSE(st) << words;
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    expect_same_state(s.state(), before);
    EXPECT_TRUE(s.can_redo());
  };
  DeformOp op = lift_op(s.state().model);
  op.handle.clear();
  refused(op, "handle stroke has 0 point(s)");
  op = lift_op(s.state().model);
  op.target[3].x() = std::numeric_limits<double>::quiet_NaN();
  refused(op, "target stroke point 3 is not finite");
  op = lift_op(s.state().model);
  for (auto& p : op.handle) p = Vec2(5, 5) + 0.01 * p;  // the top-left corner: off the model
  refused(op, "misses the mesh");
  op = lift_op(s.state().model);
  op.target_camera = op.handle_camera;  // the base plane contains this view's direction
  refused(op, "edge-on");
  op = lift_op(s.state().model);
  op.roi.method = VertexSelection::Method::kLasso;
  op.roi.camera = handle_camera();
  op.roi.stroke = {Vec2(1, 1), Vec2(20, 1), Vec2(20, 20), Vec2(1, 20)};
  refused(op, "region of interest is empty");
  op = lift_op(s.state().model);
  op.roi.radius = -1;
  refused(op, "radius must be a positive");
  op = lift_op(s.state().model);
  op.roi.method = VertexSelection::Method::kBrush;
  op.roi.camera = handle_camera();
  op.roi.stroke = {Vec2(2, 2), Vec2(30, 3)};
  refused(op, "brush stroke misses the model");
  // The handle pushed through the model: the result would intersect itself.
  const double depth = bounding_box(s.state().model.vertices).size().z();
  refused(move_op(s.state().model, handle_camera(), handle_stroke(), target_camera(), Vec3(0, 0, -1.2 * depth), 0.1),
          "intersect itself");

  SketchSession empty;
  const Status none = empty.deform(lift_op(s.state().model));
  ASSERT_FALSE(none);
  EXPECT_NE(none.message().find("no model"), std::string::npos) << none.message();

  const auto refused_paint = [&](const StiffnessOp& p, const std::string& words) {
    const Status st = s.paint_stiffness(p);
    ASSERT_FALSE(st) << words;
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    expect_same_state(s.state(), before);
    EXPECT_TRUE(s.state().stiffness.empty());
  };
  StiffnessOp paint;
  paint.region.method = VertexSelection::Method::kLasso;
  paint.region.camera = handle_camera();
  paint.region.stroke = {Vec2(100, 100), Vec2(540, 100), Vec2(540, 380), Vec2(100, 380)};
  paint.value = 1.5;
  refused_paint(paint, "[0, 1]");
  paint.value = std::numeric_limits<double>::quiet_NaN();
  refused_paint(paint, "[0, 1]");
  paint.value = 1;
  paint.region.method = VertexSelection::Method::kRadius;
  refused_paint(paint, "lasso or a brush");
  paint.region.method = VertexSelection::Method::kLasso;
  paint.region.stroke = {Vec2(1, 1), Vec2(20, 1)};
  refused_paint(paint, "lasso stroke has 2 point(s)");
  paint.region.stroke = {Vec2(1, 1), Vec2(20, 1), Vec2(20, 20)};
  refused_paint(paint, "stiffness region is empty");
}

// Mean relative change of the lengths of the edges with a moved end (and, when `painted` is not
// empty, both ends painted).
double edge_length_change(const TriMesh& a, const TriMesh& b, const std::vector<double>& painted = {}) {
  double sum = 0;
  int n = 0;
  for (const Face& f : a.faces)
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(f[static_cast<std::size_t>(k)]);
      const auto j = static_cast<std::size_t>(f[static_cast<std::size_t>((k + 1) % 3)]);
      if (a.vertices[i] == b.vertices[i] && a.vertices[j] == b.vertices[j]) continue;
      if (!painted.empty() && (std::isnan(painted[i]) || std::isnan(painted[j]))) continue;
      const double la = (a.vertices[i] - a.vertices[j]).norm(), lb = (b.vertices[i] - b.vertices[j]).norm();
      sum += std::abs(lb - la) / la;
      ++n;
    }
  return n ? sum / n : 0.0;
}

TEST(DeformSession, PaintingEverythingIsTheGlobalLambda) {
  // A lasso around the whole model paints every vertex; undo removes the painting.
  StiffnessOp lasso;
  lasso.region.method = VertexSelection::Method::kLasso;
  lasso.region.camera = handle_camera();
  lasso.region.stroke = {Vec2(50, 20), Vec2(590, 20), Vec2(590, 460), Vec2(50, 460)};
  const TriMesh rest = blob().state().model;
  for (double value : {1.0, 0.0}) {
    SketchSession s = blob();
    lasso.value = value;
    ASSERT_TRUE(s.paint_stiffness(lasso));
    ASSERT_EQ(s.state().stiffness.size(), rest.vertices.size());
    for (double k : s.state().stiffness) EXPECT_EQ(k, value);
    EXPECT_EQ(s.state().model.vertices, rest.vertices);  // painting does not move the surface
    ASSERT_TRUE(s.deform(lift_op(rest)));
    expect_solid(s.state().model);
    // The same as the global lambda = value without painting (the session's lambda is 0.5).
    SketchSession global = blob();
    ASSERT_TRUE(global.set_parameter("lambda", value));
    ASSERT_TRUE(global.deform(lift_op(rest)));
    for (std::size_t v = 0; v < rest.vertices.size(); ++v)
      EXPECT_NEAR((s.state().model.vertices[v] - global.state().model.vertices[v]).norm(), 0.0, 1e-9) << v;
    // Undo the deformation, then the painting: the unpainted model.
    ASSERT_TRUE(s.undo());
    EXPECT_EQ(s.state().stiffness.size(), rest.vertices.size());
    ASSERT_TRUE(s.undo());
    EXPECT_TRUE(s.state().stiffness.empty());
    EXPECT_EQ(s.state().model.vertices, rest.vertices);
  }
}

TEST(DeformSession, APatchPaintedStiffKeepsItsShapeBetterThanOnePaintedSoft) {
  // A brush stroke beside the handle, inside the ROI, painted 1 (rigid) or 0 (smooth) with the
  // global lambda at 0.5: the patch's edges change length less when it is stiff.
  const TriMesh rest = blob().state().model;
  StiffnessOp brush;
  brush.region.method = VertexSelection::Method::kBrush;
  brush.region.radius = 0.05;
  brush.region.camera = handle_camera();
  for (int i = 0; i <= 10; ++i) brush.region.stroke.emplace_back(290.0 + 6.0 * i, 215.0);
  double change[2] = {0, 0};
  std::vector<double> painted_field;
  for (int value : {1, 0}) {
    SketchSession s = blob();
    brush.value = value;
    ASSERT_TRUE(s.paint_stiffness(brush));
    int painted = 0;
    for (std::size_t v = 0; v < s.state().stiffness.size(); ++v) {
      const double k = s.state().stiffness[v];
      if (std::isnan(k)) continue;
      EXPECT_EQ(k, value);
      const auto p = handle_camera().project(rest.vertices[v]);
      EXPECT_LT(std::abs(p->y() - 215.0), 60.0) << v;  // near the brush, not all over the model
      ++painted;
    }
    EXPECT_GT(painted, 10);
    EXPECT_LT(painted, static_cast<int>(rest.vertices.size()) / 4);
    ASSERT_TRUE(s.deform(lift_op(rest)));
    expect_solid(s.state().model);
    change[value] = edge_length_change(rest, s.state().model, s.state().stiffness);
    painted_field = s.state().stiffness;
  }
  EXPECT_GT(change[0], 0.0);
  EXPECT_LT(change[1], 0.8 * change[0]) << "patch stiffness 1: " << change[1] << ", stiffness 0: " << change[0];

  // The painting is applied again after a section edit, before the deformation it precedes.
  SketchSession s = blob();
  brush.value = 1;
  ASSERT_TRUE(s.paint_stiffness(brush));
  ASSERT_TRUE(s.deform(lift_op(rest)));
  ASSERT_TRUE(s.add_section(axis_plane(2, -0.9), circle(2, -0.9, 0.43)));
  ASSERT_EQ(s.state().ops.size(), 2u);
  EXPECT_STREQ(session_op_name(s.state().ops[0]), "stiffness");
  EXPECT_STREQ(session_op_name(s.state().ops[1]), "deform");
  ASSERT_EQ(s.state().stiffness.size(), s.state().model.vertices.size());
  int repainted = 0;
  for (double k : s.state().stiffness) repainted += std::isnan(k) ? 0 : 1;
  EXPECT_GT(repainted, 10);
  expect_solid(s.state().model);
}

TEST(DeformSession, StiffnessSurvivesATunnelOnTheKeptVertices) {
  SketchSession s = blob();
  StiffnessOp paint;
  paint.region.method = VertexSelection::Method::kLasso;
  paint.region.camera = handle_camera();
  paint.region.stroke = {Vec2(50, 20), Vec2(590, 20), Vec2(590, 460), Vec2(50, 460)};
  paint.value = 0.25;
  ASSERT_TRUE(s.paint_stiffness(paint));
  const TriMesh before = s.state().model;
  SculptOp tunnel;
  tunnel.kind = SculptOp::Kind::kTunnel;
  tunnel.camera = handle_camera();
  tunnel.stroke = window_circle(Vec2(320, 240), 30.0, 40);
  ASSERT_TRUE(s.sculpt(tunnel));
  const auto& after = s.state();
  ASSERT_EQ(after.stiffness.size(), after.model.vertices.size());
  std::set<std::array<double, 3>> old_positions;
  for (const auto& p : before.vertices) old_positions.insert({p.x(), p.y(), p.z()});
  int kept = 0, added = 0;
  for (std::size_t v = 0; v < after.model.vertices.size(); ++v) {
    const Vec3& p = after.model.vertices[v];
    if (old_positions.count({p.x(), p.y(), p.z()})) {
      EXPECT_EQ(after.stiffness[v], 0.25) << v;
      ++kept;
    } else {
      EXPECT_TRUE(std::isnan(after.stiffness[v])) << v;
      ++added;
    }
  }
  EXPECT_GT(kept, 100);
  EXPECT_GT(added, 0);
}

}  // namespace
}  // namespace ps
