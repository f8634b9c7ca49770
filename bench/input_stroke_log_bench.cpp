// Input-layer throughput: reading, writing and replaying stroke logs, synthesizing the demo,
// translating tablet events. Figures go to bench/results/input.md (never asserted in tests).
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "input/log_presets.h"
#include "input/pen_input.h"
#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"

namespace {

const std::string& demo_text() {
  static const std::string text = [] {
    std::ifstream in(std::string(PLANESKETCH_SOURCE_DIR) + "/assets/logs/demo.jsonl", std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  return text;
}

void BM_ParseDemoLog(benchmark::State& st) {
  const std::string& text = demo_text();
  std::size_t events = 0;
  for (auto _ : st) {
    auto log = ps::parse_stroke_log(text, "demo");
    if (!log) st.SkipWithError(log.message().c_str());
    else events = log->events.size();
    benchmark::DoNotOptimize(log);
  }
  st.SetBytesProcessed(st.iterations() * static_cast<std::int64_t>(text.size()));
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(events));
}
BENCHMARK(BM_ParseDemoLog)->Unit(benchmark::kMillisecond);

void BM_WriteDemoLog(benchmark::State& st) {
  auto log = ps::parse_stroke_log(demo_text(), "demo");
  for (auto _ : st) {
    auto text = ps::to_jsonl(*log);
    benchmark::DoNotOptimize(text);
  }
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(log->events.size()));
}
BENCHMARK(BM_WriteDemoLog)->Unit(benchmark::kMillisecond);

class NullSink : public ps::EventSink {
 public:
  std::size_t n = 0;
  void on_header(const ps::LogHeader&) override {}
  void on_pen_sample(const ps::PenSample&) override { ++n; }
  void on_action(const ps::TimedEvent&) override { ++n; }
  void on_stroke(const ps::Stroke& s) override { n += s.samples.size(); }
};

void BM_ReplayDemoLog(benchmark::State& st) {
  auto log = ps::parse_stroke_log(demo_text(), "demo");
  for (auto _ : st) {
    NullSink sink;
    ps::replay(*log, sink);
    benchmark::DoNotOptimize(sink.n);
  }
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(log->events.size()));
}
BENCHMARK(BM_ReplayDemoLog)->Unit(benchmark::kMicrosecond);

void BM_SynthesizeVase(benchmark::State& st) {
  for (auto _ : st) {
    auto r = ps::synthesize_preset("vase");
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_SynthesizeVase)->Unit(benchmark::kMillisecond);

void BM_TranslateTabletEvent(benchmark::State& st) {
  const ps::TabletMapping m = ps::TabletMapping::fit(152, 95, 1280, 800);
  ps::TabletToolEvent e;
  e.x = 40;
  e.y = 30;
  e.pressure = 0.5;
  for (auto _ : st) {
    e.x += 1e-6;
    auto s = ps::translate_tablet_event(e, m);
    benchmark::DoNotOptimize(s);
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
}
BENCHMARK(BM_TranslateTabletEvent);

}  // namespace

BENCHMARK_MAIN();
