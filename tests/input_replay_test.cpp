// Replay on a virtual clock: determinism, stroke grouping, stepping and pacing.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

#include "input/input_state.h"
#include "input/stroke_log_io.h"
#include "input/stroke_replayer.h"

namespace ps {
namespace {

// Writes everything it receives into one transcript.
class TranscriptSink : public EventSink {
 public:
  std::ostringstream out;
  std::vector<Stroke> strokes;
  int headers = 0, ends = 0;

  void on_header(const LogHeader& h) override {
    ++headers;
    out << "header " << *format_header(h) << "\n";
  }
  void on_pen_sample(const PenSample& s) override {
    out << "pen " << *format_event(TimedEvent{s.t, 0, s}) << "\n";
  }
  void on_action(const TimedEvent& e) override { out << "action " << *format_event(e) << "\n"; }
  void on_stroke(const Stroke& s) override {
    strokes.push_back(s);
    out << "stroke " << s.samples.size() << " " << s.ended_with_up << "\n";
  }
  void on_end() override {
    ++ends;
    out << "end\n";
  }
};

PenSample pen(double t, Phase ph, double x, Tool tool = Tool::kPen) {
  PenSample s;
  s.t = t;
  s.x = x;
  s.y = 2 * x;
  s.pressure = ph == Phase::kMove || ph == Phase::kDown ? 0.5 : 0.0;
  s.phase = ph;
  s.tool = tool;
  return s;
}

StrokeLog sample_log() {
  StrokeLog log;
  auto add = [&](Event e, double t) { log.events.push_back(TimedEvent{t, 0, std::move(e)}); };
  double t = 0;
  add(SetToolMode{"sketch"}, t);
  add(SelectPlane{1}, t += 3);
  add(TranslatePlane{1, 0.25}, t += 3);
  // Stroke 1: proximity-in, hover, down, 3 moves, up, proximity-out.
  for (Phase ph : {Phase::kProximityIn, Phase::kMove, Phase::kDown, Phase::kMove, Phase::kMove, Phase::kMove,
                   Phase::kUp, Phase::kProximityOut}) {
    t += 5;
    add(pen(t, ph, t), t);
  }
  add(Undo{}, t += 100);
  // Stroke 2 is cut off by proximity-out (no up); stroke 3 by a new down; stroke 4 by log end.
  for (Phase ph : {Phase::kProximityIn, Phase::kDown, Phase::kMove, Phase::kProximityOut, Phase::kProximityIn,
                   Phase::kDown, Phase::kMove, Phase::kDown, Phase::kMove}) {
    t += 5;
    add(pen(t, ph, t), t);
  }
  add(SetParameter{"lambda", 0.5}, t += 3600000.0);  // an hour later: no wall clock involved
  add(pen(t + 1, Phase::kMove, 1.0), t + 1);
  return log;
}

TEST(StrokeReplayer, ReplayingTwiceGivesIdenticalSequences) {
  const StrokeLog log = sample_log();
  TranscriptSink a, b;
  replay(log, a);
  StrokeReplayer r(log);
  r.replay_all(b);
  EXPECT_EQ(a.out.str(), b.out.str());
  // Rewinding the same replayer gives the same sequence again.
  TranscriptSink c;
  r.rewind();
  r.replay_all(c);
  EXPECT_EQ(a.out.str(), c.out.str());
  // Through the text format as well.
  auto text = to_jsonl(log);
  ASSERT_TRUE(text);
  auto back = parse_stroke_log(*text, "mem");
  ASSERT_TRUE(back);
  TranscriptSink d;
  replay(*back, d);
  EXPECT_EQ(a.out.str(), d.out.str());
  EXPECT_EQ(a.headers, 1);
  EXPECT_EQ(a.ends, 1);
}

TEST(StrokeReplayer, SteppingTheClockEqualsReplayingAtOnce) {
  const StrokeLog log = sample_log();
  TranscriptSink whole, stepped;
  replay(log, whole);
  StrokeReplayer r(log);
  std::size_t n = 0;
  for (double t = 0; !r.done(); t += 16.7) {  // window frames at 60 Hz, then jumps
    n += r.replay_until(t, stepped);
    EXPECT_LE(r.clock_ms(), std::max(t, 0.0));
    if (t > 500) t += 1e6;
  }
  EXPECT_EQ(n, log.events.size());
  EXPECT_EQ(whole.out.str(), stepped.out.str());
  EXPECT_EQ(stepped.ends, 1);
}

TEST(StrokeReplayer, PacingSeesEveryEventTimeInOrder) {
  const StrokeLog log = sample_log();
  std::vector<double> seen;
  TranscriptSink sink;
  StrokeReplayer r(log);
  r.replay_all(sink, [&](double t) { seen.push_back(t); });
  ASSERT_EQ(seen.size(), log.events.size());
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], log.events[i].t);
}

TEST(StrokeReplayer, GroupsSamplesIntoStrokes) {
  const StrokeLog log = sample_log();
  TranscriptSink sink;
  replay(log, sink);
  ASSERT_EQ(sink.strokes.size(), 4u);
  EXPECT_EQ(sink.strokes[0].samples.size(), 5u);  // down, 3 moves, up
  EXPECT_TRUE(sink.strokes[0].ended_with_up);
  EXPECT_EQ(sink.strokes[0].samples.front().phase, Phase::kDown);
  EXPECT_EQ(sink.strokes[0].samples.back().phase, Phase::kUp);
  EXPECT_EQ(sink.strokes[1].samples.size(), 2u);
  EXPECT_FALSE(sink.strokes[1].ended_with_up);
  EXPECT_EQ(sink.strokes[2].samples.size(), 2u);
  EXPECT_FALSE(sink.strokes[2].ended_with_up);
  EXPECT_EQ(sink.strokes[3].samples.size(), 3u);  // down, move, and the move after the hour
  EXPECT_FALSE(sink.strokes[3].ended_with_up);
  // The free function agrees with the replayer.
  const auto strokes = group_strokes(log);
  ASSERT_EQ(strokes.size(), sink.strokes.size());
  for (std::size_t i = 0; i < strokes.size(); ++i) EXPECT_EQ(strokes[i].samples.size(), sink.strokes[i].samples.size());
  // A tool change in the middle of a stroke cuts it.
  StrokeGrouper g;
  EXPECT_FALSE(g.add(pen(0, Phase::kDown, 0)));
  auto cut = g.add(pen(1, Phase::kMove, 1, Tool::kEraser));
  ASSERT_TRUE(cut);
  EXPECT_FALSE(cut->ended_with_up);
  EXPECT_FALSE(g.in_stroke());
}

TEST(StrokeReplayer, RealTimePacerNeverRunsAheadOfTheLog) {
  StrokeLog log;
  for (int i = 0; i <= 10; ++i) log.events.push_back(TimedEvent{100.0 + 6.0 * i, 0, Undo{}});  // 60 ms of log
  TranscriptSink paced, fast;
  StrokeReplayer r(log);
  const auto begin = std::chrono::steady_clock::now();
  r.replay_all(paced, StrokeReplayer::real_time_pacer(2.0));  // twice as fast: at least 30 ms
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  EXPECT_GE(ms, 30.0);
  replay(log, fast);
  EXPECT_EQ(paced.out.str(), fast.out.str());  // pacing changes when, never what
}

TEST(InputState, AppliesPlaneCameraAndModeActions) {
  LogHeader h;
  InputState s = InputState::from_header(h);
  EXPECT_EQ(s.selected_plane, 2);
  EXPECT_TRUE(s.apply(SelectPlane{0}));
  EXPECT_TRUE(s.apply(TranslatePlane{0, 0.75}));
  EXPECT_FALSE(s.apply(SelectPlane{9}));
  EXPECT_FALSE(s.apply(TranslatePlane{3, 1.0}));
  EXPECT_EQ(s.selected_plane, 0);
  EXPECT_EQ(s.current_plane()->offset, 0.75);
  Camera c;
  c.eye = Vec3(5, 0.1, 0.2);
  c.target = Vec3(0.75, 0, 0);
  c.up = Vec3(0, 0, 1);
  EXPECT_TRUE(s.apply(CameraChange{c}));
  const auto p = s.lift(c.width / 2.0, c.height / 2.0);  // the centre ray hits the target
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p - c.target).norm(), 0.0, 1e-12);
  EXPECT_TRUE(s.apply(SetParameter{"lambda", 0.25}));
  EXPECT_EQ(s.parameters.at("lambda"), 0.25);
  EXPECT_TRUE(s.apply(SetToolMode{"deform"}));
  EXPECT_EQ(s.mode, "deform");
}

}  // namespace
}  // namespace ps
