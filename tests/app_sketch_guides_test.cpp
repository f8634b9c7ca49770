// The sketching guides of the selected plane (app/session_scene.h): rule-4 crossing markers and
// the model's cross section drawn semi-transparently, as scene values and as a golden image on
// lavapipe (validation on). Update the golden with scripts/update-goldens.
#include <gtest/gtest.h>

#include <cmath>

#include "app/session_scene.h"
#include "engine/renderer.h"
#include "tests/golden_compare.h"
#include "tests/section_fixtures.h"

namespace ps::app {
namespace {

using testing::axis_plane;
using testing::circle;

// Slices of the unit sphere by z = 0.05, x = 0.1, y = -0.15 (consistent crossings, rule 4).
SessionState blob() {
  SketchSession s;  // improved, as the window shows it
  for (const auto& [axis, offset] : {std::pair{2, 0.05}, std::pair{0, 0.1}, std::pair{1, -0.15}}) {
    const Status st = s.add_section(axis_plane(axis, offset), circle(axis, offset, std::sqrt(1 - offset * offset), 64));
    EXPECT_TRUE(st) << st.message();
  }
  return s.state();
}

// The z plane moved to `z` and selected, in sketch mode.
InputState on_z(double z) {
  InputState in;
  in.planes[2].offset = z;
  in.selected_plane = 2;
  return in;
}

// Nearly straight down on the z plane, as the window turns the view to a selected plane.
Camera top_view(int w, int h) { return testing::look_at(Vec3(0.5, -0.8, 5.0), Vec3::Zero(), Vec3::UnitY(), w, h); }

constexpr engine::Rgba kMarker{0.85f, 0.10f, 0.75f, 1.0f};

bool is_marker(const engine::Rgba& c) { return c.r == kMarker.r && c.g == kMarker.g && c.b == kMarker.b; }

TEST(AppSketchGuides, MarkersAndTheModelSectionInTheScene) {
  const SessionState st = blob();
  const InputState in = on_z(0.4);
  const SketchGuides g = sketch_guides(st, in);
  ASSERT_EQ(g.crossings.size(), 4u);
  for (const auto& h : g.crossings) EXPECT_FALSE(h.met);
  ASSERT_EQ(g.model_section.size(), 1u);
  const Camera cam = top_view(640, 480);
  const engine::Scene plain = session_scene(st, in, cam);
  const engine::Scene with = session_scene(st, in, cam, {}, std::nullopt, &g);
  // Per open crossing a ring and its centre dot; one half-transparent curve for the section.
  ASSERT_EQ(with.strokes.size(), plain.strokes.size() + 2 * 4 + 1);
  std::size_t rings = 0, sections = 0;
  for (const auto& sv : with.strokes) {
    if (is_marker(sv.color)) {
      ASSERT_EQ(sv.points.size(), 16u);
      // A ring facing the camera, around a crossing's place on screen; the outer one 6 px wide.
      Vec2 centre = Vec2::Zero();
      std::vector<Vec2> px;
      for (const Vec3& p : sv.points) px.push_back(cam.project(p)->head<2>());
      for (const Vec2& p : px) centre += p / 16.0;
      double nearest = 1e9;
      for (const auto& h : g.crossings) nearest = std::min(nearest, (cam.project(h.point)->head<2>() - centre).norm());
      EXPECT_LT(nearest, 0.05);
      for (const Vec2& p : px) EXPECT_TRUE(std::abs((p - centre).norm() - 6.0) < 0.05 || std::abs((p - centre).norm() - 1.0) < 0.05);
      ++rings;
    } else if (sv.color.a < 1.0f) {
      EXPECT_TRUE(sv.closed);
      // The section's curve, drawn in front of the model at the same place on screen.
      ASSERT_EQ(sv.points.size(), g.model_section[0].size());
      for (std::size_t i = 0; i < sv.points.size(); ++i)
        EXPECT_LT((cam.project(sv.points[i])->head<2>() - cam.project(g.model_section[0][i])->head<2>()).norm(), 1e-6);
      ++sections;
    }
  }
  EXPECT_EQ(rings, 8u);
  EXPECT_EQ(sections, 1u);
  // On the plane that holds a section every crossing is met: faint rings, no centre dots.
  const SketchGuides met = sketch_guides(st, on_z(0.05));
  ASSERT_EQ(met.crossings.size(), 4u);
  for (const auto& h : met.crossings) EXPECT_TRUE(h.met);
  const engine::Scene faint = session_scene(st, on_z(0.05), cam, {}, std::nullopt, &met);
  std::size_t faint_rings = 0;
  for (const auto& sv : faint.strokes) faint_rings += sv.color.a < 0.5f ? 1u : 0u;
  EXPECT_EQ(faint_rings, 4u);
  // Other tool modes have no guides.
  InputState cut = in;
  cut.mode = "cut";
  const SketchGuides none = sketch_guides(st, cut);
  EXPECT_TRUE(none.crossings.empty());
  EXPECT_TRUE(none.model_section.empty());
}

TEST(AppSketchGuides, RenderedGolden) {
  constexpr int kW = 256, kH = 160;
  engine::RendererOptions o;
  o.width = kW;
  o.height = kH;
  o.validation = true;
  o.prefer_gpu = false;  // goldens are lavapipe's output
  auto r = engine::create_offscreen_renderer(o);
  ASSERT_TRUE(r) << r.message();
  const SessionState st = blob();
  const InputState in = on_z(0.4);
  const SketchGuides g = sketch_guides(st, in);
  const Camera cam = framed_camera(st, top_view(kW, kH), kW, kH);
  auto plain = (*r)->render(session_scene(st, in, cam));
  ASSERT_TRUE(plain) << plain.message();
  auto img = (*r)->render(session_scene(st, in, cam, {}, std::nullopt, &g));
  ASSERT_TRUE(img) << img.message();
  EXPECT_EQ((*r)->validation_messages(), 0u);
  // Every open crossing shows its marker colour on screen (within the lavapipe rounding).
  for (const auto& h : g.crossings) {
    const Vec3 p = *cam.project(h.point);
    const std::uint8_t* px = img->pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
    EXPECT_GT(px[0], 180) << h.point.transpose();
    EXPECT_LT(px[1], 80) << h.point.transpose();
    EXPECT_GT(px[2], 150) << h.point.transpose();
  }
  // The guides change a visible share of the picture (markers and the section curve).
  const engine::ImageDiff d = engine::compare_images(*img, *plain, 8);
  EXPECT_GT(d.differing_pixels, 300u);
  EXPECT_IMAGE_MATCHES_GOLDEN(*img, "sketch_guides");
}

// === Notices: what the driver says about accepted sketch strokes

Stroke pen_stroke(const std::vector<Vec2>& pts, double t0) {
  Stroke st;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    PenSample s;
    s.t = t0 + static_cast<double>(i);
    s.x = pts[i].x();
    s.y = pts[i].y();
    s.pressure = 1.0;
    s.phase = i == 0 ? Phase::kDown : i + 1 == pts.size() ? Phase::kUp : Phase::kMove;
    st.samples.push_back(s);
  }
  return st;
}

TEST(AppSessionNotices, SeparatePartAndOversketchAreNoticedRefusalsStayMessages) {
  SessionParams params;
  params.improve = false;
  SessionDriver d(params);
  LogHeader h;
  h.viewport_width = 640;
  h.viewport_height = 480;
  h.camera = top_view(640, 480);
  d.on_header(h);
  d.on_action(TimedEvent{0, 0, SelectPlane{2}});
  d.on_stroke(pen_stroke(testing::window_circle(Vec2(200, 240), 60, 40), 10));
  EXPECT_TRUE(d.notices().empty());  // the first part is not a separate one
  d.on_stroke(pen_stroke(testing::window_circle(Vec2(460, 240), 60, 40), 100));
  ASSERT_EQ(d.notices().size(), 1u);
  EXPECT_EQ(d.notices()[0].text,
            "section 1 makes a separate part: the model now has 2 parts (a section through the marked crossing points joins them)");
  EXPECT_EQ(d.notices()[0].t, 100);
  // An open stroke over the first circle, from 20 to 70 degrees, bulging out by a quarter.
  std::vector<Vec2> arc;
  for (int i = 0; i <= 30; ++i) {
    const double a = (20 + 50 * i / 30.0) * M_PI / 180, r = 60 * (1 + 0.25 * std::sin(M_PI * i / 30.0));
    arc.push_back(Vec2(200, 240) + r * Vec2(std::cos(a), std::sin(a)));
  }
  d.on_stroke(pen_stroke(arc, 200));
  ASSERT_EQ(d.notices().size(), 2u) << (d.messages().empty() ? "" : d.messages().back().text);
  EXPECT_EQ(d.notices()[1].text, "the stroke oversketched section 0 (the part it runs along was replaced)");
  EXPECT_EQ(d.session().state().sections.curves.size(), 2u);
  // An open stroke over nothing is a refusal (a message), not a notice.
  std::vector<Vec2> away;
  for (int i = 0; i <= 20; ++i) away.emplace_back(20.0 + 10.0 * i, 20.0);
  d.on_stroke(pen_stroke(away, 300));
  EXPECT_EQ(d.notices().size(), 2u);
  ASSERT_FALSE(d.messages().empty());
  EXPECT_EQ(d.messages().back().text.rfind("stroke refused: the stroke is open", 0), 0u) << d.messages().back().text;
}

}  // namespace
}  // namespace ps::app
