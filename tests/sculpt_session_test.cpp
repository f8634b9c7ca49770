// Sculpting inside the sketch session (issue 6 point 7): operations are undoable, kept with the
// session state, applied again when the cross sections change, and a refused operation leaves
// the session exactly as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/sketch_session.h"
#include "tests/section_fixtures.h"

namespace ps {
namespace {

using testing::axis_plane;
using testing::circle;
using testing::window_circle;

Camera front_camera() {
  Camera c;
  c.eye = Vec3(0, 0, 9);
  c.target = Vec3::Zero();
  c.width = 640;
  c.height = 480;
  return c;
}

SketchSession blob() {
  SessionParams params;
  params.improve = false;  // the test is about the operations, not the preview quality
  SketchSession s(params);
  // Slices of the unit sphere by x = 0.1, y = -0.15, z = 0.05: consistent crossings (rule 4)
  // and no point common to all three planes on a curve.
  for (const auto& [axis, offset] : {std::pair{2, 0.05}, std::pair{0, 0.1}, std::pair{1, -0.15}}) {
    const Status st = s.add_section(axis_plane(axis, offset), circle(axis, offset, std::sqrt(1 - offset * offset)));
    EXPECT_TRUE(st) << st.message();
  }
  return s;
}

SculptOp tunnel_op(double radius_px = 30) {
  SculptOp op;
  op.kind = SculptOp::Kind::kTunnel;
  op.camera = front_camera();
  op.stroke = window_circle(Vec2(320, 240), radius_px, 40);
  return op;
}

TEST(SculptSession, TunnelIsUndoableAndSurvivesANewSection) {
  SketchSession s = blob();
  const TriMesh before = s.state().model;
  ASSERT_EQ(mesh_topology(before).genus, 0);
  ASSERT_TRUE(s.sculpt(tunnel_op())) << "tunnel";
  EXPECT_EQ(mesh_topology(s.state().model).genus, 1);
  EXPECT_TRUE(check_guarantees(s.state().model).valid());
  EXPECT_EQ(s.state().ops.size(), 1u);
  // A new section away from the hole: the model is rebuilt and the tunnel applied again.
  ASSERT_TRUE(s.add_section(axis_plane(0, 0.5), circle(0, 0.5, 0.7)));
  EXPECT_EQ(mesh_topology(s.state().model).genus, 1);
  EXPECT_EQ(s.state().ops.size(), 1u);
  // Undo twice: back to the unsculpted model, bit for bit.
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.state().model.vertices, before.vertices);
  EXPECT_EQ(s.state().model.faces, before.faces);
  EXPECT_TRUE(s.state().ops.empty());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(mesh_topology(s.state().model).genus, 1);
}

TEST(SculptSession, CutKeepsTheUnmarkedSide) {
  SketchSession s = blob();
  SculptOp op;
  op.kind = SculptOp::Kind::kCut;
  op.camera = front_camera();
  for (int i = 0; i <= 40; ++i) op.stroke.emplace_back(360.0, 10.0 + 11.5 * i);
  op.side = Vec2(620, 240);
  const Status st = s.sculpt(op);
  ASSERT_TRUE(st) << st.message();
  const MeshTopology t = mesh_topology(s.state().model);
  EXPECT_EQ(t.components, 1);
  for (const auto& v : s.state().model.vertices) {
    const auto p = op.camera.project(v);
    ASSERT_TRUE(p);
    EXPECT_LE(p->x(), 360.0 + 1e-6);
  }
}

TEST(SculptSession, RefusedOperationsChangeNothing) {
  SketchSession empty;
  const auto none = empty.sculpt(tunnel_op());
  ASSERT_FALSE(none);
  EXPECT_NE(none.message().find("no model"), std::string::npos) << none.message();

  SketchSession s = blob();
  const SessionState before = s.state();
  const auto outside = s.sculpt(tunnel_op(400));  // leaves the silhouette
  ASSERT_FALSE(outside);
  EXPECT_NE(outside.message().find("tunnel"), std::string::npos) << outside.message();
  EXPECT_EQ(s.state().model.vertices, before.model.vertices);
  EXPECT_TRUE(s.state().ops.empty());
  EXPECT_TRUE(s.can_undo());  // the three sections' history is intact
}

TEST(SculptSession, ExtrusionAddsAValidBumpAndUndoes) {
  SketchSession s = blob();
  const TriMesh before = s.state().model;
  SculptOp op;
  op.kind = SculptOp::Kind::kExtrude;
  op.camera = front_camera();
  op.stroke = window_circle(Vec2(320, 240), 18.0, 48);
  auto plane = extrusion_reference_plane(before, op.stroke, op.camera);
  ASSERT_TRUE(plane) << plane.message();
  // The silhouette: half an ellipse on the reference plane from one side of the base to the
  // other, drawn under a camera facing the plane.
  Camera side;
  side.eye = plane->centre + 5.0 * plane->plane.normal;
  side.target = plane->centre;
  side.up = plane->normal_axis;
  side.width = 640;
  side.height = 480;
  double lo = 1e300, hi = -1e300;
  for (const auto& q : plane->base_curve) {
    lo = std::min(lo, (q - plane->centre).dot(plane->across));
    hi = std::max(hi, (q - plane->centre).dot(plane->across));
  }
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI * i / 40;
    const Vec3 q = plane->centre + (0.5 * (lo + hi) - 0.47 * (hi - lo) * std::cos(a)) * plane->across +
                   0.4 * std::sin(a) * plane->normal_axis;
    const auto w = side.project(q);
    ASSERT_TRUE(w);
    op.silhouette.emplace_back(w->x(), w->y());
  }
  op.silhouette_camera = side;
  const Status st = s.sculpt(op);
  ASSERT_TRUE(st) << st.message();
  const MeshGuarantees g = check_guarantees(s.state().model);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, mesh_topology(before).genus);
  EXPECT_GT(g.topology.signed_volume, signed_volume(before));
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.state().model.vertices, before.vertices);
}

TEST(SculptSession, DeletingTheLastSectionOfASculptedModelIsRefused) {
  SessionParams params;
  params.improve = false;
  SketchSession s(params);
  ASSERT_TRUE(s.add_section(axis_plane(2, 0.0), circle(2, 0.0, 1.0)));
  ASSERT_TRUE(s.sculpt(tunnel_op(20)));
  const auto st = s.delete_section(0);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("sculpted"), std::string::npos) << st.message();
  EXPECT_EQ(s.state().ops.size(), 1u);
}

}  // namespace
}  // namespace ps
