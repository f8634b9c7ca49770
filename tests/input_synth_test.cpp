// Log synthesis: lift-back exactness, determinism, stroke shape, and the presets' consistency
// with the stroke rules (rule 2 rings, rule 4 crossings on orthogonal planes).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "input/implicit_slice.h"
#include "input/input_state.h"
#include "input/log_presets.h"
#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"

namespace ps {
namespace {

// Presets are cached: slicing them is the slow part of these tests.
const LogPreset& preset(const std::string& name) {
  static std::map<std::string, LogPreset> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    auto p = make_log_preset(name);
    EXPECT_TRUE(p) << p.message();
    it = cache.emplace(name, p ? std::move(*p) : LogPreset{}).first;
  }
  return it->second;
}

// Replays a log the way the app reads input: tracks the camera and planes and lifts every pen
// sample onto the selected plane.
class LiftingSink : public EventSink {
 public:
  InputState state;
  std::vector<std::optional<Vec3>> lifted;  // per event index
  std::vector<Plane> plane_at;              // selected plane per event index
  void on_header(const LogHeader& h) override { state = InputState::from_header(h); }
  void on_pen_sample(const PenSample& s) override {
    lifted.push_back(state.lift(s.x, s.y));
    plane_at.push_back(state.current_plane().value_or(Plane{}));
  }
  void on_action(const TimedEvent& e) override {
    EXPECT_TRUE(state.apply(e.event)) << e.line;
    lifted.emplace_back();
    plane_at.push_back(state.current_plane().value_or(Plane{}));
  }
};

// `log` is res.log itself or the same log read back from text.
void expect_lift_back(const SynthResult& res, const StrokeLog& log, double scale) {
  LiftingSink sink;
  replay(log, sink);
  ASSERT_EQ(sink.lifted.size(), log.events.size());
  std::size_t checked = 0;
  double worst = 0.0;
  for (const SynthStroke& st : res.strokes) {
    const Plane& pl = sink.plane_at[st.events.front()];
    for (std::size_t k = 0; k < st.events.size(); ++k) {
      const auto& p = sink.lifted[st.events[k]];
      ASSERT_TRUE(p) << "stroke sample does not lift onto the selected plane";
      const double err = (*p - st.drawn[k]).norm() / scale;
      worst = std::max(worst, err);
      EXPECT_LE(err, 1e-9) << "step " << st.step << " curve " << st.curve << " sample " << k;
      EXPECT_LE(std::abs(pl.signed_distance(st.drawn[k])), 1e-12 * scale);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000u);
  ::testing::Test::RecordProperty("worst_relative_lift_error", std::to_string(worst));
}

TEST(LogSynth, PresetSamplesLiftBackOntoTheirCurvePoints) {
  for (const std::string& name : log_preset_names()) {
    SCOPED_TRACE(name);
    auto res = synthesize_preset(preset(name), 7);
    ASSERT_TRUE(res) << res.message();
    expect_lift_back(*res, res->log, preset(name).scale);
  }
}

TEST(LogSynth, DrawnPointsStayWithinJitterOfTheSourceCurve) {
  const LogPreset* vase = &preset("vase");
  auto res = synthesize_preset(preset("vase"), 3);
  ASSERT_TRUE(res);
  for (const SynthStroke& st : res->strokes) {
    const auto& curve = vase->steps[st.step].curves[st.curve];
    for (std::size_t i = 0; i < st.drawn.size(); i += 5) {
      const Vec3& p = st.drawn[i];
      double best = 1e300;
      for (std::size_t k = 0; k < curve.size(); ++k) {
        const Vec3 a = curve[k], b = curve[(k + 1) % curve.size()];
        const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        best = std::min(best, (a + t * (b - a) - p).norm());
      }
      EXPECT_LT(best, 0.01 * vase->scale);  // jitter is half a pixel; 1% is ~10 px
    }
  }
}

TEST(LogSynth, SameSeedSameLogOtherSeedOtherLog) {
  auto a = synthesize_preset(preset("figure"), 11), b = synthesize_preset(preset("figure"), 11), c = synthesize_preset(preset("figure"), 12);
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(*to_jsonl(a->log), *to_jsonl(b->log));
  EXPECT_NE(*to_jsonl(a->log), *to_jsonl(c->log));
}

TEST(LogSynth, StrokesLookLikeAPen) {
  auto res = synthesize_preset(preset("vase"), 5);
  ASSERT_TRUE(res);
  const auto strokes = group_strokes(res->log);
  ASSERT_EQ(strokes.size(), res->strokes.size());
  for (const Stroke& s : strokes) {
    EXPECT_TRUE(s.ended_with_up);
    ASSERT_GE(s.samples.size(), 60u);
    double mean_seg = 0.0, peak = 0.0;
    for (std::size_t k = 1; k < s.samples.size(); ++k) {
      EXPECT_NEAR(s.samples[k].t - s.samples[k - 1].t, 5.0, 1e-9);
      mean_seg += std::hypot(s.samples[k].x - s.samples[k - 1].x, s.samples[k].y - s.samples[k - 1].y);
      peak = std::max(peak, s.samples[k].pressure);
      EXPECT_GE(s.samples[k].x, 0.0);
      EXPECT_LE(s.samples[k].x, 1280.0);
      EXPECT_GE(s.samples[k].y, 0.0);
      EXPECT_LE(s.samples[k].y, 800.0);
    }
    mean_seg /= static_cast<double>(s.samples.size() - 1);
    // Closed by the thesis's test: ends closer than 3 mean segment lengths.
    const double gap = std::hypot(s.samples.front().x - s.samples.back().x, s.samples.front().y - s.samples.back().y);
    EXPECT_LT(gap, 3.0 * mean_seg);
    // Pressure rises from the tip-down value and falls back.
    EXPECT_GT(peak, 0.4);
    EXPECT_LT(s.samples.front().pressure, 0.1);
    EXPECT_EQ(s.samples.back().pressure, 0.0);
  }
}

TEST(LogSynth, CameraFacesTheSelectedPlaneBeforeEachStep) {
  auto res = synthesize_preset(preset("figure"), 1);
  ASSERT_TRUE(res);
  InputState st = InputState::from_header(res->log.header);
  bool camera_since_plane_change = true;
  for (const TimedEvent& e : res->log.events) {
    if (std::holds_alternative<SelectPlane>(e.event) || std::holds_alternative<TranslatePlane>(e.event))
      camera_since_plane_change = false;
    if (std::holds_alternative<CameraChange>(e.event)) camera_since_plane_change = true;
    ASSERT_TRUE(st.apply(e.event));
    if (const auto* s = std::get_if<PenSample>(&e.event); s && s->phase == Phase::kDown) {
      EXPECT_TRUE(camera_since_plane_change);
      const Vec3 view = (st.camera.target - st.camera.eye).normalized();
      const double cosang = std::abs(view.dot(st.current_plane()->normal));
      EXPECT_NEAR(cosang, std::cos(15.0 * M_PI / 180.0), 1e-9);
    }
  }
}

TEST(LogSynth, RefusesCurvesOffTheirPlane) {
  SketchStep step{2, 0.5, {{Vec3(0, 0, 0.5), Vec3(1, 0, 0.5), Vec3(0, 1, 0.6)}}};
  auto r = synthesize_log(Camera{}, LogHeader::default_reference_planes(), {step});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("step 0 curve 0 point 2"), std::string::npos) << r.message();
  SketchStep bad_plane{7, 0.0, {}};
  EXPECT_FALSE(synthesize_log(Camera{}, LogHeader::default_reference_planes(), {bad_plane}));
}

// === Presets obey the stroke rules

// Points where the closed polyline crosses plane q.
std::vector<Vec3> crossings(const std::vector<Vec3>& c, const Plane& q) {
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Vec3 a = c[k], b = c[(k + 1) % c.size()];
    const double da = q.signed_distance(a), db = q.signed_distance(b);
    if ((da < 0) != (db < 0)) out.push_back(a + da / (da - db) * (b - a));
  }
  return out;
}

TEST(LogPresets, CurvesOnOrthogonalPlanesCrossTheirCommonLineAtTheSamePoints) {
  for (const std::string& name : log_preset_names()) {
    SCOPED_TRACE(name);
    const LogPreset* p = &preset(name);
    int pairs = 0;
    for (std::size_t i = 0; i < p->steps.size(); ++i)
      for (std::size_t j = i + 1; j < p->steps.size(); ++j) {
        const SketchStep &a = p->steps[i], &b = p->steps[j];
        if (a.plane == b.plane) continue;
        const Plane pa{Vec3::Unit(a.plane), a.offset}, pb{Vec3::Unit(b.plane), b.offset};
        std::vector<Vec3> xa, xb;
        for (const auto& c : a.curves) for (const Vec3& x : crossings(c, pb)) xa.push_back(x);
        for (const auto& c : b.curves) for (const Vec3& x : crossings(c, pa)) xb.push_back(x);
        ASSERT_EQ(xa.size(), xb.size()) << "planes " << i << " and " << j;
        for (const Vec3& x : xa) {
          double best = 1e300;
          for (const Vec3& y : xb) best = std::min(best, (x - y).norm());
          EXPECT_LT(best, 1e-3 * p->scale) << "planes " << i << " and " << j;
        }
        pairs += xa.empty() ? 0 : 1;
      }
    EXPECT_GE(pairs, 8);
  }
}

TEST(LogPresets, VaseHasRingsAndFigureHasSeveralCurvesPerPlane) {
  const LogPreset* vase = &preset("vase");
  int rings = 0;
  for (const SketchStep& s : vase->steps) {
    if (s.plane == 2 && s.curves.size() == 2) {
      ++rings;
      // Rule 2: the second curve lies inside the first (every point of it is inside the solid's
      // outer boundary and encloses the cavity); check by the solid itself.
      Vec3 centroid = Vec3::Zero();
      for (const Vec3& q : s.curves[1]) centroid += q;
      centroid /= static_cast<double>(s.curves[1].size());
      EXPECT_GT(vase->solid(centroid), 0.0);  // the hole: outside the solid
    }
    for (const auto& c : s.curves)
      for (const Vec3& q : c) EXPECT_LT(std::abs(vase->solid(q)), 1e-9);
  }
  EXPECT_EQ(rings, 2);
  const LogPreset* fig = &preset("figure");
  std::vector<std::size_t> counts;
  for (const SketchStep& s : fig->steps) counts.push_back(s.curves.size());
  EXPECT_EQ(counts, (std::vector<std::size_t>{1, 1, 3, 2, 2, 1, 1, 1}));
}

TEST(ImplicitSlice, CircleSliceOfASphereIsExactAndOrdered) {
  // Two concentric spheres make a shell: slicing gives an outer and an inner circle.
  const ScalarField shell = [](const Vec3& p) { return std::max(p.norm() - 1.0, 0.5 - p.norm()); };
  const Plane pl{Vec3(1, 2, 2).normalized(), 0.3};
  auto loops = slice_implicit(shell, pl, SliceWindow{Vec3::Zero(), 1.2, 200});
  ASSERT_TRUE(loops) << loops.message();
  ASSERT_EQ(loops->size(), 2u);
  const double r_out = std::sqrt(1.0 - 0.09), r_in = std::sqrt(0.25 - 0.09);
  const Vec3 c = 0.3 * pl.normal;
  for (const Vec3& q : (*loops)[0]) EXPECT_NEAR((q - c).norm(), r_out, 1e-12);
  for (const Vec3& q : (*loops)[1]) EXPECT_NEAR((q - c).norm(), r_in, 1e-12);
  // Too small a window: refused.
  EXPECT_FALSE(slice_implicit(shell, pl, SliceWindow{Vec3::Zero(), 0.5, 50}));
  // Translating the solid translates the slice (metamorphic).
  const Vec3 d(0.2, -0.1, 0.05);
  const ScalarField moved = [&](const Vec3& p) { return shell(p - d); };
  const Plane pl2{pl.normal, pl.offset + pl.normal.dot(d)};
  auto loops2 = slice_implicit(moved, pl2, SliceWindow{d, 1.2, 200});
  ASSERT_TRUE(loops2);
  ASSERT_EQ(loops2->size(), 2u);
  for (const Vec3& q : (*loops2)[0]) EXPECT_NEAR((q - c - d).norm(), r_out, 1e-12);
}

TEST(LogPresets, CommittedDemoLogsAreTheGeneratedOnes) {
  for (const auto& [name, file] : {std::pair{"vase", "demo.jsonl"}, {"figure", "figure.jsonl"}}) {
    const std::string path = std::string(PLANESKETCH_SOURCE_DIR) + "/assets/logs/" + file;
    std::ifstream in(path, std::ios::binary);
    if (!in) GTEST_SKIP() << path << " is absent";
    std::ostringstream s;
    s << in.rdbuf();
    auto res = synthesize_preset(preset(name));
    ASSERT_TRUE(res);
    // Same events; the text may differ only if a libm rounds differently, so compare parsed values.
    auto committed = parse_stroke_log(s.str(), path);
    ASSERT_TRUE(committed) << committed.message();
    ASSERT_EQ(committed->events.size(), res->log.events.size()) << name;
    for (std::size_t i = 0; i < res->log.events.size(); ++i) {
      const auto* a = std::get_if<PenSample>(&committed->events[i].event);
      const auto* b = std::get_if<PenSample>(&res->log.events[i].event);
      ASSERT_EQ(a == nullptr, b == nullptr) << i;
      if (a) {
        EXPECT_NEAR(a->x, b->x, 1e-6) << i;
        EXPECT_NEAR(a->y, b->y, 1e-6) << i;
        EXPECT_EQ(a->phase, b->phase) << i;
      }
    }
    // Lifting the committed text's samples gives the synthesized 3D points back.
    expect_lift_back(*res, *committed, preset(name).scale);
  }
}

}  // namespace
}  // namespace ps
