#pragma once
// The progressive preview off the UI thread (issue 7, point 4): a worker thread owns the
// SessionDriver and applies the events the UI hands it; the UI draws the newest model the
// worker has finished and never waits for a reconstruction.
//
//   PreviewWorker worker(params, [] { glfwPostEmptyEvent(); });   // wake the UI on a result
//   worker.on_header(header);                  // UI thread: EventSink calls only enqueue
//   worker.on_stroke(stroke);                  //   (journal the event first, as before)
//   auto snap = worker.latest();               // each frame: the newest published snapshot
//   draw(session_scene(snap->state, worker.input(), camera));
//
// === Why the final model is the synchronous one, bit for bit
// Every event goes through one FIFO queue and the worker applies them to its SessionDriver in
// submission order, with the same calls the synchronous window made. The driver, and so the
// session, sees exactly the synchronous event sequence; nothing is applied out of order,
// merged or dropped. Refusals (a stroke that breaks a rule, an eraser that touches nothing)
// depend on the state left by the strokes before, so they come out the same as well.
//
// === Supersession
// What a newer stroke replaces is the *preview* of a computation still running: after applying
// an event the worker publishes a snapshot (a copy of the session state, the driver's
// messages and counters) only when no newer model-changing event (stroke, undo, redo, delete)
// is waiting in the queue; otherwise that result is stale and skipped (`superseded()` counts
// them), and the UI goes straight from the older preview to the newer one. The superseded
// computation itself still runs to its end: the next state is built on it and undo restores
// it, and SketchSession (modeling/) has no cancellation point, which it should not grow for a
// UI concern.
//
// === Threads
// The EventSink calls, input(), initial_camera() and strokes_submitted() belong to one thread
// (the UI thread; the one that constructed the worker). latest(), counters, wait_idle() and
// check() may be called from any thread. The driver and its session are touched only by the
// worker thread. `on_published` runs on the worker thread after each publication; keep it
// short and thread-safe (glfwPostEmptyEvent is).
//
// Plane, camera, mode and parameter actions are also applied at once to a mirror InputState on
// the UI side (input()), so the view, the selected plane and the lifting of a stroke in
// progress follow the user without waiting for the worker. The driver applies the same
// actions with InputState::apply, so the mirror equals the driver's input state once the
// worker has caught up.
//
// An exception thrown while applying an event stops the worker; wait_idle() and check()
// rethrow it on the caller's thread (the synchronous window would have thrown it from the
// event). Destruction stops the worker after the event in progress and drops the queue (the
// journal holds every event, so nothing is lost that recovery needs).
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <variant>
#include <vector>

#include "app/session_driver.h"
#include "input/input_state.h"
#include "input/stroke_replayer.h"

namespace ps::app {

// What the worker publishes: the session as it was after `events_applied` events.
struct PreviewSnapshot {
  SessionState state;
  std::vector<DriverMessage> messages;  // every message so far, in order
  std::vector<DriverMessage> notices;   // every notice so far (SessionDriver::notices)
  std::size_t events_applied = 0;       // events applied (header, samples, actions, strokes)
  std::size_t strokes_applied = 0;      // of them, strokes (on_stroke calls)
  std::vector<double> rebuild_ms;       // the driver's pen-up to rebuilt model times so far
  bool can_undo = false, can_redo = false;
  // The reference plane of an extrusion waiting for its silhouette (SessionDriver).
  std::optional<ExtrudePlane> extrusion_plane;
};

class PreviewWorker : public EventSink {
 public:
  explicit PreviewWorker(SessionParams params = {}, std::function<void()> on_published = {});
  ~PreviewWorker() override;
  PreviewWorker(const PreviewWorker&) = delete;
  PreviewWorker& operator=(const PreviewWorker&) = delete;

  // === EventSink (UI thread): update the mirror, enqueue, return at once.
  void on_header(const LogHeader& header) override;
  void on_pen_sample(const PenSample& sample) override;
  void on_action(const TimedEvent& event) override;
  void on_stroke(const Stroke& stroke) override;

  // UI thread: session files, queued and applied in order like every event (the driver's
  // load_session / import_mesh: a refusal becomes a message in the next snapshot).
  // `t`: the log time messages carry.
  void load_session(std::string path, double t = 0.0);
  void import_mesh(std::string path, double t = 0.0);
  // What a `save` action does, called on the worker thread with the session as it is after
  // every event before the action. Set it before the first event is submitted.
  void set_save_handler(std::function<void(const SketchSession&, const std::string& path)> handler);

  // UI thread: the input state with every submitted action applied.
  const InputState& input() const { return input_; }
  const Camera& initial_camera() const { return initial_camera_; }
  // UI thread: strokes submitted so far; stroke k (1-based) is in every snapshot with
  // strokes_applied >= k.
  std::size_t strokes_submitted() const { return strokes_submitted_; }

  // Any thread: the newest published snapshot (an empty session before the first one).
  std::shared_ptr<const PreviewSnapshot> latest() const;
  // Blocks until every event submitted before the call is applied and its snapshot published.
  // Rethrows a failure of the worker.
  void wait_idle();
  // Rethrows a failure of the worker, if any; never blocks on a computation.
  void check() const;
  // True when every submitted event is applied and the newest state is published.
  bool caught_up() const;

  std::size_t published() const;   // snapshots published
  std::size_t superseded() const;  // model changes whose snapshot was skipped for a newer one

 private:
  struct FileRequest {
    std::string path;
    double t = 0.0;
    bool import = false;  // else load a session
  };
  using Item = std::variant<LogHeader, PenSample, TimedEvent, Stroke, FileRequest>;
  void submit(Item item, bool changes_model);
  void run();
  // Applies one item to the driver (worker thread).
  void apply(const Item& item);
  std::shared_ptr<const PreviewSnapshot> snapshot() const;

  // UI side.
  InputState input_;
  Camera initial_camera_;
  std::size_t strokes_submitted_ = 0;

  // Worker side (touched only by the worker thread once it runs).
  SessionDriver driver_;
  std::size_t applied_ = 0, strokes_applied_ = 0;
  std::function<void()> on_published_;
  std::function<void(const SketchSession&, const std::string&)> save_handler_;

  // Shared, under m_.
  mutable std::mutex m_;
  std::condition_variable work_cv_, idle_cv_;
  struct Queued {
    Item item;
    bool changes_model;
  };
  std::deque<Queued> queue_;
  std::size_t pending_model_ = 0;  // queued items that change the model
  std::size_t submitted_ = 0, done_ = 0;  // items submitted / applied and settled
  bool dirty_ = false;  // applied changes not yet published
  bool stop_ = false;
  std::exception_ptr failure_;
  std::shared_ptr<const PreviewSnapshot> latest_;
  std::size_t published_ = 0, superseded_ = 0;

  std::thread thread_;  // last: starts after every member above exists, joined first
};

}  // namespace ps::app
