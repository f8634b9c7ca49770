#pragma once
// Replays a stroke log through an EventSink, the same interface the live app implements.
//
// Time is the log's own (a virtual clock): headless replay runs as fast as possible and gives
// the same event sequence every time; a window can pass a pacing callback (called with each
// event's virtual time before it is delivered, e.g. to sleep until the wall clock catches up)
// or advance the clock frame by frame with replay_until().
//
// Strokes: the replayer also groups pen samples into strokes (down..up) and hands each
// completed stroke to EventSink::on_stroke after its last sample. A stroke also ends, with
// ended_with_up = false, at proximity-out, at a new down, at a tool change or at the end of
// the log, so a consumer never sees half a stroke twice.
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "input/stroke_log.h"

namespace ps {

class EventSink {
 public:
  virtual ~EventSink() = default;
  virtual void on_header(const LogHeader& header) = 0;
  virtual void on_pen_sample(const PenSample& sample) = 0;
  // Every event that is not a pen sample (plane, camera, tool mode, parameter, undo, redo,
  // delete, save).
  virtual void on_action(const TimedEvent& event) = 0;
  // A stroke just ended (after on_pen_sample of its last sample). Default: ignored.
  virtual void on_stroke(const Stroke& stroke) {}
  // The log is exhausted. Default: ignored.
  virtual void on_end() {}
};

// Groups a stream of pen samples into strokes (rules above). Stateful: feed samples in order.
class StrokeGrouper {
 public:
  // The stroke this sample ends, if any: completed by an up (the up is its last sample), or
  // cut off (before this sample) by proximity, a new down or a tool change.
  std::optional<Stroke> add(const PenSample& s);
  // Ends a stroke in progress (log end); nothing if none.
  std::optional<Stroke> finish();
  bool in_stroke() const { return active_.has_value(); }

 private:
  std::optional<Stroke> active_;
};

// All strokes of a log, in order.
std::vector<Stroke> group_strokes(const StrokeLog& log);

class StrokeReplayer {
 public:
  using PaceFn = std::function<void(double t_ms)>;

  explicit StrokeReplayer(StrokeLog log);

  // A pacing callback for a window: sleeps until `speed` x the wall-clock time since its first
  // call reaches each event's time (speed 2 replays twice as fast). The only place replay
  // looks at a clock, and only when asked.
  static PaceFn real_time_pacer(double speed = 1.0);

  // Delivers the header (once) and every event with t <= t_ms; returns how many events.
  std::size_t replay_until(double t_ms, EventSink& sink);
  // Delivers everything left, calling `pace` (if set) with each event's time first.
  void replay_all(EventSink& sink, const PaceFn& pace = {});
  // Starts over from the header.
  void rewind();

  bool done() const { return next_ >= log_.events.size(); }
  double clock_ms() const { return clock_; }
  double end_time_ms() const { return log_.events.empty() ? 0.0 : log_.events.back().t; }
  const StrokeLog& log() const { return log_; }

 private:
  void deliver(const TimedEvent& e, EventSink& sink);
  void start(EventSink& sink);
  void finish(EventSink& sink);

  StrokeLog log_;
  std::size_t next_ = 0;
  double clock_ = 0.0;
  bool started_ = false;
  bool finished_ = false;
  StrokeGrouper grouper_;
};

// One-shot: replays a whole log as fast as possible.
void replay(const StrokeLog& log, EventSink& sink);

}  // namespace ps
