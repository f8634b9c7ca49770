// Stroke-log replay on a virtual clock, and grouping of pen samples into strokes.
#include "input/stroke_replayer.h"

#include <chrono>
#include <memory>
#include <thread>
#include <utility>

namespace ps {

// === Stroke grouping

std::optional<Stroke> StrokeGrouper::add(const PenSample& s) {
  std::optional<Stroke> done;
  auto cut = [&](bool with_up) {
    if (!active_) return;
    active_->ended_with_up = with_up;
    done = std::move(active_);
    active_.reset();
  };
  switch (s.phase) {
    case Phase::kDown:
      cut(false);  // a down without an up before it: the earlier stroke was cut off
      active_ = Stroke{{s}, s.tool, true};
      break;
    case Phase::kMove:
      if (active_) {
        if (s.tool != active_->tool) cut(false);
        else active_->samples.push_back(s);
      }
      break;
    case Phase::kUp:
      if (active_) {
        active_->samples.push_back(s);
        cut(true);
      }
      break;
    case Phase::kProximityIn:
    case Phase::kProximityOut:
      cut(false);
      break;
  }
  return done;
}

std::optional<Stroke> StrokeGrouper::finish() {
  if (!active_) return std::nullopt;
  std::optional<Stroke> done = std::move(active_);
  done->ended_with_up = false;
  active_.reset();
  return done;
}

std::vector<Stroke> group_strokes(const StrokeLog& log) {
  std::vector<Stroke> out;
  StrokeGrouper g;
  for (const TimedEvent& e : log.events)
    if (const auto* s = std::get_if<PenSample>(&e.event))
      if (auto st = g.add(*s)) out.push_back(std::move(*st));
  if (auto st = g.finish()) out.push_back(std::move(*st));
  return out;
}

// === Replayer

StrokeReplayer::StrokeReplayer(StrokeLog log) : log_(std::move(log)) {}

StrokeReplayer::PaceFn StrokeReplayer::real_time_pacer(double speed) {
  using Clock = std::chrono::steady_clock;
  struct State {
    bool started = false;
    Clock::time_point start;
    double first_t = 0.0;
  };
  auto st = std::make_shared<State>();
  const double s = speed > 0.0 ? speed : 1.0;
  return [st, s](double t_ms) {
    if (!st->started) {
      st->started = true;
      st->start = Clock::now();
      st->first_t = t_ms;
      return;
    }
    const auto due = st->start + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double, std::milli>((t_ms - st->first_t) / s));
    std::this_thread::sleep_until(due);
  };
}

void StrokeReplayer::rewind() {
  next_ = 0;
  clock_ = 0.0;
  started_ = false;
  finished_ = false;
  grouper_ = StrokeGrouper{};
}

void StrokeReplayer::start(EventSink& sink) {
  if (started_) return;
  started_ = true;
  sink.on_header(log_.header);
}

void StrokeReplayer::finish(EventSink& sink) {
  if (finished_ || !done()) return;
  finished_ = true;
  if (auto st = grouper_.finish()) sink.on_stroke(*st);
  sink.on_end();
}

void StrokeReplayer::deliver(const TimedEvent& e, EventSink& sink) {
  clock_ = e.t;
  if (const auto* s = std::get_if<PenSample>(&e.event)) {
    // A stroke cut off by this sample ends before the sample is delivered; one completed by
    // this sample (pen-up) ends after it.
    const bool completes = s->phase == Phase::kUp;
    std::optional<Stroke> st = grouper_.add(*s);
    if (st && !completes) sink.on_stroke(*st);
    sink.on_pen_sample(*s);
    if (st && completes) sink.on_stroke(*st);
  } else {
    sink.on_action(e);
  }
}

std::size_t StrokeReplayer::replay_until(double t_ms, EventSink& sink) {
  start(sink);
  std::size_t n = 0;
  while (!done() && log_.events[next_].t <= t_ms) {
    deliver(log_.events[next_++], sink);
    ++n;
  }
  if (t_ms > clock_) clock_ = done() ? clock_ : t_ms;
  finish(sink);
  return n;
}

void StrokeReplayer::replay_all(EventSink& sink, const PaceFn& pace) {
  start(sink);
  while (!done()) {
    const TimedEvent& e = log_.events[next_++];
    if (pace) pace(e.t);
    deliver(e, sink);
  }
  finish(sink);
}

void replay(const StrokeLog& log, EventSink& sink) {
  StrokeReplayer r(log);
  r.replay_all(sink);
}

}  // namespace ps
