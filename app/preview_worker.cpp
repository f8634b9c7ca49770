#include "app/preview_worker.h"

#include <type_traits>

namespace ps::app {

namespace {

// Actions the session applies to the model, or that change what a snapshot shows (the turned
// reference plane of a half-drawn extrusion); everything else only changes the input state.
bool action_changes_model(const Event& e) {
  if (const auto* p = std::get_if<SetParameter>(&e)) return p->name == "extrude_spin" || p->name == "extrude_tilt";
  return std::holds_alternative<Undo>(e) || std::holds_alternative<Redo>(e) ||
         std::holds_alternative<DeleteSection>(e) || std::holds_alternative<OpenFile>(e);
}

}  // namespace

PreviewWorker::PreviewWorker(SessionParams params, std::function<void()> on_published)
    : driver_(std::move(params)),
      on_published_(std::move(on_published)),
      latest_(std::make_shared<const PreviewSnapshot>()),
      thread_([this] { run(); }) {}

PreviewWorker::~PreviewWorker() {
  {
    std::lock_guard lk(m_);
    stop_ = true;
  }
  work_cv_.notify_all();
  thread_.join();
}

// === UI side

void PreviewWorker::on_header(const LogHeader& header) {
  input_ = InputState::from_header(header);
  initial_camera_ = header.camera;
  submit(header, true);
}

void PreviewWorker::on_pen_sample(const PenSample& sample) { submit(sample, false); }

void PreviewWorker::on_action(const TimedEvent& event) {
  // The same InputState::apply the driver makes; its refusals are reported by the driver.
  (void)input_.apply(event.event);
  submit(event, action_changes_model(event.event));
}

void PreviewWorker::on_stroke(const Stroke& stroke) {
  ++strokes_submitted_;
  submit(stroke, true);
}

void PreviewWorker::load_session(std::string path, double t) { submit(FileRequest{std::move(path), t, false}, true); }
void PreviewWorker::import_mesh(std::string path, double t) { submit(FileRequest{std::move(path), t, true}, true); }

void PreviewWorker::set_save_handler(std::function<void(const SketchSession&, const std::string&)> handler) {
  std::lock_guard lk(m_);  // the worker reads it under the same lock's happens-before (submit)
  save_handler_ = std::move(handler);
  driver_.on_save = [this](const std::string& path) {
    if (save_handler_) save_handler_(driver_.session(), path);
  };
}

void PreviewWorker::submit(Item item, bool changes_model) {
  {
    std::lock_guard lk(m_);
    queue_.push_back(Queued{std::move(item), changes_model});
    if (changes_model) ++pending_model_;
    ++submitted_;
  }
  work_cv_.notify_one();
}

std::shared_ptr<const PreviewSnapshot> PreviewWorker::latest() const {
  std::lock_guard lk(m_);
  return latest_;
}

void PreviewWorker::wait_idle() {
  std::unique_lock lk(m_);
  const std::size_t target = submitted_;
  idle_cv_.wait(lk, [&] { return failure_ || (done_ >= target && !dirty_); });
  if (failure_) std::rethrow_exception(failure_);
}

void PreviewWorker::check() const {
  std::lock_guard lk(m_);
  if (failure_) std::rethrow_exception(failure_);
}

bool PreviewWorker::caught_up() const {
  std::lock_guard lk(m_);
  return done_ == submitted_ && !dirty_;
}

std::size_t PreviewWorker::published() const {
  std::lock_guard lk(m_);
  return published_;
}

std::size_t PreviewWorker::superseded() const {
  std::lock_guard lk(m_);
  return superseded_;
}

// === Worker side

void PreviewWorker::apply(const Item& item) {
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, LogHeader>) {
          driver_.on_header(x);
        } else if constexpr (std::is_same_v<T, PenSample>) {
          driver_.on_pen_sample(x);
        } else if constexpr (std::is_same_v<T, TimedEvent>) {
          driver_.on_action(x);
        } else if constexpr (std::is_same_v<T, FileRequest>) {
          if (x.import) (void)driver_.import_mesh(x.t, x.path);
          else (void)driver_.load_session(x.t, x.path);
        } else {
          driver_.on_stroke(x);
          ++strokes_applied_;
        }
      },
      item);
  ++applied_;
}

std::shared_ptr<const PreviewSnapshot> PreviewWorker::snapshot() const {
  auto s = std::make_shared<PreviewSnapshot>();
  s->state = driver_.session().state();
  s->messages = driver_.messages();
  s->notices = driver_.notices();
  s->events_applied = applied_;
  s->strokes_applied = strokes_applied_;
  s->rebuild_ms = driver_.stroke_latencies_ms();
  s->can_undo = driver_.session().can_undo();
  s->can_redo = driver_.session().can_redo();
  s->extrusion_plane = driver_.pending_extrusion_plane();
  return s;
}

void PreviewWorker::run() {
  std::unique_lock lk(m_);
  for (;;) {
    work_cv_.wait(lk, [&] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    Queued q = std::move(queue_.front());
    queue_.pop_front();
    lk.unlock();

    // === Apply, outside the lock: the UI keeps submitting meanwhile.
    const std::size_t messages_before = driver_.messages().size();
    std::exception_ptr failed;
    try {
      apply(q.item);
    } catch (...) {
      failed = std::current_exception();
    }
    const bool changed = q.changes_model || driver_.messages().size() != messages_before;

    lk.lock();
    if (q.changes_model) --pending_model_;
    if (failed) {
      failure_ = failed;
      idle_cv_.notify_all();
      return;
    }
    dirty_ = dirty_ || changed;
    bool publish = false;
    if (dirty_ && pending_model_ == 0) {
      publish = true;
    } else if (q.changes_model && pending_model_ > 0) {
      ++superseded_;  // a newer model change is queued: this result is stale
    }
    if (publish) {
      lk.unlock();
      auto snap = snapshot();  // the driver is the worker's alone; copy without the lock
      lk.lock();
      latest_ = std::move(snap);
      ++published_;
      dirty_ = false;
    }
    ++done_;
    idle_cv_.notify_all();
    if (publish && on_published_) {
      lk.unlock();
      on_published_();
      lk.lock();
    }
  }
}

}  // namespace ps::app
