// Topology edits in the sketch session (thesis 6.4): a join stroke drawn in the window over two
// separate parts joins them, a split stroke across a part separates it; undo, the session file
// and refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/session_io.h"
#include "modeling/sketch_session.h"

namespace ps {
namespace {

std::vector<Vec3> circle(double z, double cx, double r, int n, double phase) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n + phase;
    pts.emplace_back(cx + r * std::cos(a), r * std::sin(a), z);
  }
  return pts;
}

Plane z_plane(double z) {
  Plane p;
  p.normal = Vec3::UnitZ();
  p.offset = z;
  return p;
}

// Looking at the two sections from the side (along +y).
Camera side_camera() {
  Camera c;
  c.eye = Vec3(1.0, -8.0, 0.5);
  c.target = Vec3(1.0, 0.0, 0.5);
  c.up = Vec3::UnitZ();
  c.width = 800;
  c.height = 600;
  return c;
}

// A window stroke through the projections of `pts`, densified.
std::vector<Vec2> window_stroke(const Camera& cam, const std::vector<Vec3>& pts) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i)
    for (int k = 0; k < 20; ++k) {
      const Vec3 p = pts[i] + (pts[i + 1] - pts[i]) * (k / 20.0);
      const auto w = cam.project(p);
      out.emplace_back(w->x(), w->y());
    }
  const auto w = cam.project(pts.back());
  out.emplace_back(w->x(), w->y());
  return out;
}

SessionParams fast() {
  SessionParams p;
  p.improve = false;
  return p;
}

int parts(const SketchSession& s) { return mesh_topology(s.state().model).components; }

TEST(SessionTopologyEdit, JoinStrokeJoinsTwoPartsAndUndoes) {
  SketchSession s(fast());
  ASSERT_TRUE(s.add_section(z_plane(0.0), circle(0.0, 0.0, 0.5, 40, 0.37)));
  ASSERT_TRUE(s.add_section(z_plane(1.0), circle(1.0, 2.0, 0.5, 40, 0.91)));
  ASSERT_EQ(parts(s), 2);
  const TriMesh before = s.state().model;
  const Camera cam = side_camera();
  // From the lower part's side to the upper part's side (the front surfaces, y < 0).
  const auto st = s.topology_edit(TopologyEditKind::kJoin, window_stroke(cam, {Vec3(0.0, -0.5, 0.2), Vec3(2.0, -0.5, 0.8)}), cam);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(parts(s), 1);
  EXPECT_TRUE(check_guarantees(s.state().model).valid());
  ASSERT_EQ(s.state().edits.size(), 1u);
  for (const auto& c : s.state().sewn.curves)
    EXPECT_LT(max_distance_to_surface(s.state().model, c.points), 1e-6 * bounding_box(before.vertices).diagonal());

  // The session file keeps the edit, and loading it rebuilds the same model.
  auto file = session_from_json(session_to_json(s.params(), s.state(), ""), "t.json");
  ASSERT_TRUE(file) << file.message();
  SketchSession loaded;
  ASSERT_TRUE(loaded.load(file->params, file->state));
  EXPECT_TRUE(loaded.state().model.vertices == s.state().model.vertices);
  EXPECT_TRUE(loaded.state().model.faces == s.state().model.faces);

  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.state().edits.empty());
  EXPECT_TRUE(s.state().model.vertices == before.vertices);
}

TEST(SessionTopologyEdit, SplitStrokeSeparatesAPart) {
  SketchSession s(fast());
  ASSERT_TRUE(s.add_section(z_plane(0.0), circle(0.0, 0.0, 0.5, 40, 0.37)));
  ASSERT_TRUE(s.add_section(z_plane(1.0), circle(1.0, 0.5, 0.5, 40, 0.91)));
  ASSERT_EQ(parts(s), 1);
  const Camera cam = side_camera();
  const auto st = s.topology_edit(TopologyEditKind::kSplit, window_stroke(cam, {Vec3(-1.5, -0.5, 0.5), Vec3(2.0, -0.5, 0.5)}), cam);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(parts(s), 2);
  EXPECT_TRUE(check_guarantees(s.state().model).valid());
}

TEST(SessionTopologyEdit, RefusalsChangeNothing) {
  SketchSession s(fast());
  const Camera cam = side_camera();
  const auto none = s.topology_edit(TopologyEditKind::kJoin, {Vec2(10, 10), Vec2(20, 20)}, cam);
  ASSERT_FALSE(none);
  EXPECT_NE(none.message().find("no model"), std::string::npos) << none.message();
  ASSERT_TRUE(s.add_section(z_plane(0.0), circle(0.0, 0.0, 0.5, 40, 0.37)));
  ASSERT_TRUE(s.add_section(z_plane(1.0), circle(1.0, 2.0, 0.5, 40, 0.91)));
  const TriMesh before = s.state().model;
  // Off the model (the top-left corner of the window).
  const auto miss = s.topology_edit(TopologyEditKind::kJoin, {Vec2(5, 5), Vec2(30, 8)}, cam);
  ASSERT_FALSE(miss);
  EXPECT_NE(miss.message().find("start and end on the model"), std::string::npos) << miss.message();
  // Both ends on the same part.
  const auto same = s.topology_edit(TopologyEditKind::kJoin, window_stroke(cam, {Vec3(-0.2, -0.5, 0.1), Vec3(0.2, -0.5, 0.3)}), cam);
  ASSERT_FALSE(same);
  EXPECT_NE(same.message().find("same part"), std::string::npos) << same.message();
  EXPECT_TRUE(s.state().edits.empty());
  EXPECT_TRUE(s.state().model.vertices == before.vertices);
  // A bad "edits" entry in a session file names its path.
  SessionState with_edit = s.state();
  with_edit.edits.push_back({TopologyEditKind::kJoin, {Vec3(0, 0, 0.2), Vec3(2, 0, 0.8)}});
  std::string text = session_to_json(s.params(), with_edit, "");
  const auto at = text.find("\"join\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 6, "\"fold\"");
  auto bad = session_from_json(text, "bad.json");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("edits[0]"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace ps
