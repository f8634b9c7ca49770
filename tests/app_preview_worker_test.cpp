// The window's preview worker (app/preview_worker.h), headless: the session it builds on its
// thread must be the synchronous SessionDriver's, bit for bit, however fast events arrive and
// however many previews are superseded; every snapshot it publishes must be a state the
// synchronous session passed through. PreviewWorkerTest.* is also part of the
// ThreadSanitizer run (scripts/test; 54 s there).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <future>
#include <random>
#include <thread>

#include "app/preview_worker.h"
#include "app/session_driver.h"
#include "input/log_presets.h"
#include "input/stroke_replayer.h"

namespace ps::app {
namespace {

// === Fingerprints of a session as the worker publishes it (FNV-1a over the exact bits).
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  void num(double v) { bytes(&v, sizeof v); }
  void num(std::size_t v) { bytes(&v, sizeof v); }
  void text(const std::string& s) {
    num(s.size());
    bytes(s.data(), s.size());
  }
  void points(const std::vector<Vec3>& pts) {
    num(pts.size());
    for (const auto& p : pts) bytes(p.data(), 3 * sizeof(double));
  }
  void sections(const SectionSet& s) {
    num(s.curves.size());
    for (const auto& c : s.curves) {
      num(static_cast<std::size_t>(c.plane + 1));
      points(c.points);
    }
  }
};

std::uint64_t fingerprint(const SessionState& st, const std::vector<DriverMessage>& messages, bool can_undo,
                          bool can_redo) {
  Fnv f;
  f.sections(st.sections);
  f.sections(st.sewn);
  f.num(st.ops.size());
  f.points(st.model.vertices);
  f.num(st.model.faces.size());
  f.bytes(st.model.faces.data(), st.model.faces.size() * sizeof(Face));
  for (const auto& h : st.hints) f.text(h);
  f.num(messages.size());
  for (const auto& m : messages) f.text(m.text);
  f.num(static_cast<std::size_t>(can_undo) * 2 + static_cast<std::size_t>(can_redo));
  return f.h;
}

std::uint64_t fingerprint(const SessionDriver& d) {
  return fingerprint(d.session().state(), d.messages(), d.session().can_undo(), d.session().can_redo());
}
std::uint64_t fingerprint(const PreviewSnapshot& s) {
  return fingerprint(s.state, s.messages, s.can_undo, s.can_redo);
}

// The session parameters of every run here. Without the mesh improvement (4.5.1): it runs the
// same on either thread, and leaving it out makes the ThreadSanitizer run affordable (the
// window's own bit-for-bit check with improvement is the screenshot comparison in
// bench/results/window.md).
SessionParams params() {
  SessionParams p;
  p.improve = false;
  return p;
}

// The synchronous reference: a driver fed directly, with the fingerprint after every event
// (index = events applied, counted the way the worker counts them).
class RecordingSink : public EventSink {
 public:
  void on_header(const LogHeader& h) override { step(&SessionDriver::on_header, h); }
  // The driver takes whole strokes; a single sample changes nothing it holds (checked on the
  // cheap parts, so the reference does not hash the model after each of ~5000 samples).
  void on_pen_sample(const PenSample& s) override {
    const auto faces = driver.session().state().model.faces.size();
    const auto messages = driver.messages().size();
    driver.on_pen_sample(s);
    EXPECT_EQ(faces, driver.session().state().model.faces.size());
    EXPECT_EQ(messages, driver.messages().size());
    states.push_back(states.back());
  }
  void on_action(const TimedEvent& e) override { step(&SessionDriver::on_action, e); }
  void on_stroke(const Stroke& s) override { step(&SessionDriver::on_stroke, s); }
  SessionDriver driver{params()};
  std::vector<std::uint64_t> states{fingerprint(SessionDriver{})};  // states[0]: nothing applied

 private:
  template <class T>
  void step(void (SessionDriver::*apply)(const T&), const T& x) {
    (driver.*apply)(x);
    states.push_back(fingerprint(driver));
  }
};

// === The test session: three sections of the vase preset, then a burst of rapid edits drawn
// 1 ms apart: every stroke again (each refused or accepted exactly as in the synchronous run),
// undo, redo, an eraser stroke over the first section, a refused redo, undo, and the strokes
// once more.
void add_sample(StrokeLog& log, double t, double x, double y, Tool tool, Phase phase) {
  PenSample s;
  s.t = t;
  s.x = x;
  s.y = y;
  s.pressure = phase == Phase::kUp ? 0.0 : 0.7;
  s.tool = tool;
  s.phase = phase;
  log.events.push_back(TimedEvent{t, 0, s});
}

StrokeLog three_sections(Vec3& first_drawn) {
  auto preset = make_log_preset("vase");
  EXPECT_TRUE(preset) << preset.message();
  // z = -0.7, z = 0.1 and the profile on x = 0: slices of one solid, so rule 4 holds.
  preset->steps = {preset->steps[0], preset->steps[2], preset->steps[5]};
  auto res = synthesize_preset(*preset, 20261201);
  EXPECT_TRUE(res) << res.message();
  const auto& drawn = res->strokes.front().drawn;
  first_drawn = drawn[drawn.size() / 2];
  return res->log;
}

StrokeLog rapid_edits_log() {
  Vec3 first_drawn;
  StrokeLog log = three_sections(first_drawn);
  const StrokeLog base = log;
  double t = log.events.back().t;
  const auto again = [&] {  // every pen sample of the base log, 1 ms apart
    for (const auto& e : base.events)
      if (const auto* s = std::get_if<PenSample>(&e.event)) {
        t += 1.0;
        PenSample c = *s;
        c.t = t;
        log.events.push_back(TimedEvent{t, 0, c});
      }
  };
  const auto action = [&](Event e) {
    t += 1.0;
    log.events.push_back(TimedEvent{t, 0, std::move(e)});
  };
  again();
  action(Undo{});
  action(Undo{});
  action(Redo{});
  // The eraser over the first section (a point drawn for it, seen through the log's last
  // camera; the undo/redo above leave that section in place).
  InputState view = InputState::from_header(log.header);
  for (const auto& e : log.events) (void)view.apply(e.event);
  const auto p = view.camera.project(first_drawn);
  EXPECT_TRUE(p);
  add_sample(log, t += 1.0, p->x(), p->y(), Tool::kEraser, Phase::kDown);
  add_sample(log, t += 1.0, p->x() + 1.0, p->y(), Tool::kEraser, Phase::kMove);
  add_sample(log, t += 1.0, p->x() + 2.0, p->y(), Tool::kEraser, Phase::kUp);
  action(Redo{});  // nothing to redo after an edit: refused with a message
  action(Undo{});
  again();
  action(Undo{});
  return log;
}

std::size_t model_events(const StrokeLog& log) {
  std::size_t n = group_strokes(log).size();
  for (const auto& e : log.events)
    if (std::holds_alternative<Undo>(e.event) || std::holds_alternative<Redo>(e.event) ||
        std::holds_alternative<DeleteSection>(e.event))
      ++n;
  return n;
}

void expect_same_session(const PreviewSnapshot& snap, const SessionDriver& d) {
  const auto& a = snap.state;
  const auto& b = d.session().state();
  ASSERT_EQ(a.model.vertices.size(), b.model.vertices.size());
  ASSERT_EQ(a.model.faces.size(), b.model.faces.size());
  EXPECT_EQ(0, std::memcmp(a.model.vertices.data(), b.model.vertices.data(), a.model.vertices.size() * sizeof(Vec3)));
  EXPECT_TRUE(a.model.faces == b.model.faces);
  ASSERT_EQ(a.sections.curves.size(), b.sections.curves.size());
  for (std::size_t i = 0; i < a.sections.curves.size(); ++i)
    EXPECT_TRUE(a.sections.curves[i].points == b.sections.curves[i].points) << "section " << i;
  ASSERT_EQ(snap.messages.size(), d.messages().size());
  for (std::size_t i = 0; i < snap.messages.size(); ++i) EXPECT_EQ(snap.messages[i].text, d.messages()[i].text);
  EXPECT_EQ(snap.can_undo, d.session().can_undo());
  EXPECT_EQ(snap.can_redo, d.session().can_redo());
  EXPECT_EQ(fingerprint(snap), fingerprint(d));
}

class PreviewWorkerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    log_ = new StrokeLog(rapid_edits_log());
    sync_ = new RecordingSink;
    replay(*log_, *sync_);
  }
  static void TearDownTestSuite() {
    delete sync_;
    delete log_;
  }
  static StrokeLog* log_;
  static RecordingSink* sync_;
};
StrokeLog* PreviewWorkerTest::log_ = nullptr;
RecordingSink* PreviewWorkerTest::sync_ = nullptr;

TEST_F(PreviewWorkerTest, TheLogExercisesStrokesRefusalsUndoRedoAndTheEraser) {
  const auto& d = sync_->driver;
  EXPECT_FALSE(d.session().state().model.empty());
  bool refused_stroke = false, refused_redo = false;
  for (const auto& m : d.messages()) {
    EXPECT_EQ(m.text.find("eraser touched no section"), std::string::npos) << m.text;
    refused_stroke = refused_stroke || m.text.rfind("stroke refused", 0) == 0;
    refused_redo = refused_redo || m.text.find("redo") != std::string::npos;
  }
  EXPECT_TRUE(refused_stroke);
  EXPECT_TRUE(refused_redo);
  EXPECT_GE(model_events(*log_), 10u);
}

// Everything submitted at once, as fast as the replayer delivers it: the worker's final
// session is the synchronous one, and the many superseded previews left no trace.
TEST_F(PreviewWorkerTest, AllAtOnceGivesTheSynchronousSessionBitForBit) {
  PreviewWorker worker(params());
  replay(*log_, worker);
  worker.wait_idle();
  const auto snap = worker.latest();
  expect_same_session(*snap, sync_->driver);
  EXPECT_EQ(snap->events_applied + 1, sync_->states.size());
  EXPECT_EQ(snap->strokes_applied, group_strokes(*log_).size());
  EXPECT_EQ(worker.input().camera.eye, sync_->driver.input().camera.eye);
  EXPECT_EQ(worker.input().selected_plane, sync_->driver.input().selected_plane);
}

// Deterministic supersession: the worker is held inside its first publication (the header)
// until every event is queued, so every model change but the last is superseded and exactly
// one more snapshot is published.
TEST_F(PreviewWorkerTest, QueuedStrokesSupersedeEveryPreviewButTheNewest) {
  std::promise<void> entered, release;
  auto release_future = release.get_future().share();
  std::atomic<int> calls{0};
  PreviewWorker worker(params(), [&] {
    if (calls.fetch_add(1) == 0) {
      entered.set_value();
      release_future.wait();
    }
  });
  worker.on_header(log_->header);
  entered.get_future().wait();
  StrokeReplayer replayer(*log_);
  class AfterHeader : public EventSink {
   public:
    explicit AfterHeader(EventSink& next) : next_(next) {}
    void on_header(const LogHeader&) override {}  // already submitted
    void on_pen_sample(const PenSample& s) override { next_.on_pen_sample(s); }
    void on_action(const TimedEvent& e) override { next_.on_action(e); }
    void on_stroke(const Stroke& s) override { next_.on_stroke(s); }

   private:
    EventSink& next_;
  } rest(worker);
  replayer.replay_all(rest);
  EXPECT_EQ(worker.published(), 1u);
  release.set_value();
  worker.wait_idle();
  EXPECT_EQ(worker.published(), 2u);
  EXPECT_EQ(worker.superseded(), model_events(*log_) - 1);
  expect_same_session(*worker.latest(), sync_->driver);
}

// Events arrive at an irregular pace (seeded: after some strokes a pause until the preview is
// there, after the others a few ms) while the test thread keeps reading snapshots: every snapshot it sees is exactly the synchronous state after the
// number of events it says it has applied, and the end is the synchronous end.
TEST_F(PreviewWorkerTest, EverySnapshotIsAStateTheSynchronousSessionPassedThrough) {
  PreviewWorker worker(params());
  std::mt19937 rng(7);
  std::size_t checked = 0;
  std::size_t last_applied = 0;
  const auto check = [&] {
    const auto snap = worker.latest();
    ASSERT_LT(snap->events_applied, sync_->states.size());
    EXPECT_GE(snap->events_applied, last_applied);  // previews never go back in time
    last_applied = snap->events_applied;
    EXPECT_EQ(fingerprint(*snap), sync_->states[snap->events_applied]) << "after " << snap->events_applied << " events";
    ++checked;
  };
  class Paced : public EventSink {
   public:
    Paced(PreviewWorker& w, std::mt19937& rng, const std::function<void()>& check)
        : w_(w), rng_(rng), check_(check) {}
    void on_header(const LogHeader& h) override { w_.on_header(h); }
    void on_pen_sample(const PenSample& s) override {
      w_.on_pen_sample(s);
      if (++n_ % 64 == 0) check_();
    }
    void on_action(const TimedEvent& e) override {
      w_.on_action(e);
      check_();
    }
    void on_stroke(const Stroke& s) override {
      w_.on_stroke(s);
      check_();
      // A third of the strokes the user pauses until the preview is there; the rest follow
      // within a few ms, superseding the preview still being computed.
      if (rng_() % 3 == 0) {
        while (!w_.caught_up()) {
          check_();
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(rng_() % 5));
      }
    }

   private:
    PreviewWorker& w_;
    std::mt19937& rng_;
    const std::function<void()>& check_;
    std::size_t n_ = 0;
  };
  const std::function<void()> check_fn = check;
  Paced paced(worker, rng, check_fn);
  replay(*log_, paced);
  while (!worker.caught_up()) {
    check();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  worker.wait_idle();
  check();
  EXPECT_GT(checked, 10u);
  EXPECT_GE(worker.published(), 3u);  // the pauses (seed 7: after strokes 1, 4 and 10) show previews
  EXPECT_GE(worker.published() + worker.superseded(), model_events(*log_));
  expect_same_session(*worker.latest(), sync_->driver);
}

// With the mesh improvement on (the window's default), too: the final mesh is the synchronous
// one, bit for bit. (Its own suite: too slow for the ThreadSanitizer run, which takes
// PreviewWorkerTest.*.)
TEST(PreviewWorkerImproved, FinalMeshIsTheSynchronousOne) {
  const StrokeLog log = rapid_edits_log();
  SessionDriver sync;
  replay(log, sync);
  ASSERT_FALSE(sync.session().state().model.empty());
  PreviewWorker worker;
  replay(log, worker);
  worker.wait_idle();
  expect_same_session(*worker.latest(), sync);
}

// Destroying the worker with work queued stops it after the event in progress (the window
// closing during a rebuild); nothing is left running.
TEST_F(PreviewWorkerTest, DestructionWithQueuedWorkStopsCleanly) {
  const auto t0 = std::chrono::steady_clock::now();
  {
    PreviewWorker worker(params());
    replay(*log_, worker);
  }
  SUCCEED() << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s";
}

}  // namespace
}  // namespace ps::app
