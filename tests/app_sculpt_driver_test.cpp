// Extrusion through the session driver (issue 6): the base stroke is checked when drawn, the
// pending reference plane follows the extrude_spin / extrude_tilt parameters, the values are
// recorded with the operation, and a turned plane puts the part in the turned direction.
#include <gtest/gtest.h>

#include <cmath>

#include "app/session_driver.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "tests/mesh_fixtures.h"

namespace ps {
namespace {

using testing::front_camera;

struct Driver {
  app::SessionDriver d;
  double t = 0;

  Driver() {
    LogHeader h;
    h.camera = front_camera();
    h.viewport_width = h.camera.width;
    h.viewport_height = h.camera.height;
    d.on_header(h);
    const Status st = d.session().import_base(testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48));
    EXPECT_TRUE(st) << st.message();
  }
  void act(Event e) { d.on_action(TimedEvent{t += 10, 0, std::move(e)}); }
  void stroke(const std::vector<Vec2>& pts) {
    Stroke s;
    for (const auto& p : pts) {
      PenSample q;
      q.t = (t += 5);
      q.x = p.x();
      q.y = p.y();
      q.pressure = 0.5;
      s.samples.push_back(q);
    }
    d.on_stroke(s);
  }
};

std::vector<Vec2> circle_px(const Vec2& c, double r, int n = 48) {
  std::vector<Vec2> s;
  for (int i = 0; i < n; ++i) s.push_back(c + r * Vec2(-std::cos(2 * M_PI * i / n), -std::sin(2 * M_PI * i / n)));
  return s;
}

// A 0.5 high bump on the pending plane, drawn under a camera facing it; the camera is set.
std::vector<Vec2> bump_on(Driver& r, const ExtrudePlane& p, double lean) {
  Camera c = front_camera();
  c.eye = p.centre + 4.0 * p.plane.normal;
  c.target = p.centre;
  c.up = p.normal_axis;
  r.act(CameraChange{c});
  double lo = 1e300, hi = -1e300;
  for (const auto& q : p.base_curve) {
    lo = std::min(lo, (q - p.centre).dot(p.across));
    hi = std::max(hi, (q - p.centre).dot(p.across));
  }
  std::vector<Vec2> px;
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI * i / 40, h = std::sin(a);
    const Vec3 q = p.centre + (0.5 * (lo + hi) - 0.45 * (hi - lo) * std::cos(a) + lean * h * h) * p.across +
                   0.5 * h * p.normal_axis;
    const auto w = c.project(q);
    px.emplace_back(w->x(), w->y());
  }
  return px;
}

TEST(SculptDriver, BaseStrokeOffTheModelIsRefusedWhenDrawn) {
  Driver r;
  r.act(SetToolMode{"extrude"});
  r.stroke(circle_px(Vec2(40, 40), 20));
  ASSERT_EQ(r.d.messages().size(), 1u);
  EXPECT_NE(r.d.messages()[0].text.find("extrude: the base stroke misses the model"), std::string::npos)
      << r.d.messages()[0].text;
  EXPECT_FALSE(r.d.pending_extrusion_plane());
  // The next closed stroke is a base again (not taken as a silhouette).
  r.stroke(circle_px(Vec2(340, 230), 40));
  EXPECT_EQ(r.d.messages().size(), 1u);
  EXPECT_TRUE(r.d.pending_extrusion_plane());
  EXPECT_TRUE(r.d.session().state().ops.empty());
}

TEST(SculptDriver, TurnedPlaneIsRecordedAndPutsThePartInTheTurnedDirection) {
  Driver r;
  const TriMesh before = r.d.session().state().model;
  r.act(SetToolMode{"extrude"});
  r.stroke(circle_px(Vec2(340, 230), 40));
  const auto flat = r.d.pending_extrusion_plane();
  ASSERT_TRUE(flat);
  // The panel's sliders: the pending plane follows them.
  r.act(SetParameter{"extrude_tilt", 0.5});
  r.act(SetParameter{"extrude_spin", -0.4});
  r.act(SetParameter{"extrude_tilt", 1.7});  // refused, 0.5 kept
  ASSERT_EQ(r.d.messages().size(), 1u);
  EXPECT_NE(r.d.messages()[0].text.find("tilt must lie strictly between -90 and 90 degrees"), std::string::npos);
  const auto turned = r.d.pending_extrusion_plane();
  ASSERT_TRUE(turned);
  EXPECT_NEAR(std::acos(turned->normal_axis.dot(turned->region_normal)), 0.5, 1e-9);
  EXPECT_NEAR(turned->region_normal.dot(flat->region_normal), 1.0, 1e-12);
  EXPECT_NEAR(std::acos(std::clamp(turned->across.dot(flat->across), -1.0, 1.0)), 0.4, 1e-9);
  r.stroke(bump_on(r, *turned, 0.0));
  ASSERT_EQ(r.d.messages().size(), 1u) << r.d.messages().back().text;
  EXPECT_FALSE(r.d.pending_extrusion_plane());
  const SessionState st = r.d.session().state();
  ASSERT_EQ(st.ops.size(), 1u);
  const auto& op = std::get<SculptOp>(st.ops[0]);
  EXPECT_EQ(op.kind, SculptOp::Kind::kExtrude);
  EXPECT_EQ(op.spin, -0.4);
  EXPECT_EQ(op.tilt, 0.5);
  const MeshGuarantees g = check_guarantees(st.model);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(mesh_topology(st.model).genus, 0);
  // The new material's (outside the unit sphere) farthest point from the centre lies along the
  // tilted axis, 0.5 out, and not along the untilted one.
  Vec3 far = turned->centre;
  for (const auto& v : st.model.vertices)
    if (v.norm() > 1.0 + 1e-9 && (v - turned->centre).norm() > (far - turned->centre).norm()) far = v;
  EXPECT_NEAR((far - turned->centre).norm(), 0.5, 0.02);
  EXPECT_GT((far - turned->centre).normalized().dot(turned->normal_axis), 0.99);
  EXPECT_LT((far - turned->centre).normalized().dot(turned->region_normal), std::cos(0.4));
  // The parameters changed since do not change the recorded operation: undo, redo restore it.
  r.act(SetParameter{"extrude_tilt", 0.0});
  r.act(Undo{});
  EXPECT_EQ(r.d.session().state().model.vertices, before.vertices);
  r.act(Redo{});
  EXPECT_EQ(r.d.session().state().model.vertices, st.model.vertices);
}

}  // namespace
}  // namespace ps
