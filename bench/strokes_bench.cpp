// Stroke preprocessing, self-crossing and curve sewing timings (figures in bench/results/strokes.md).
// Run: build/release/bench/strokes_bench --benchmark_repetitions=7 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "input/stroke_corpus.h"
#include "modeling/curve_sewing.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/stroke_classify.h"
#include "modeling/polyline_crossing.h"
#include "modeling/stroke_preprocess.h"

using namespace ps;

namespace {

// A 500-sample hand-drawn-like closed stroke (a wobbly circle of radius 200 px, ~2.5 px steps).
std::vector<Vec2> stroke(int samples) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  std::vector<Vec2> pts;
  for (int i = 0; i < samples; ++i) {
    const double t = 0.2 + 2 * M_PI * 0.97 * i / (samples - 1);
    const double r = 200 + 10 * std::sin(3 * t);
    pts.emplace_back(640 + r * std::cos(t) + jitter(rng), 400 + r * std::sin(t) + jitter(rng));
  }
  return pts;
}

CrossSection ellipse(int plane, Vec3 o, Vec3 e1, Vec3 e2, double ra, double rb, int n, double phase) {
  CrossSection s;
  s.plane = plane;
  for (int k = 0; k < n; ++k) {
    const double t = phase + 2 * M_PI * k / n;
    s.points.push_back(o + ra * std::cos(t) * e1 + rb * std::sin(t) * e2);
  }
  return s;
}

// 20 slices of an ellipsoid (10 on z = const, 10 on x = const), each scaled by up to +-4% so no
// two agree: 100 plane pairs, 200 crossings to sew.
SectionSet grid(int points_per_curve) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> noise(0.96, 1.04);
  const double a = 1.0, b = 0.8, c = 0.6;
  SectionSet s;
  for (int i = 0; i < 10; ++i) {
    const double z = c * (-0.6 + 1.2 * i / 9.0);
    s.planes.push_back(Plane{Vec3::UnitZ(), z});
    const double f = std::sqrt(1 - z * z / (c * c));
    s.curves.push_back(ellipse(i, z * Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY(), a * f * noise(rng),
                               b * f * noise(rng), points_per_curve, 0.01 * i));
  }
  for (int i = 0; i < 10; ++i) {
    const double x = a * (-0.6 + 1.2 * i / 9.0);
    s.planes.push_back(Plane{Vec3::UnitX(), x});
    const double f = std::sqrt(1 - x * x / (a * a));
    s.curves.push_back(ellipse(10 + i, x * Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), b * f * noise(rng),
                               c * f * noise(rng), points_per_curve, 0.013 * i));
  }
  return s;
}

void BM_PreprocessStroke(benchmark::State& state) {
  const auto raw = stroke(static_cast<int>(state.range(0)));
  std::size_t out = 0;
  for (auto _ : state) {
    auto r = preprocess_stroke(raw);
    out = r->points.size();
    benchmark::DoNotOptimize(r);
  }
  state.counters["points_out"] = static_cast<double>(out);
}
BENCHMARK(BM_PreprocessStroke)->Arg(500)->Unit(benchmark::kMicrosecond);

void BM_PreparePlaneStroke(benchmark::State& state) {
  // Preprocess + self-crossing test + lift through the default perspective camera.
  const auto raw = stroke(static_cast<int>(state.range(0)));
  const Camera cam;
  const Plane plane{Vec3::UnitY(), 0.0};
  for (auto _ : state) {
    auto r = prepare_plane_stroke(raw, cam, plane);
    if (!r) state.SkipWithError(r.message().c_str());
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_PreparePlaneStroke)->Arg(500)->Unit(benchmark::kMicrosecond);

// A smooth closed curve sampled uniformly, as preprocessing leaves strokes (the common case).
void BM_FirstSelfCrossing(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<Vec2> curve;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n, r = 1.0 + 0.3 * std::sin(5 * t);
    curve.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  for (auto _ : state) benchmark::DoNotOptimize(first_self_crossing(curve));
}
BENCHMARK(BM_FirstSelfCrossing)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

// Worst case for the grid: a star-shaped zigzag of long spikes (radius 0.5-1 at random), where
// each segment's box overlaps hundreds of others.
void BM_FirstSelfCrossingZigzag(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> rad(0.5, 1.0);
  std::vector<Vec2> blob;
  for (int i = 0; i < n; ++i) {
    const double r = rad(rng), t = 2 * M_PI * i / n;
    blob.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  for (auto _ : state) benchmark::DoNotOptimize(first_self_crossing(blob));
}
BENCHMARK(BM_FirstSelfCrossingZigzag)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_SewTwentyCurves(benchmark::State& state) {
  const SectionSet s = grid(static_cast<int>(state.range(0)));
  SewingReport rep;
  for (auto _ : state) {
    auto r = sew_curves(s, {}, &rep);
    if (!r) state.SkipWithError(r.message().c_str());
    benchmark::DoNotOptimize(r);
  }
  state.counters["crossings"] = static_cast<double>(rep.crossings.size());
  state.counters["iterations"] = rep.iterations;
  state.counters["max_moved"] = rep.max_moved;
  state.counters["max_displacement"] = rep.max_displacement;
}
BENCHMARK(BM_SewTwentyCurves)->Arg(64)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_RequiredCrossings(benchmark::State& state) {
  const SectionSet s = grid(200);
  const Plane target{Vec3(0, 1, 0), 0.1};
  for (auto _ : state) benchmark::DoNotOptimize(required_crossings(s, target));
}
BENCHMARK(BM_RequiredCrossings)->Unit(benchmark::kMicrosecond);

// Stroke recognition over the generated labelled corpus (input/stroke_corpus.h: 150 strokes per
// class over a disc, an ellipse and a blob, 200 Hz): time per stroke and accuracy.
void BM_ClassifyCorpus(benchmark::State& state) {
  static const auto corpus = make_stroke_corpus();
  static const auto sil = corpus_silhouettes();
  std::vector<std::vector<Vec2>> pts;
  std::size_t samples = 0;
  for (const auto& ls : corpus) pts.push_back(stroke_positions(ls.samples)), samples += pts.back().size();
  std::vector<InsideModelFn> inside;
  for (const auto& s : sil) inside.push_back([&s](const Vec2& p) { return point_in_polygon_2d(p, s.outline); });
  std::size_t right = 0;
  for (auto _ : state) {
    right = 0;
    for (std::size_t i = 0; i < corpus.size(); ++i) {
      auto c = classify_stroke(pts[i], inside[corpus[i].silhouette]);
      if (c && c->cls == corpus[i].label) ++right;
    }
  }
  state.counters["strokes"] = static_cast<double>(corpus.size());
  state.counters["mean_samples"] = static_cast<double>(samples) / static_cast<double>(corpus.size());
  state.counters["accuracy"] = static_cast<double>(right) / static_cast<double>(corpus.size());
  state.counters["strokes_per_s"] =
      benchmark::Counter(static_cast<double>(corpus.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ClassifyCorpus)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
