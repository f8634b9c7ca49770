// Editing sections with open strokes (modeling/section_oversketch.h): oversketching replaces only
// the overlapped part, a partial stroke is completed from the model's cross section
// (modeling/sketch_guides.h), and the guides shown before drawing: rule-4 crossing points and
// the model's section on the selected plane. Also the session's report of a new separate part.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "modeling/polygon_triangulate.h"
#include "modeling/polyline_crossing.h"
#include "modeling/section_oversketch.h"
#include "modeling/section_validate.h"
#include "modeling/sketch_guides.h"
#include "modeling/sketch_session.h"
#include "tests/mesh_fixtures.h"
#include "tests/section_fixtures.h"

namespace ps {
namespace {

using testing::axis_plane;
using testing::circle;

std::vector<Vec2> circle_2d(double r, int n) {
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n));
  return pts;
}

double angle_of(const Vec2& p) { return std::atan2(p.y(), p.x()); }

bool contains(const std::vector<Vec2>& pts, const Vec2& p) { return std::find(pts.begin(), pts.end(), p) != pts.end(); }

double area(const std::vector<Vec2>& pts) { return 0.5 * signed_area_2d(pts); }

// An arc from angle a0 to a1 (radians) whose radius rises from r_end at the ends to r_mid halfway.
std::vector<Vec2> bulge(double a0, double a1, double r_end, double r_mid, int n) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n, a = a0 + s * (a1 - a0);
    const double r = r_end + (r_mid - r_end) * std::sin(M_PI * s);
    pts.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return pts;
}

TEST(SectionOversketch, ArcOverACircleReplacesOnlyTheOverlappedPart) {
  const auto c = circle_2d(1.0, 64);  // point i at angle 2 pi i / 64: 0.098 rad apart
  const auto stroke = bulge(-0.5, 0.5, 1.01, 1.3, 20);
  // Kept: the points past +-0.5 rad, i.e. 6 .. 58; the three next to each end (6, 7, 8 and
  // 56, 57, 58) take the fading step, the rest keep their bits.
  auto r = splice_open_stroke(c, stroke, 0.05);
  ASSERT_TRUE(r) << r.message();
  EXPECT_FALSE(first_self_crossing(r->curve).has_value()) << "the result must be simple";
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (i >= 9 && i <= 55) {
      EXPECT_TRUE(contains(r->curve, c[i])) << "point " << i << " off the stroke's span changed";
    } else {
      EXPECT_FALSE(contains(r->curve, c[i])) << "point " << i << " next to or under the stroke kept its bits";
    }
  }
  EXPECT_EQ(r->kept_points, 47u);
  // The faded neighbours (points 6, 7, 8 at 0.59 to 0.79 rad, and their mirror images) moved
  // outwards, by at most 0.7 of the end step: 0.8 of the stroke end's distance to the chord
  // under it (0.01 off the circle plus the chord's 0.0012 sagitta).
  std::size_t moved = 0;
  for (const Vec2& p : r->curve) {
    const double a = std::abs(angle_of(p));
    if (a > 0.55 && a < 0.83) {
      EXPECT_GT(p.norm(), 1.0 + 1e-4);
      EXPECT_LT(p.norm() - 1.0, 0.7 * 0.8 * 0.0113);
      ++moved;
    }
  }
  EXPECT_EQ(moved, 6u);
  // Under the stroke the curve follows it: 0.8 of the bulge (radius up to 1.3), and it grew.
  double highest = 0.0;
  for (const Vec2& p : r->curve) {
    if (std::abs(angle_of(p)) < 0.45) {
      EXPECT_GT(p.norm(), 1.0 + 1e-3) << p.transpose();
      highest = std::max(highest, p.norm());
    }
  }
  EXPECT_NEAR(highest, 0.8 * 1.3 + 0.2 * 1.0, 0.01);
  EXPECT_GT(std::abs(area(r->curve)), std::abs(area(c)));
  EXPECT_NEAR(r->replaced_length + r->kept_length, 2 * 64 * std::sin(M_PI / 64), 1e-9);
  EXPECT_LT(r->replaced_length, r->kept_length);
  // Without blending: the stroke itself between the curve points under its ends; every kept
  // point keeps its bits.
  auto plain = splice_open_stroke(c, stroke, 0.05, SpliceBlend{1.0, {}});
  ASSERT_TRUE(plain) << plain.message();
  EXPECT_FALSE(first_self_crossing(plain->curve).has_value());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_EQ(contains(plain->curve, c[i]), i >= 6 && i <= 58) << i;
  for (std::size_t i = 1; i + 1 < stroke.size(); ++i) EXPECT_TRUE(contains(plain->curve, stroke[i])) << i;
  EXPECT_EQ(plain->kept_points, 53u);
}

// A stroke drawn the long way round, just inside the curve, replaces the long part: which part
// goes is the one the stroke runs along, not the shorter one.
TEST(SectionOversketch, StrokeAlongTheLongSideReplacesTheLongSide) {
  const auto c = circle_2d(1.0, 64);
  const auto stroke = bulge(0.5, 2 * M_PI - 0.5, 0.99, 0.8, 60);
  auto r = splice_open_stroke(c, stroke, 0.05);
  ASSERT_TRUE(r) << r.message();
  EXPECT_FALSE(first_self_crossing(r->curve).has_value());
  for (const Vec2& p : c) {
    if (std::abs(angle_of(p)) > 0.5) {
      EXPECT_FALSE(contains(r->curve, p)) << p.transpose();
    }
  }
  EXPECT_TRUE(contains(r->curve, c[0]));  // the middle of the kept part, past the fading
  EXPECT_GT(r->replaced_length, r->kept_length);
  EXPECT_LT(std::abs(area(r->curve)), std::abs(area(c)));
}

TEST(SectionOversketch, RefusalsNameTheReason) {
  const auto c = circle_2d(1.0, 64);
  auto far = splice_open_stroke(c, bulge(-0.5, 0.5, 1.2, 1.4, 20), 0.05);
  ASSERT_FALSE(far);
  EXPECT_NE(far.message().find("too far from the section"), std::string::npos) << far.message();
  auto same = splice_open_stroke(c, bulge(0.0, 0.01, 1.0, 1.5, 4), 0.05);
  ASSERT_FALSE(same);
  EXPECT_NE(same.message().find("same place"), std::string::npos) << same.message();
  // A stroke whose two halves cross: the edited curve would cross itself.
  const std::vector<Vec2> crossing = {{std::cos(-0.3), std::sin(-0.3)}, {1.2, 0.2}, {1.2, -0.2}, {std::cos(0.3), std::sin(0.3)}};
  auto x = splice_open_stroke(c, crossing, 0.05);
  ASSERT_FALSE(x);
  EXPECT_NE(x.message().find("cross itself"), std::string::npos) << x.message();
  EXPECT_FALSE(splice_open_stroke(c, {{1.0, 0.0}}, 0.05));
  EXPECT_FALSE(splice_open_stroke(c, {{1.0, 0.0}, {std::nan(""), 1.0}, {0.0, 1.0}}, 0.05));
  EXPECT_FALSE(splice_open_stroke(c, bulge(-0.5, 0.5, 1.0, 1.3, 10), 0.0));
  EXPECT_FALSE(splice_open_stroke(c, bulge(-0.5, 0.5, 1.0, 1.3, 10), 0.05, SpliceBlend{1.5, {}}));
}

TEST(SectionOversketch, AStrokeOnOneSideOfItsChordIsMirroredAboutIt) {
  std::vector<Vec2> half;  // the upper half of the unit circle, from (1, 0) to (-1, 0)
  for (int i = 0; i <= 32; ++i) half.emplace_back(std::cos(M_PI * i / 32), std::sin(M_PI * i / 32));
  const auto closed = mirror_about_chord(half);
  ASSERT_TRUE(closed.has_value());
  ASSERT_EQ(closed->size(), 64u);  // 33 drawn points and the 31 inner ones mirrored
  EXPECT_FALSE(first_self_crossing(*closed).has_value());
  for (std::size_t i = 1; i < 32; ++i) {
    const Vec2& m = (*closed)[64 - i];  // the image of point i
    EXPECT_NEAR(m.x(), half[i].x(), 1e-15);
    EXPECT_NEAR(m.y(), -half[i].y(), 1e-15);
  }
  EXPECT_NEAR(std::abs(area(*closed)), M_PI, 0.01);
  // Crossing or touching the chord, or straight: nothing to mirror.
  std::vector<Vec2> s_curve = {{0, 0}, {1, 0.5}, {2, -0.5}, {3, 0}};
  EXPECT_FALSE(mirror_about_chord(s_curve).has_value());
  EXPECT_FALSE(mirror_about_chord({{0, 0}, {1, 0}, {2, 0}}).has_value());
  EXPECT_FALSE(mirror_about_chord({{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}}).has_value());
  EXPECT_FALSE(mirror_about_chord({{0, 0}, {2, 0}}).has_value());
}

// === Guides on the selected plane

// Slices of the unit sphere by z = 0.05, x = 0.1, y = -0.15 (consistent crossings, rule 4).
SketchSession blob() {
  SessionParams params;
  params.improve = false;
  SketchSession s(params);
  for (const auto& [axis, offset] : {std::pair{2, 0.05}, std::pair{0, 0.1}, std::pair{1, -0.15}}) {
    const Status st = s.add_section(axis_plane(axis, offset), circle(axis, offset, std::sqrt(1 - offset * offset), 64));
    EXPECT_TRUE(st) << st.message();
  }
  return s;
}

TEST(SketchGuides, CrossingHintsAreOpenOnAFreePlaneAndMetOnASketchedOne) {
  const SketchSession s = blob();
  const auto free_plane = crossing_hints(s.state().sewn, axis_plane(2, 0.4));
  ASSERT_EQ(free_plane.size(), 4u);  // the x and the y curve cross z = 0.4 twice each
  for (const auto& h : free_plane) {
    EXPECT_FALSE(h.met);
    EXPECT_DOUBLE_EQ(h.point.z(), 0.4);
  }
  const auto sketched = crossing_hints(s.state().sewn, axis_plane(2, 0.05));
  ASSERT_EQ(sketched.size(), 4u);
  for (const auto& h : sketched) EXPECT_TRUE(h.met) << h.point.transpose();
  // The same plane with its normal flipped is the same plane.
  const auto flipped = crossing_hints(s.state().sewn, Plane{-Vec3::UnitZ(), -0.05});
  ASSERT_EQ(flipped.size(), 4u);
  for (const auto& h : flipped) EXPECT_TRUE(h.met);
}

TEST(SketchGuides, ModelSectionOfASphere) {
  const TriMesh sphere = testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  auto loops = model_section(sphere, axis_plane(2, 0.3));
  ASSERT_TRUE(loops) << loops.message();
  ASSERT_EQ(loops->size(), 1u);
  EXPECT_GE((*loops)[0].size(), 48u);  // at least one point per face column
  for (const Vec3& p : (*loops)[0]) {
    EXPECT_NEAR(p.z(), 0.3, 1e-9);
    EXPECT_NEAR(p.head<2>().norm(), std::sqrt(1 - 0.09), 0.01);
  }
  auto none = model_section(sphere, axis_plane(2, 2.0));
  ASSERT_TRUE(none) << none.message();
  EXPECT_TRUE(none->empty());
  TriMesh open = sphere;  // without a face the plane cuts
  for (std::size_t f = 0; f < open.faces.size(); ++f) {
    double lo = 1e9, hi = -1e9;
    for (int v : open.faces[f]) {
      lo = std::min(lo, open.vertices[static_cast<std::size_t>(v)].z());
      hi = std::max(hi, open.vertices[static_cast<std::size_t>(v)].z());
    }
    if (lo < 0.3 && hi > 0.3) {
      open.faces.erase(open.faces.begin() + static_cast<std::ptrdiff_t>(f));
      break;
    }
  }
  auto refused = model_section(open, axis_plane(2, 0.3));
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("not closed"), std::string::npos) << refused.message();
  EXPECT_FALSE(model_section(TriMesh{}, axis_plane(2, 0.0)));
  // A plane through a ring of vertices (z = 0 holds the sphere's equator): still one loop.
  auto equator = model_section(sphere, axis_plane(2, 0.0));
  ASSERT_TRUE(equator) << equator.message();
  ASSERT_EQ(equator->size(), 1u);
  for (const Vec3& p : (*equator)[0]) EXPECT_NEAR(p.head<2>().norm(), 1.0, 0.01);
}

// === In the session: window strokes seen from above

Camera top_camera() { return testing::look_at(Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 640, 480); }

std::vector<Vec2> to_window(const Camera& cam, const std::vector<Vec3>& pts) {
  std::vector<Vec2> out;
  for (const Vec3& p : pts) out.push_back(cam.project(p)->head<2>());
  return out;
}

std::vector<Vec3> on_plane_z(const std::vector<Vec2>& pts, double z) {
  std::vector<Vec3> out;
  for (const Vec2& p : pts) out.emplace_back(p.x(), p.y(), z);
  return out;
}

TEST(SessionOversketch, OpenStrokeOverASectionReplacesItsPart) {
  SketchSession s = blob();
  const SessionState before = s.state();
  const Camera cam = top_camera();
  const double r = std::sqrt(1 - 0.05 * 0.05);
  // From 20 to 70 degrees, bulging out by a quarter: between the crossings with the other
  // planes (at about -9, 84, 189 and 276 degrees; the fading reaches 17 degrees past each
  // end), so those stay where they were.
  const auto a0 = 20 * M_PI / 180, a1 = 70 * M_PI / 180;
  const auto stroke = to_window(cam, on_plane_z(bulge(a0, a1, r, 1.25 * r, 40), 0.05));
  StrokeEdit edit;
  const Status st = s.add_window_stroke(stroke, cam, axis_plane(2, 0.05), &edit);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(edit.kind, StrokeEdit::Kind::kOversketch);
  EXPECT_EQ(edit.section, 0);
  ASSERT_EQ(s.state().sections.curves.size(), 3u);
  const auto& edited = s.state().sections.curves[0].points;
  const auto& old = before.sections.curves[0].points;
  for (const Vec3& p : old) {
    const double a = std::atan2(p.y(), p.x());
    const bool under = a > a0 - 0.35 && a < a1 + 0.35;  // the span and the three faded points each side
    const bool found = std::find(edited.begin(), edited.end(), p) != edited.end();
    if (!under) {
      EXPECT_TRUE(found) << "lost " << p.transpose();
    } else if (a > a0 + 0.02 && a < a1 - 0.02) {
      EXPECT_FALSE(found) << "kept under the stroke " << p.transpose();
    }
  }
  EXPECT_EQ(s.state().sections.curves[1].points, before.sections.curves[1].points);
  EXPECT_NE(s.state().model.vertices, before.model.vertices);
  // Undo restores the section and the model bit for bit.
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.state().sections.curves[0].points, old);
  EXPECT_EQ(s.state().model.vertices, before.model.vertices);
}

TEST(SessionOversketch, PartialStrokeIsCompletedFromTheModelsSection) {
  SketchSession s = blob();
  const Camera cam = top_camera();
  const Plane z04 = axis_plane(2, 0.4);
  auto loops = model_section(s.state().model, z04);
  ASSERT_TRUE(loops) << loops.message();
  ASSERT_EQ(loops->size(), 1u);
  const auto& loop = (*loops)[0];
  // A stroke from the computed section's point at 20 degrees to the one at 70, bulging out by
  // 15%: between the crossings with the other planes (about -10 and 84 degrees here), which a
  // new section must keep (rule 4).
  const std::size_t n = loop.size();
  const auto nearest = [&](double deg) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(std::atan2(loop[i].y(), loop[i].x()) - deg * M_PI / 180) <
          std::abs(std::atan2(loop[best].y(), loop[best].x()) - deg * M_PI / 180))
        best = i;
    return best;
  };
  std::size_t i0 = nearest(20), i1 = nearest(70);
  if ((i1 + n - i0) % n > n / 2) std::swap(i0, i1);  // walk forward along the short way
  if (i1 < i0) i1 += n;
  std::vector<Vec3> part;
  for (std::size_t i = i0; i <= i1; ++i) {
    const double s01 = static_cast<double>(i - i0) / static_cast<double>(i1 - i0);
    const Vec3 p = loop[i % n];
    part.push_back(Vec3(p.x() * (1 + 0.15 * std::sin(M_PI * s01)), p.y() * (1 + 0.15 * std::sin(M_PI * s01)), 0.4));
  }
  StrokeEdit edit;
  const Status st = s.add_window_stroke(to_window(cam, part), cam, z04, &edit);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(edit.kind, StrokeEdit::Kind::kCompletion);
  ASSERT_EQ(s.state().sections.curves.size(), 4u);
  EXPECT_EQ(edit.section, 3);
  const auto& curve = s.state().sections.curves[3].points;
  std::vector<Vec2> flat;
  for (const Vec3& p : curve) {
    EXPECT_EQ(p.z(), 0.4);
    flat.push_back(p.head<2>());
  }
  ASSERT_GE(flat.size(), 3u);
  EXPECT_FALSE(first_self_crossing(flat).has_value()) << "the completed curve must be simple";
  // The part away from the stroke is the computed section's.
  std::size_t kept = 0;
  for (std::size_t i = i1 + 4; i + 4 < i0 + n; ++i)  // past the three faded points each side
    kept += std::find(flat.begin(), flat.end(), Vec2(loop[i % n].head<2>())) != flat.end() ? 1u : 0u;
  EXPECT_EQ(kept, n - (i1 - i0) - 8);
  EXPECT_EQ(edit.parts_after, 1);
}

TEST(SessionOversketch, OpenStrokeAwayFromEverythingIsRefusedAndChangesNothing) {
  SketchSession s = blob();
  const SessionState before = s.state();
  const Camera cam = top_camera();
  std::vector<Vec2> far;
  for (int i = 0; i <= 20; ++i) far.emplace_back(20.0 + 10.0 * i, 20.0 + 2.0 * i);  // a corner of the view
  const Status st = s.add_window_stroke(far, cam, axis_plane(2, 0.05));
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("the stroke is open"), std::string::npos) << st.message();
  EXPECT_EQ(s.state().sections.curves.size(), before.sections.curves.size());
  EXPECT_EQ(s.state().model.vertices, before.model.vertices);
  ASSERT_TRUE(s.undo());  // the last add_section, not a phantom edit
  EXPECT_EQ(s.state().sections.curves.size(), 2u);
}

TEST(SessionOversketch, AnArcWithNothingUnderItsEndsIsMirroredIntoASection) {
  SketchSession s = blob();
  const Camera cam = top_camera();
  std::vector<Vec2> arc;  // an arch in the view's top left corner, away from the model
  for (int i = 0; i <= 24; ++i) arc.push_back(Vec2(100, 120) + 50.0 * Vec2(std::cos(M_PI * i / 24), -std::sin(M_PI * i / 24)));
  StrokeEdit edit;
  const Status st = s.add_window_stroke(arc, cam, axis_plane(2, 0.05), &edit);
  ASSERT_TRUE(st) << st.message();
  EXPECT_EQ(edit.kind, StrokeEdit::Kind::kMirrored);
  EXPECT_EQ(edit.section, 3);
  EXPECT_EQ(edit.parts_before, 1);
  const auto& c = s.state().sections.curves[3].points;
  // Symmetric about the chord (window row 120, i.e. one world y): as many points above as below.
  const double chord_y = cam.lift(100, 120, axis_plane(2, 0.05))->y();
  std::size_t above = 0, below = 0;
  for (const Vec3& p : c) {
    above += p.y() > chord_y + 1e-9 ? 1u : 0u;
    below += p.y() < chord_y - 1e-9 ? 1u : 0u;
  }
  EXPECT_GT(above, 5u);
  EXPECT_EQ(above, below);
}

TEST(SessionOversketch, ASectionAwayFromTheModelIsReportedAsASeparatePart) {
  SessionParams params;
  params.improve = false;
  SketchSession s(params);
  const Camera cam = top_camera();
  StrokeEdit first, second;
  ASSERT_TRUE(s.add_window_stroke(testing::window_circle(Vec2(200, 240), 60, 40), cam, axis_plane(2, 0.0), &first));
  EXPECT_EQ(first.kind, StrokeEdit::Kind::kNewSection);
  EXPECT_EQ(first.parts_before, 0);
  EXPECT_EQ(first.parts_after, 1);
  ASSERT_TRUE(s.add_window_stroke(testing::window_circle(Vec2(460, 240), 60, 40), cam, axis_plane(2, 0.0), &second));
  EXPECT_EQ(second.section, 1);
  EXPECT_EQ(second.parts_before, 1);
  EXPECT_EQ(second.parts_after, 2);
}

}  // namespace
}  // namespace ps
