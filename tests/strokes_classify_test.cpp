// Stroke recognition (modeling/stroke_classify.h): accuracy on the generated labelled corpus
// (input/stroke_corpus.h) and on the committed logs under assets/logs/strokes/, metamorphic
// invariance, hard cases and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "input/stroke_corpus.h"
#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/stroke_classify.h"

namespace ps {
namespace {

constexpr double kPi = 3.14159265358979323846;
const StrokeClass kClasses[] = {StrokeClass::kClosed, StrokeClass::kScratchOut, StrokeClass::kOpenCutting,
                                StrokeClass::kOpenDeformation, StrokeClass::kOpenMiss};

InsideModelFn polygon_test(const std::vector<Vec2>& poly) {
  return [poly](const Vec2& p) { return point_in_polygon_2d(p, poly); };
}

struct Tally {
  std::map<StrokeClass, int> total, right;
  std::map<std::string, std::pair<int, int>> by_kind;  // right, total
  std::map<std::pair<StrokeClass, StrokeClass>, int> confusion;
  std::vector<std::string> failures;
  void add(const LabelledStroke& ls, const StrokeClassification& c) {
    const bool ok = c.cls == ls.label;
    ++total[ls.label];
    right[ls.label] += ok ? 1 : 0;
    auto& k = by_kind[std::string(stroke_class_name(ls.label)) + "/" + ls.kind];
    k.first += ok ? 1 : 0;
    ++k.second;
    ++confusion[{ls.label, c.cls}];
    if (!ok && failures.size() < 40)
      failures.push_back(std::string(stroke_class_name(ls.label)) + "/" + ls.kind + " -> " + c.reason +
                         " [rev " + std::to_string(c.features.reversals) + ", maxturn " +
                         std::to_string(c.features.max_turn_deg) + ", overdraw " + std::to_string(c.features.overdraw) +
                         ", diag " + std::to_string(c.features.bbox_diagonal_px) + ", area " +
                         std::to_string(c.features.closed_area_ratio) + ", simple " +
                         std::to_string(c.features.closed_simple) + "]");
  }
  double overall() const {
    int r = 0, t = 0;
    for (const auto& [c, n] : total) t += n, r += right.at(c);
    return t ? static_cast<double>(r) / t : 0.0;
  }
  double of(StrokeClass c) const {
    const auto it = total.find(c);
    return it == total.end() || it->second == 0 ? 1.0 : static_cast<double>(right.at(c)) / it->second;
  }
  std::string report() const {
    std::ostringstream o;
    char buf[160];
    for (const auto& [c, n] : total) {
      std::snprintf(buf, sizeof buf, "  %-17s %4d/%-4d %.1f%%\n", std::string(stroke_class_name(c)).c_str(), right.at(c),
                    n, 100.0 * of(c));
      o << buf;
    }
    std::snprintf(buf, sizeof buf, "  overall           %.2f%%\n", 100.0 * overall());
    o << buf << "  by kind:";
    for (const auto& [k, v] : by_kind) o << " " << k << " " << v.first << "/" << v.second << ";";
    o << "\n  confusion (label -> got):";
    for (const auto& [k, n] : confusion)
      if (k.first != k.second) o << " " << stroke_class_name(k.first) << "->" << stroke_class_name(k.second) << " " << n << ";";
    o << "\n";
    for (const auto& f : failures) o << "  miss: " << f << "\n";
    return o.str();
  }
};

Tally run_corpus(const StrokeCorpusOptions& opt) {
  const auto sil = corpus_silhouettes(opt.width, opt.height);
  const auto corpus = make_stroke_corpus(opt);
  Tally t;
  for (const auto& ls : corpus) {
    auto c = classify_stroke(stroke_positions(ls.samples), polygon_test(sil[ls.silhouette].outline));
    EXPECT_TRUE(c) << c.message();
    if (c) t.add(ls, *c);
  }
  return t;
}

TEST(StrokeClassify, GeneratedCorpusTablet) {
  StrokeCorpusOptions opt;  // 150 per class, 200 Hz, 80-2500 px/s, jitter up to 1.5 px
  const Tally t = run_corpus(opt);
  const std::string rep = t.report();
  std::printf("generated corpus, 200 Hz tablet:\n%s", rep.c_str());
  int n = 0;
  for (const auto& [c, k] : t.total) n += k;
  EXPECT_GE(n, 400);
  EXPECT_GE(t.overall(), 0.95) << rep;
  for (StrokeClass c : {StrokeClass::kClosed, StrokeClass::kScratchOut, StrokeClass::kOpenCutting,
                        StrokeClass::kOpenDeformation})
    EXPECT_GE(t.of(c), 0.90) << stroke_class_name(c) << "\n" << rep;
}

TEST(StrokeClassify, GeneratedCorpusMouseRateAndMoreJitter) {
  StrokeCorpusOptions opt;
  opt.seed = 77;
  opt.per_class = 100;
  opt.sample_interval_ms = 16.0;  // 60 Hz pointer
  opt.max_jitter_px = 2.0;
  opt.hard_fraction = 0.5;
  const Tally t = run_corpus(opt);
  const std::string rep = t.report();
  std::printf("generated corpus, 60 Hz, jitter 2 px, half hard cases:\n%s", rep.c_str());
  EXPECT_GE(t.overall(), 0.95) << rep;
}

// === Metamorphic: moving, scaling, rotating or reversing a stroke together with the model
// does not change its class.
TEST(StrokeClassify, MetamorphicTransformsKeepTheClass) {
  StrokeCorpusOptions opt;
  opt.seed = 5;
  opt.per_class = 40;
  const auto sil = corpus_silhouettes();
  const auto corpus = make_stroke_corpus(opt);
  struct Xf {
    std::string name;
    double scale, angle;
    Vec2 shift;
    bool reverse;
  };
  const Xf xfs[] = {{"translate", 1.0, 0.0, Vec2(137.25, -61.5), false}, {"rotate 90", 1.0, kPi / 2, Vec2::Zero(), false},
                    {"rotate 33", 1.0, 33 * kPi / 180, Vec2::Zero(), false}, {"scale 0.6", 0.6, 0.0, Vec2::Zero(), false},
                    {"scale 1.7", 1.7, 0.0, Vec2::Zero(), false}, {"reverse", 1.0, 0.0, Vec2::Zero(), true},
                    {"all", 1.3, -1.1, Vec2(20, 40), true}};
  const Vec2 centre(640, 400);
  for (const Xf& x : xfs) {
    const double c = std::cos(x.angle), s = std::sin(x.angle);
    auto fwd = [&](const Vec2& p) {
      const Vec2 q = p - centre;
      return Vec2(centre.x() + x.shift.x() + x.scale * (c * q.x() - s * q.y()),
                  centre.y() + x.shift.y() + x.scale * (s * q.x() + c * q.y()));
    };
    int same = 0, n = 0;
    std::vector<std::string> diffs;
    for (const auto& ls : corpus) {
      const auto pts = stroke_positions(ls.samples);
      std::vector<Vec2> moved;
      for (const Vec2& p : pts) moved.push_back(fwd(p));
      if (x.reverse) std::reverse(moved.begin(), moved.end());
      std::vector<Vec2> poly;
      for (const Vec2& p : sil[ls.silhouette].outline) poly.push_back(fwd(p));
      auto a = classify_stroke(pts, polygon_test(sil[ls.silhouette].outline));
      auto b = classify_stroke(moved, polygon_test(poly));
      ASSERT_TRUE(a && b);
      ++n;
      if (a->cls == b->cls) ++same;
      else if (diffs.size() < 10) diffs.push_back(ls.kind + ": " + a->reason + "  VS  " + b->reason);
    }
    std::string d;
    for (const auto& s2 : diffs) d += "\n  " + s2;
    std::printf("metamorphic %-10s %d/%d same class%s\n", x.name.c_str(), same, n, d.c_str());
    // Translation, rotation and reversal are exact symmetries of the rules; scaling changes how
    // the pixel thresholds (15 px filter, 8 px legs) compare with the stroke, so a stroke on a
    // threshold may flip.
    const bool exact = x.scale == 1.0 && !x.reverse && x.angle == 0.0;
    if (exact) EXPECT_EQ(same, n) << x.name << d;
    else EXPECT_GE(same, n * 97 / 100) << x.name << d;
  }
}

// === Hard cases built by hand
std::vector<Vec2> sample_path(const std::function<Vec2(double)>& f, int n) {
  std::vector<Vec2> p;
  for (int k = 0; k <= n; ++k) p.push_back(f(static_cast<double>(k) / n));
  return p;
}

const std::vector<Vec2>& disc() {
  static const std::vector<Vec2> d = corpus_silhouettes()[0].outline;  // centre (640, 400), r 264
  return d;
}

StrokeClass cls(const std::vector<Vec2>& pts, const InsideModelFn& in = polygon_test(disc())) {
  auto c = classify_stroke(pts, in);
  EXPECT_TRUE(c) << c.message();
  return c ? c->cls : StrokeClass::kOpenMiss;
}

TEST(StrokeClassify, SlowClosedLoopWithAGapIsClosed) {
  // 1 px apart (a slow pen), ending 25 px short of the start.
  const double r = 100, gap = 25.0 / r;
  const auto pts = sample_path([&](double t) { return Vec2(640 + r * std::cos(t * (2 * kPi - gap)), 400 + r * std::sin(t * (2 * kPi - gap))); }, 600);
  auto c = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->cls, StrokeClass::kClosed) << c->reason;
  EXPECT_NEAR(c->features.end_gap_px, 25.0, 0.5);
}

TEST(StrokeClassify, ZigZagWithTwoReversalsIsOpen) {
  const std::vector<Vec2> corners = {{560, 350}, {720, 370}, {560, 390}, {720, 410}};
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i + 1 < corners.size(); ++i)
    for (int k = 0; k < 40; ++k) pts.push_back(corners[i] + (k / 40.0) * (corners[i + 1] - corners[i]));
  pts.push_back(corners.back());
  auto c = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->features.reversals, 2);
  EXPECT_EQ(c->cls, StrokeClass::kOpenDeformation) << c->reason;
  // One more leg: three reversals, a scratch-out.
  for (int k = 1; k <= 40; ++k) pts.push_back(corners.back() + (k / 40.0) * Vec2(-160, 20));
  auto d = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->cls, StrokeClass::kScratchOut) << d->reason;
}

TEST(StrokeClassify, LongWavyStrokeIsOpen) {
  const auto pts = sample_path([](double t) { return Vec2(450 + 380 * t, 400 + 25 * std::sin(2 * kPi * 6 * t)); }, 800);
  auto c = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->features.reversals, 0);
  EXPECT_EQ(c->cls, StrokeClass::kOpenDeformation) << c->reason;
}

TEST(StrokeClassify, CuttingStrokeEndingJustOutside) {
  // The disc spans x in [376, 904] on y = 400; ends 3 px outside on both sides.
  const auto pts = sample_path([](double t) { return Vec2(373 + (907.5 - 373) * t, 400 + 30 * std::sin(kPi * t)); }, 300);
  auto c = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->cls, StrokeClass::kOpenCutting) << c->reason;
  EXPECT_EQ(c->features.silhouette_crossings, 2);
  // Stopping 3 px before the outline: it starts outside and ends on the model: deformation.
  const auto short_pts = sample_path([](double t) { return Vec2(373 + (901 - 373) * t, 400); }, 300);
  EXPECT_EQ(cls(short_pts), StrokeClass::kOpenDeformation);
}

TEST(StrokeClassify, CuttingAcrossAConcavityCrossesFourTimes) {
  const auto sil = corpus_silhouettes()[2];  // three lobes: a horizontal line through y = 400 - 120
  const auto pts = sample_path([](double t) { return Vec2(100 + 1080 * t, 250); }, 1000);
  auto c = classify_stroke(pts, polygon_test(sil.outline));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->cls, StrokeClass::kOpenCutting) << c->reason;
  EXPECT_GE(c->features.silhouette_crossings, 2);
}

TEST(StrokeClassify, StarOutlineIsClosedNotScratchOut) {
  std::vector<Vec2> star;
  for (int k = 0; k <= 10; ++k) {
    const double r = (k % 2 == 0) ? 150 : 75, a = -kPi / 2 + k * kPi / 5;
    star.emplace_back(640 + r * std::cos(a), 400 + r * std::sin(a));
  }
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i + 1 < star.size(); ++i)
    for (int k = 0; k < 30; ++k) pts.push_back(star[i] + (k / 30.0) * (star[i + 1] - star[i]));
  pts.push_back(star.back());
  auto c = classify_stroke(pts, polygon_test(disc()));
  ASSERT_TRUE(c);
  EXPECT_GE(c->features.reversals, 3);
  EXPECT_EQ(c->cls, StrokeClass::kClosed) << c->reason;
}

TEST(StrokeClassify, ScratchOutThatEndsWhereItStarted) {
  // Four legs back and forth on one line: the ends meet, but it encloses nothing.
  std::vector<Vec2> pts;
  for (int leg = 0; leg < 4; ++leg)
    for (int k = 0; k < 60; ++k) {
      const double x = (leg % 2 == 0) ? 600 + k : 660 - k;
      pts.emplace_back(x, 400 + 2 * leg + 0.5 * (k % 2));
    }
  EXPECT_EQ(cls(pts), StrokeClass::kScratchOut);
}

TEST(StrokeClassify, StrokeMissingTheModelOrWithoutAModel) {
  const auto pts = sample_path([](double t) { return Vec2(20 + 200 * t, 30 + 10 * t); }, 100);
  EXPECT_EQ(cls(pts), StrokeClass::kOpenMiss);
  const auto on = sample_path([](double t) { return Vec2(600 + 80 * t, 400); }, 100);
  EXPECT_EQ(cls(on, InsideModelFn{}), StrokeClass::kOpenMiss);
  // Closed and scratch-out do not need the model.
  const auto loop = sample_path([](double t) { return Vec2(60 + 40 * std::cos(2 * kPi * t), 60 + 40 * std::sin(2 * kPi * t)); }, 200);
  EXPECT_EQ(cls(loop, InsideModelFn{}), StrokeClass::kClosed);
}

// === Bad input: a clear error, never a crash
TEST(StrokeClassify, BadInputIsRefusedWithAMessage) {
  const auto in = polygon_test(disc());
  auto e = classify_stroke({}, in);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.message(), "stroke is empty");
  auto one = classify_stroke({Vec2(1, 2)}, in);
  ASSERT_FALSE(one);
  EXPECT_NE(one.message().find("only 1 sample"), std::string::npos) << one.message();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto n = classify_stroke({Vec2(1, 2), Vec2(nan, 3), Vec2(50, 50)}, in);
  ASSERT_FALSE(n);
  EXPECT_NE(n.message().find("sample 1 is not finite"), std::string::npos) << n.message();
  auto inf = classify_stroke({Vec2(1, 2), Vec2(3, std::numeric_limits<double>::infinity())}, in);
  ASSERT_FALSE(inf);
  auto same = classify_stroke({Vec2(5, 5), Vec2(5, 5), Vec2(5, 5)}, in);
  ASSERT_FALSE(same);
  EXPECT_NE(same.message().find("too short"), std::string::npos) << same.message();
  auto tiny = classify_stroke({Vec2(5, 5), Vec2(9, 5)}, in);
  ASSERT_FALSE(tiny);
  // Two samples far apart: a straight open stroke, fine.
  auto two = classify_stroke({Vec2(600, 400), Vec2(700, 400)}, in);
  ASSERT_TRUE(two) << two.message();
  EXPECT_EQ(two->cls, StrokeClass::kOpenDeformation);
  // Huge coordinates stay finite in the features.
  auto big = classify_stroke({Vec2(-1e12, 0), Vec2(1e12, 1), Vec2(0, 1e12)}, [](const Vec2&) { return false; });
  ASSERT_TRUE(big) << big.message();
  StrokeClassifyParams bad;
  bad.silhouette_step_px = 0;
  EXPECT_FALSE(classify_stroke({Vec2(600, 400), Vec2(700, 400)}, in, bad));
  StrokeClassifyParams nan_leg;
  nan_leg.min_leg_px = nan;
  auto p = classify_stroke({Vec2(600, 400), Vec2(700, 400)}, in, nan_leg);
  ASSERT_FALSE(p);
  EXPECT_NE(p.message().find("parameters invalid"), std::string::npos) << p.message();
}

TEST(StrokeClassify, ClassNamesRoundTrip) {
  for (StrokeClass c : kClasses) {
    StrokeClass back = StrokeClass::kOpenMiss;
    ASSERT_TRUE(parse_stroke_class(stroke_class_name(c), back));
    EXPECT_EQ(back, c);
  }
  StrokeClass x;
  EXPECT_FALSE(parse_stroke_class("lasso", x));
}

// === Committed stroke logs with labels (assets/logs/strokes/*.jsonl + *.labels.json)
struct AssetLog {
  std::string name;
  std::size_t silhouette;
  StrokeCorpusOptions opt;
};
std::vector<AssetLog> asset_logs() {
  std::vector<AssetLog> out;
  StrokeCorpusOptions tablet;
  tablet.seed = 1001;
  tablet.per_class = 12;  // 4 per class over each of the 3 silhouettes
  tablet.hard_fraction = 0.4;
  tablet.sample_interval_ms = 8.0;  // 125 Hz keeps the files small
  tablet.min_speed_px_s = 150.0;
  StrokeCorpusOptions mouse = tablet;
  mouse.seed = 1002;
  mouse.sample_interval_ms = 16.0;
  mouse.max_jitter_px = 2.0;
  out.push_back({"disc-tablet", 0, tablet});
  out.push_back({"ellipse-mouse", 1, mouse});
  out.push_back({"blob-tablet", 2, tablet});
  return out;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path asset_dir() { return std::filesystem::path(PLANESKETCH_SOURCE_DIR) / "assets" / "logs" / "strokes"; }

// The committed files are the generator's output; PLANESKETCH_WRITE_STROKE_LOGS=1 rewrites them.
TEST(StrokeClassifyLogs, CommittedLogsMatchTheGenerator) {
  const bool write = std::getenv("PLANESKETCH_WRITE_STROKE_LOGS") != nullptr;
  const auto sil = corpus_silhouettes();
  for (const AssetLog& a : asset_logs()) {
    std::vector<LabelledStroke> mine;
    for (auto& ls : make_stroke_corpus(a.opt))
      if (ls.silhouette == a.silhouette) mine.push_back(std::move(ls));
    const std::string gen = "tests/strokes_classify_test.cpp (" + a.name + ", seed " + std::to_string(a.opt.seed) + ")";
    StrokeLog log = corpus_log(mine, 1280, 800, gen);
    if (a.opt.sample_interval_ms > 10.0)
      for (auto& e : log.events)
        if (auto* s = std::get_if<PenSample>(&e.event)) s->tool = Tool::kMouse, s->tilt_x = s->tilt_y = 0.0;
    auto text = to_jsonl(log);
    ASSERT_TRUE(text) << text.message();
    StrokeLabels labels;
    labels.silhouette = sil[a.silhouette].outline;
    for (auto& p : labels.silhouette) p = Vec2(std::round(4 * p.x()) / 4, std::round(4 * p.y()) / 4);
    for (const auto& ls : mine) labels.labels.push_back(ls.label);
    const auto jl = asset_dir() / (a.name + ".jsonl"), lj = asset_dir() / (a.name + ".labels.json");
    if (write) {
      std::filesystem::create_directories(asset_dir());
      std::ofstream(jl, std::ios::binary) << *text;
      std::ofstream(lj, std::ios::binary) << format_stroke_labels(labels);
    }
    EXPECT_EQ(slurp(jl), *text) << jl << " differs from the generator; rerun with PLANESKETCH_WRITE_STROKE_LOGS=1";
    EXPECT_EQ(slurp(lj), format_stroke_labels(labels)) << lj;
  }
}

TEST(StrokeClassifyLogs, LabelledLogsAreRecognised) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(asset_dir(), ec))
    if (e.path().extension() == ".jsonl") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty()) << "no " << asset_dir() << "/*.jsonl";
  Tally all;
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    std::vector<std::string> warnings;
    auto log = read_stroke_log(f.string(), &warnings);
    ASSERT_TRUE(log) << log.message();
    EXPECT_TRUE(warnings.empty());
    auto path = f;
    path.replace_extension(".labels.json");
    auto labels = parse_stroke_labels(slurp(path), path.string());
    ASSERT_TRUE(labels) << labels.message();
    const auto strokes = group_strokes(*log);
    ASSERT_EQ(strokes.size(), labels->labels.size());
    const auto in = polygon_test(labels->silhouette);
    for (std::size_t i = 0; i < strokes.size(); ++i) {
      LabelledStroke ls;
      ls.label = labels->labels[i];
      ls.kind = f.stem().string();
      auto c = classify_stroke(stroke_positions(strokes[i].samples), in);
      ASSERT_TRUE(c) << "stroke " << i << ": " << c.message();
      all.add(ls, *c);
    }
  }
  const std::string rep = all.report();
  std::printf("committed logs:\n%s", rep.c_str());
  EXPECT_GE(all.overall(), 0.95) << rep;
}

TEST(StrokeClassifyLogs, BadLabelFilesAreRefused) {
  EXPECT_FALSE(parse_stroke_labels("", "x"));
  EXPECT_FALSE(parse_stroke_labels("[]", "x"));
  EXPECT_FALSE(parse_stroke_labels(R"({"silhouette":[[0,0],[1,0]],"labels":[]})", "x"));
  auto u = parse_stroke_labels(R"({"silhouette":[[0,0],[1,0],[0,1]],"labels":["lasso"]})", "x");
  ASSERT_FALSE(u);
  EXPECT_NE(u.message().find("unknown label"), std::string::npos);
  EXPECT_TRUE(parse_stroke_labels(R"({"silhouette":[[0,0],[1,0],[0,1]],"labels":["closed"]})", "x"));
}

}  // namespace
}  // namespace ps
