// Every committed stroke log (assets/logs/*.jsonl) is a regression input for the input layer:
// it reads without errors or warnings, writes back to the same text, its strokes are complete,
// and every stroke sample lifts onto the plane selected when it was drawn.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "input/input_state.h"
#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"

namespace ps {
namespace {

std::vector<std::filesystem::path> corpus() {
  std::vector<std::filesystem::path> out;
  const std::filesystem::path dir = std::filesystem::path(PLANESKETCH_SOURCE_DIR) / "assets" / "logs";
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".jsonl") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

class LiftSink : public EventSink {
 public:
  InputState state;
  std::size_t lifted = 0, missed = 0, strokes = 0, incomplete = 0;
  void on_header(const LogHeader& h) override { state = InputState::from_header(h); }
  void on_pen_sample(const PenSample& s) override {
    if (s.phase == Phase::kDown || s.phase == Phase::kMove || s.phase == Phase::kUp)
      (state.lift(s.x, s.y) ? lifted : missed)++;
  }
  void on_action(const TimedEvent& e) override { EXPECT_TRUE(state.apply(e.event)) << "line " << e.line; }
  void on_stroke(const Stroke& s) override {
    ++strokes;
    incomplete += s.ended_with_up ? 0 : 1;
  }
};

TEST(StrokeLogCorpus, EveryCommittedLogReadsCleanlyAndLiftsOntoItsPlanes) {
  const auto files = corpus();
  if (files.empty()) GTEST_SKIP() << "no assets/logs/*.jsonl";
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    std::vector<std::string> warnings;
    auto log = read_stroke_log(f.string(), &warnings);
    ASSERT_TRUE(log) << log.message();
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    std::ifstream in(f, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(*to_jsonl(*log), text.str());  // committed logs are in the writer's canonical form
    LiftSink sink;
    replay(*log, sink);
    EXPECT_GT(sink.strokes, 0u);
    EXPECT_EQ(sink.incomplete, 0u);
    EXPECT_GT(sink.lifted, 0u);
    EXPECT_EQ(sink.missed, 0u);
  }
}

}  // namespace
}  // namespace ps
