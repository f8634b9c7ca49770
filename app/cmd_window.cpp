// planesketch window [--replay LOG] [--screenshot FILE] [--journal FILE] [--size WxH] [--report R.json]
// The interactive window: GLFW + Vulkan swapchain (engine/window_presenter.h), pen input from
// libinput when the seat allows it, else the mouse (pressure 1), every event journaled to a
// stroke log as it happens (fsync per stroke, end marker on a clean exit) and then applied
// through the same SessionDriver that headless replay uses, which runs on a worker thread
// (app/preview_worker.h): the UI thread keeps drawing and taking strokes while the model is
// rebuilt, and shows the newest finished model.
//
// Frames are drawn when something changed (input, a new preview, a resize; at least every
// 250 ms), so an idle window leaves both cores to the reconstruction. For every stroke the
// time from pen-up to the first presented frame that shows its result is printed and, with
// --report, written with the UI thread's busy time per frame (docs/session.md, "Latency").
//
// The panel (Dear ImGui, engine/window_presenter.h; off with --no-panel) picks the tool mode,
// the reference plane and its offset, and lambda; each change is journaled and applied like
// the keys below, and it shows the newest refusal or notice. It is shown for live input, not
// while a log is replayed.
//
// In sketch mode the selected plane carries its guides (app/session_scene.h): rings where
// sections on other planes cross it (rule 4; faint once a section on the plane meets them) and
// the model's cross section by it, half transparent. An open stroke oversketches a section it
// starts and ends on, or is completed from that cross section (modeling/section_oversketch.h).
//
// Keys: 1/2/3 select the x/y/z plane (the view turns to face it), Up/Down move the selected plane
// by 0.04, Ctrl+Z undo, Ctrl+Y redo, E toggles the mouse eraser, Esc quits. Left drag sketches;
// right drag orbits the camera (arcball about the target).
// Files (docs/session-format.md): --session S.json is loaded at start when it exists; Ctrl+S
// saves the session there and Ctrl+E exports the model to --export FILE (both journaled `save`
// actions, carried out on the worker after the events before them); Ctrl+O loads S.json again
// (replacing the session, history cleared); --import MESH starts from a mesh as the base. Every
// open is a journaled `open` event with the file's digest, so recovery restores the same model.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <iterator>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>
#include <tuple>

#include "app/commands.h"
#include "modeling/session_io.h"
#include "app/journal.h"
#include "app/preview_worker.h"
#include "app/session_scene.h"
#include "engine/image.h"
#include "engine/renderer.h"
#include "engine/window_presenter.h"
#include "input/pen_input.h"
#include "input/stroke_log_io.h"
#include "input/stroke_recorder.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Nearest-rank percentile (q in (0, 1]) of `v`; 0 for an empty list.
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

nlohmann::json summary(const std::vector<double>& v) {
  return {{"count", v.size()},
          {"median", percentile(v, 0.5)},
          {"p95", percentile(v, 0.95)},
          {"max", v.empty() ? 0.0 : *std::max_element(v.begin(), v.end())}};
}

struct Options {
  std::string replay, screenshot, journal, report, size = "1280x800";
  std::string session, export_path, import_mesh;  // session file, export target, base mesh
  double speed = 0.0;  // replay speed; 0: as fast as frames allow
  bool no_panel = false;
};

std::pair<int, int> parse_size(const std::string& s) {
  static const std::regex re(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw ps::app::CommandFailed("--size " + s + ": expected WIDTHxHEIGHT");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 64 || h < 64 || w > 8192 || h > 8192) throw ps::app::CommandFailed("--size " + s + ": each side must lie in [64, 8192]");
  return {w, h};
}

// Rotate `v` about unit `axis` by `angle` radians (Rodrigues).
ps::Vec3 rotate(const ps::Vec3& v, const ps::Vec3& axis, double angle) {
  return v * std::cos(angle) + axis.cross(v) * std::sin(angle) + axis * axis.dot(v) * (1.0 - std::cos(angle));
}

class WindowApp {
 public:
  WindowApp(const Options& o, int w, int h) : o_(o), width_(w), height_(h) {}

  void run() {
    ps::engine::WindowOptions wo;
    wo.width = width_;
    wo.height = height_;
    wo.validation = ps::engine::validation_requested_by_environment();
    wo.panel = !o_.no_panel;
    auto presenter = ps::engine::WindowPresenter::create(wo);
    if (!presenter) throw ps::app::CommandFailed("cannot open the window: " + presenter.message());
    win_ = std::move(*presenter);
    // A finished preview wakes the UI thread from its wait for events.
    worker_ = std::make_unique<ps::app::PreviewWorker>(ps::SessionParams{}, [] { glfwPostEmptyEvent(); });
    // `save` actions write files only for live input: replaying a journal must not rewrite them.
    worker_->set_save_handler([this](const ps::SketchSession& s, const std::string& path) {
      if (!live_files_) return;
      const bool session_file = std::filesystem::path(path).extension() == ".json";
      const auto st = session_file ? ps::save_session(path, s) : ps::export_model(path, s.state().model);
      std::cerr << "planesketch: " << (st ? (session_file ? "session saved to " : "model exported to ") + path
                                          : "not saved: " + st.message())
                << "\n";
    });
    if (!o_.import_mesh.empty()) open_file("mesh", o_.import_mesh, 0.0);
    if (!o_.session.empty() && std::filesystem::exists(o_.session)) open_file("session", o_.session, 0.0);

    if (!o_.replay.empty()) {
      run_replay();
      // With a screenshot requested the run is a test: stop here. Otherwise keep the window
      // open for sketching on top of the replayed model.
      if (!o_.screenshot.empty() || win_->should_close()) {
        finish_report();
        return;
      }
    } else {
      start_session();
    }
    run_live();
    finish_report();
  }

 private:
  // Replayed events reach the worker through this sink, which also keeps what the UI shows of
  // them: the stroke in progress and the pen-up time of each stroke.
  class ReplayFeed : public ps::EventSink {
   public:
    explicit ReplayFeed(WindowApp& app) : app_(app) {}
    void on_header(const ps::LogHeader& h) override { app_.worker_->on_header(h); }
    void on_pen_sample(const ps::PenSample& s) override {
      app_.worker_->on_pen_sample(s);
      // The replayer groups strokes too and calls on_stroke; this grouper only tells what to draw.
      if (!grouper_.add(s) && grouper_.in_stroke()) app_.extend_live(s);
    }
    void on_action(const ps::TimedEvent& e) override {
      app_.worker_->on_action(e);
      app_.need_redraw_ = true;
    }
    void on_stroke(const ps::Stroke& stroke) override {
      app_.submit_stroke(stroke, app_.replay_pen_up(stroke));
    }

   private:
    WindowApp& app_;
    ps::StrokeGrouper grouper_;
  };

  // === Replay through the window: the same driver, paced by frames (or real time with --speed).
  void run_replay() {
    std::vector<std::string> warnings;
    auto log = ps::read_stroke_log(o_.replay, &warnings);
    if (!log) throw ps::app::CommandFailed(log.message());
    for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";
    replayed_ = *log;
    ps::StrokeReplayer replayer(std::move(*log));
    ReplayFeed feed(*this);
    replay_t0_ = Clock::now();
    while (!win_->should_close() && !replayer.done()) {
      wait_for_events(o_.speed > 0.0 ? 0.004 : 0.0);
      const auto busy = Clock::now();
      if (o_.speed > 0.0) {
        replayer.replay_until(ms_between(replay_t0_, Clock::now()) * o_.speed, feed);
      } else {
        replayer.replay_until(replayer.clock_ms() + 2000.0, feed);  // two log seconds per frame
      }
      frame(busy);
    }
    if (replayer.done()) replayer.replay_all(feed);  // delivers the end of the log
    // Keep drawing until the worker has caught up, so the last strokes' previews are presented.
    while (!win_->should_close() && !worker_->caught_up()) {
      wait_for_events(0.1);
      frame(Clock::now());
    }
    worker_->wait_idle();
    frame(Clock::now(), true);
    const auto snap = worker_->latest();
    for (const auto& m : snap->messages) std::cerr << "planesketch: t=" << m.t << " ms: " << m.text << "\n";
    for (const auto& m : snap->notices) std::cerr << "planesketch: t=" << m.t << " ms: note: " << m.text << "\n";
    seen_messages_ = snap->messages.size();
    seen_notices_ = snap->notices.size();
    if (!o_.screenshot.empty()) screenshot();
  }

  // The wall-clock pen-up of a replayed stroke: with --speed the time the log's clock maps to
  // (so frame pacing counts against the latency, as it does for a live pen), else its delivery.
  Clock::time_point replay_pen_up(const ps::Stroke& stroke) const {
    const auto now = Clock::now();
    if (o_.speed <= 0.0 || stroke.samples.empty()) return now;
    const auto at = replay_t0_ + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double, std::milli>(stroke.samples.back().t / o_.speed));
    return std::min(at, now);
  }

  // A new session: the default header (three basic planes, a z-up view).
  void start_session() {
    ps::LogHeader header;
    header.viewport_width = width_;
    header.viewport_height = height_;
    header.camera.width = width_;
    header.camera.height = height_;
    header.camera.up = ps::Vec3::UnitZ();
    header.camera.eye = ps::Vec3(3.2, -4.2, 2.4);
    header.generator = "planesketch window";
    worker_->on_header(header);
  }

  // === Live input (journaled)
  void run_live() {
    ps::LogHeader header;
    header.viewport_width = width_;
    header.viewport_height = height_;
    header.camera = worker_->input().camera;
    header.camera.width = width_;
    header.camera.height = height_;
    header.planes = worker_->input().planes;
    header.generator = "planesketch window";
    if (!replayed_)  // the next start offers to recover a session that died
      if (const auto j = ps::app::newest_unfinished_journal(ps::app::journal_dir()))
        std::cerr << "planesketch: an unfinished session journal is waiting: " << j->path.string()
                  << " (recover it with: planesketch --recover " << j->path.string()
                  << " -o recovered.obj, or continue it with: planesketch window --replay " << j->path.string() << ")\n";
    const std::string journal = o_.journal.empty() ? ps::app::new_journal_path(ps::app::journal_dir()) : o_.journal;
    if (replayed_) header = replayed_->header;  // the journal continues the replayed log
    auto rec = ps::StrokeRecorder::open(journal, header);
    if (!rec) throw ps::app::CommandFailed("cannot open the journal: " + rec.message());
    recorder_.emplace(std::move(*rec));
    // Files opened at start come first: the replayed events (if any) were applied after them.
    for (const auto& e : startup_opens_)
      if (auto st = recorder_->record(e.t, e.event); !st) throw ps::app::CommandFailed("cannot write the journal: " + st.message());
    double t_origin = 0.0;
    if (replayed_) {
      for (const auto& e : replayed_->events)
        if (auto st = recorder_->record(e.t, e.event); !st)
          throw ps::app::CommandFailed("cannot write the journal: " + st.message());
      if (!replayed_->events.empty()) t_origin = replayed_->events.back().t + 1.0;
    }
    std::cerr << "planesketch: journal " << journal << " (replay it with: planesketch replay " << journal << ")\n";

    ps::TabletMapping mapping;
    auto tablet = ps::LibinputTabletReader::open(mapping);
    if (!tablet) std::cerr << "planesketch: pen: " << tablet.message() << "; using the mouse (pressure 1)\n";

    live_files_ = true;
    const auto t0 = Clock::now();
    GLFWwindow* gw = win_->window();
    need_redraw_ = true;
    while (!win_->should_close()) {
      // A tablet is polled, not an event source: wake at its rate; the mouse and the worker wake us.
      wait_for_events(tablet ? 0.004 : 0.05);
      const auto busy = Clock::now();
      const double t = t_origin + ms_between(t0, busy);
      panel_t_ = t;
      if (win_->panel_wants_keyboard()) {
        need_redraw_ = true;  // typing into the panel: draw every frame
      } else {
        handle_keys(gw, t);
      }
      if (tablet) {
        std::vector<ps::PenSample> samples;
        if (auto st = (*tablet)->poll(samples); st)
          for (const auto& s : samples) pen(s);
      }
      handle_mouse(gw, t);
      frame(busy);
    }
    // A clean exit: the end marker tells crash recovery this session needs none.
    if (auto st = recorder_->finish(); !st) std::cerr << "planesketch: journal: " << st.message() << "\n";
  }

  // Returns at once when a frame is due, else waits for input or a finished preview (at most
  // `timeout_s`; 0 polls).
  void wait_for_events(double timeout_s) {
    if (timeout_s <= 0.0 || need_redraw_ || worker_->latest() != shown_) {
      win_->poll_events();
    } else {
      glfwWaitEventsTimeout(timeout_s);
    }
  }

  // Opens a session file or a base mesh as a journaled `open` event (docs/stroke-log.md): the
  // driver loads it on the worker, and recovery opens the same file again, refusing one whose
  // content changed. Before the journal exists (files given at start) the event waits for it.
  void open_file(const std::string& kind, const std::string& path, double t) {
    auto ev = ps::app::open_file_event(kind, path);
    if (!ev) {
      std::cerr << "planesketch: " << (kind == "mesh" ? "mesh not imported: " : "session not loaded: ") << ev.message() << "\n";
      return;
    }
    if (recorder_) {
      act(t, *ev);
    } else {
      startup_opens_.push_back(ps::TimedEvent{t, 0, *ev});
      worker_->on_action(startup_opens_.back());
    }
  }

  void act(double t, const ps::Event& e) {
    if (recorder_) (void)recorder_->record(t, e);  // journal first: nothing is lost on a crash
    worker_->on_action(ps::TimedEvent{t, 0, e});
    need_redraw_ = true;
  }

  void pen(const ps::PenSample& s) {
    if (recorder_) (void)recorder_->record(s);  // fsync at pen-up, before the stroke is applied
    worker_->on_pen_sample(s);
    if (auto stroke = grouper_.add(s)) {
      submit_stroke(*stroke, Clock::now());
    } else if (grouper_.in_stroke()) {
      extend_live(s);
    }
  }

  // The stroke goes to the worker; its pen-up time waits for the frame that shows its result.
  void submit_stroke(const ps::Stroke& stroke, Clock::time_point pen_up) {
    worker_->on_stroke(stroke);
    pen_up_.push_back(pen_up);
    live_.clear();
    need_redraw_ = true;
  }

  // The stroke in progress, lifted onto the selected plane as the driver will lift it.
  void extend_live(const ps::PenSample& s) {
    if (auto p = worker_->input().lift(s.x, s.y)) live_.push_back(*p);
    need_redraw_ = true;
  }

  void handle_keys(GLFWwindow* gw, double t) {
    auto pressed = [&](int key) {
      const bool down = glfwGetKey(gw, key) == GLFW_PRESS;
      const bool edge = down && !keys_[key];
      keys_[key] = down;
      return edge;
    };
    const bool ctrl = glfwGetKey(gw, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(gw, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    for (int k = 0; k < 3; ++k)
      if (pressed(GLFW_KEY_1 + k)) {
        act(t, ps::SelectPlane{k});
        face_selected_plane(t);
      }
    const int sel = worker_->input().selected_plane;
    if (pressed(GLFW_KEY_UP) || pressed(GLFW_KEY_DOWN)) {
      const double step = glfwGetKey(gw, GLFW_KEY_UP) == GLFW_PRESS ? 0.04 : -0.04;
      const auto plane = worker_->input().current_plane();
      if (plane) act(t, ps::TranslatePlane{sel, plane->offset + step});
    }
    if (ctrl && pressed(GLFW_KEY_Z)) act(t, ps::Undo{});
    if (ctrl && pressed(GLFW_KEY_Y)) act(t, ps::Redo{});
    if (ctrl && pressed(GLFW_KEY_S)) {
      if (o_.session.empty()) std::cerr << "planesketch: Ctrl+S saves to --session FILE.json; none was given\n";
      else act(t, ps::Save{o_.session});
    }
    if (ctrl && pressed(GLFW_KEY_E)) {
      if (o_.export_path.empty()) std::cerr << "planesketch: Ctrl+E exports to --export FILE; none was given\n";
      else act(t, ps::Save{o_.export_path});
    }
    if (ctrl && pressed(GLFW_KEY_O)) {
      if (o_.session.empty()) std::cerr << "planesketch: Ctrl+O opens --session FILE.json; none was given\n";
      else open_file("session", o_.session, t);
      need_redraw_ = true;
    }
    if (!ctrl && pressed(GLFW_KEY_E)) eraser_ = !eraser_;
    if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(gw, GLFW_TRUE);
  }

  // Turn the view to face the selected plane (3.2.1), keeping the distance to the target.
  void face_selected_plane(double t) {
    const auto plane = worker_->input().current_plane();
    if (!plane) return;
    ps::Camera cam = worker_->input().camera;
    const double dist = (cam.eye - cam.target).norm();
    ps::Vec3 n = plane->normal;
    if (n.dot(cam.eye - cam.target) < 0.0) n = -n;
    // Tilt slightly so the plane is seen face-on but the other planes keep some depth cue.
    cam.eye = cam.target + (n + 0.15 * cam.up.cross(n)).normalized() * dist;
    if (std::abs(cam.up.normalized().dot(n)) > 0.99) cam.up = n.unitOrthogonal();
    act(t, ps::CameraChange{cam});
  }

  void handle_mouse(GLFWwindow* gw, double t) {
    double x = 0, y = 0;
    glfwGetCursorPos(gw, &x, &y);
    int fw = 0, fh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(gw, &fw, &fh);
    glfwGetWindowSize(gw, &ww, &wh);
    if (ww > 0 && wh > 0) {  // HiDPI: cursor in window units, strokes in framebuffer pixels
      x *= static_cast<double>(fw) / ww;
      y *= static_cast<double>(fh) / wh;
    }
    // A press over the panel is the panel's; a stroke or orbit already going on continues.
    const bool over_panel = win_->panel_wants_mouse();
    const bool left = glfwGetMouseButton(gw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && (left_was_down_ || !over_panel);
    const bool right_down = glfwGetMouseButton(gw, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && (right_was_down_ || !over_panel);
    if (!o_.no_panel && (x != last_x_ || y != last_y_ || left != left_was_down_ || right_down != right_was_down_))
      need_redraw_ = true;  // the panel follows the pointer
    if (left || left_was_down_) {
      ps::PenSample s = ps::pointer_sample(t, x, y, left, left_was_down_);
      if (eraser_) s.tool = ps::Tool::kEraser;
      pen(s);
    }
    left_was_down_ = left;
    // Arcball-style orbit with the right button.
    const bool right = right_down;
    if (right && right_was_down_ && (x != last_x_ || y != last_y_)) {
      ps::Camera cam = worker_->input().camera;
      const ps::Vec3 off = cam.eye - cam.target;
      const double dx = (x - last_x_) * 0.01, dy = (y - last_y_) * 0.01;
      ps::Vec3 o = rotate(off, cam.up.normalized(), -dx);
      const ps::Vec3 side = o.cross(cam.up).normalized();
      o = rotate(o, side, -dy);
      cam.eye = cam.target + o;
      orbit_cam_ = cam;
      worker_->on_action(ps::TimedEvent{t, 0, ps::CameraChange{cam}});
      need_redraw_ = true;
    }
    if (!right && right_was_down_ && orbit_cam_) {
      if (recorder_) (void)recorder_->record(t, ps::CameraChange{*orbit_cam_});
      orbit_cam_.reset();
    }
    right_was_down_ = right;
    last_x_ = x;
    last_y_ = y;
  }

  // === One frame: the newest preview, presented when anything changed. `busy_since` is when
  // the UI thread stopped waiting for events; the time from there to the end of the frame is
  // what the UI thread was busy (input, journal, hand-over to the worker, scene, present).
  void frame(Clock::time_point busy_since, bool force = false) {
    worker_->check();
    const auto snap = worker_->latest();
    if (snap != shown_) {
      shown_ = snap;
      need_redraw_ = true;
      if (recorder_) {  // live: say at once why a stroke was refused
        for (std::size_t i = seen_messages_; i < snap->messages.size(); ++i)
          std::cerr << "planesketch: " << snap->messages[i].text << "\n";
        for (std::size_t i = seen_notices_; i < snap->notices.size(); ++i)
          std::cerr << "planesketch: note: " << snap->notices[i].text << "\n";
      }
      // The panel shows the newest refusal or notice until a newer one comes.
      if (snap->messages.size() > seen_messages_) last_message_ = {snap->messages.back().text, true};
      if (snap->notices.size() > seen_notices_) last_message_ = {snap->notices.back().text, false};
      seen_messages_ = snap->messages.size();
      seen_notices_ = snap->notices.size();
    }
    const auto fb = win_->framebuffer_size();
    if (fb != last_fb_) need_redraw_ = true;
    const auto now = Clock::now();
    if (!force && !need_redraw_ && ms_between(last_present_, now) < 250.0) return;
    need_redraw_ = false;  // panel actions below ask for the next frame again
    if (recorder_ && win_->begin_panel()) draw_panel();
    ps::Camera cam = worker_->input().camera;
    bool presented = false;
    if (fb.first > 0 && fb.second > 0) {
      cam.width = fb.first;
      cam.height = fb.second;
      const auto t_present = Clock::now();
      if (auto st = win_->present(ps::app::session_scene(snap->state, worker_->input(), cam, live_, snap->extrusion_plane, &guides(snap))); !st)
        std::cerr << "planesketch: " << st.message() << "\n";
      const auto t_done = Clock::now();
      present_ms_.push_back(ms_between(t_present, t_done));
      presented = true;
      // Strokes whose result this frame shows for the first time.
      for (std::size_t k = presented_strokes_; k < snap->strokes_applied && k < pen_up_.size(); ++k) {
        const double ms = ms_between(pen_up_[k], t_done);
        preview_ms_.push_back(ms);
        std::cerr << "planesketch: stroke " << k + 1 << ": preview presented " << std::lround(ms)
                  << " ms after pen-up\n";
      }
      presented_strokes_ = std::max(presented_strokes_, snap->strokes_applied);
    }
    last_fb_ = fb;
    last_present_ = Clock::now();
    busy_ms_.push_back(ms_between(busy_since, last_present_));
    work_ms_.push_back(busy_ms_.back() - (presented ? present_ms_.back() : 0.0));
  }

  // === The panel: tool mode, reference plane and offset, lambda; the session's state.
  void draw_panel() {
    const ps::InputState& in = worker_->input();
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("planesketch", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing);
    ImGui::TextUnformatted("tool");
    // Two rows: sketching and sculpting, then deformation (handle and target strokes), its
    // region of interest (lasso or brush), stiffness painting and the topology edits of the
    // reconstruction (join, split; app/session_driver.h).
    static const char* const kModes[] = {"sketch", "sculpt", "cut", "tunnel", "smooth", "extrude",
                                         "deform", "roi", "stiffness", "join", "split"};
    for (std::size_t i = 0; i < std::size(kModes); ++i) {
      const char* m = kModes[i];
      if (ImGui::RadioButton(m, in.mode == m) && in.mode != m) act(panel_t_, ps::SetToolMode{m});
      if (i != 5 && i + 1 != std::size(kModes)) ImGui::SameLine();
    }
    ImGui::Separator();
    ImGui::TextUnformatted("reference plane");
    for (int i = 0; i < static_cast<int>(in.planes.size()); ++i) {
      const int axis = in.planes[static_cast<std::size_t>(i)].axis();
      const std::string name = axis >= 0 ? std::string(1, "xyz"[axis]) : "plane " + std::to_string(i);
      if (ImGui::RadioButton(name.c_str(), in.selected_plane == i) && in.selected_plane != i) {
        act(panel_t_, ps::SelectPlane{i});
        face_selected_plane(panel_t_);
      }
      ImGui::SameLine();
      const std::string label = "offset##" + std::to_string(i);
      ImGui::SetNextItemWidth(120.0f);
      if (auto v = panel_value(label, in.planes[static_cast<std::size_t>(i)].offset, false, -10.0f, 10.0f))
        act(panel_t_, ps::TranslatePlane{i, *v});
    }
    ImGui::Separator();
    const auto lambda = in.parameters.find("lambda");
    ImGui::SetNextItemWidth(180.0f);
    if (auto v = panel_value("lambda", lambda != in.parameters.end() ? lambda->second : ps::SessionParams{}.lambda, true, 0.0f, 1.0f))
      act(panel_t_, ps::SetParameter{"lambda", *v});
    // The value painted in "stiffness" mode (1: as stiff as lambda 1 there, 0: as lambda 0).
    const auto stiffness = in.parameters.find("stiffness");
    ImGui::SetNextItemWidth(180.0f);
    if (auto v = panel_value("stiffness", stiffness != in.parameters.end() ? stiffness->second : 1.0, true, 0.0f, 1.0f))
      act(panel_t_, ps::SetParameter{"stiffness", *v});
    // The extrusion's reference plane (drawn while an extrusion waits for its silhouette) turned
    // about the region's normal (spin) and about its diameter (tilt), radians; read when the
    // silhouette is drawn (docs/sculpting.md).
    if (in.mode == "extrude" || in.mode == "sculpt") {
      for (const auto& [name, limit] : {std::pair{"extrude_spin", 3.14f}, std::pair{"extrude_tilt", 1.5f}}) {
        const auto it = in.parameters.find(name);
        ImGui::SetNextItemWidth(180.0f);
        if (auto v = panel_value(name, it != in.parameters.end() ? it->second : 0.0, true, -limit, limit))
          act(panel_t_, ps::SetParameter{name, *v});
      }
    }
    // The deformation tool (docs/deformation.md): the base plane turned about its axis (radians,
    // read when the target stroke is drawn), a shadow stroke on the projection plane after the
    // target, and the radii of the default region and of brushes (fractions of the diagonal).
    if (in.mode == "deform" || in.mode == "sculpt" || in.mode == "roi" || in.mode == "stiffness") {
      auto value = [&](const char* name, double fallback) {
        const auto it = in.parameters.find(name);
        return it != in.parameters.end() ? it->second : fallback;
      };
      struct Slider {
        const char* name;
        double fallback;
        float lo, hi;
      };
      for (const Slider& sl : {Slider{"deform_rotation", 0.0, -3.14f, 3.14f},
                               Slider{"deform_radius", ps::app::kDefaultRoiRadius, 0.01f, 1.0f},
                               Slider{"brush_radius", ps::app::kDefaultBrushRadius, 0.005f, 0.5f}}) {
        ImGui::SetNextItemWidth(180.0f);
        if (auto v = panel_value(sl.name, value(sl.name, sl.fallback), true, sl.lo, sl.hi))
          act(panel_t_, ps::SetParameter{sl.name, *v});
      }
      bool shadow = value("deform_shadow", 0.0) != 0.0;
      if (ImGui::Checkbox("deform_shadow", &shadow)) act(panel_t_, ps::SetParameter{"deform_shadow", shadow ? 1.0 : 0.0});
    }
    const auto& st = shown_->state;
    ImGui::Text("%zu sections, %zu faces%s", st.sections.curves.size(), st.model.faces.size(),
                worker_->caught_up() ? "" : ", rebuilding");
    if (!last_message_.first.empty()) {
      ImGui::Separator();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
      const ImVec4 color = last_message_.second ? ImVec4(0.95f, 0.35f, 0.30f, 1.0f) : ImVec4(0.95f, 0.80f, 0.35f, 1.0f);
      ImGui::TextColored(color, "%s", last_message_.first.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::End();
  }

  // A slider (or a drag field, ctrl+click to type) showing `current` unless the user is
  // editing it; the new value once the edit ends (one journaled action per edit).
  std::optional<double> panel_value(const std::string& label, double current, bool slider, float lo, float hi) {
    auto& [value, editing] = panel_values_[label];
    if (!editing) value = static_cast<float>(current);
    if (slider) {
      ImGui::SliderFloat(label.c_str(), &value, lo, hi, "%.2f");
    } else {
      ImGui::DragFloat(label.c_str(), &value, 0.01f, lo, hi, "%.3f");
    }
    editing = ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) return static_cast<double>(value);
    return std::nullopt;
  }

  // The sketching guides of the selected plane over `snap`, recomputed only when the snapshot,
  // the selected plane or the mode changed (slicing the model is not a per-frame cost).
  const ps::app::SketchGuides& guides(const std::shared_ptr<const ps::app::PreviewSnapshot>& snap) {
    const ps::InputState& in = worker_->input();
    const auto plane = in.current_plane();
    const auto key = std::make_tuple(snap.get(), in.mode, plane ? plane->normal : ps::Vec3::Zero(), plane ? plane->offset : 0.0,
                                     plane.has_value());
    if (!guides_key_ || *guides_key_ != key) {
      const auto t0 = Clock::now();
      guides_ = ps::app::sketch_guides(snap->state, in);
      guides_ms_.push_back(ms_between(t0, Clock::now()));
      guides_key_ = key;
      guides_snap_ = snap;  // keeps the keyed snapshot alive, so its address is not reused
    }
    return guides_;
  }

  void screenshot() {
    auto [fw, fh] = win_->framebuffer_size();
    ps::Camera cam = worker_->input().camera;
    cam.width = fw > 0 ? fw : width_;
    cam.height = fh > 0 ? fh : height_;
    ps::engine::RendererOptions ro;
    ro.width = cam.width;
    ro.height = cam.height;
    auto r = ps::engine::create_offscreen_renderer(ro);
    if (!r) throw ps::app::CommandFailed("screenshot: " + r.message());
    const auto snap = worker_->latest();
    auto img = (*r)->render(ps::app::session_scene(snap->state, worker_->input(), cam, {}, snap->extrusion_plane, &guides(snap)));
    if (!img) throw ps::app::CommandFailed("screenshot: " + img.message());
    if (auto st = ps::engine::write_png(o_.screenshot, *img); !st) throw ps::app::CommandFailed(st.message());
  }

  // The latency summary on stderr and, with --report, the figures as JSON.
  void finish_report() {
    const auto snap = worker_->latest();
    std::cerr << "planesketch: pen-up to presented preview over " << preview_ms_.size() << " strokes: median "
              << std::lround(percentile(preview_ms_, 0.5)) << " ms, p95 " << std::lround(percentile(preview_ms_, 0.95))
              << " ms; UI thread busy per frame: max " << std::lround(percentile(busy_ms_, 1.0)) << " ms, p95 "
              << std::lround(percentile(busy_ms_, 0.95)) << " ms over " << busy_ms_.size() << " frames (outside present: max "
              << std::lround(percentile(work_ms_, 1.0)) << " ms); "
              << worker_->superseded() << " superseded previews\n";
    if (o_.report.empty()) return;
    nlohmann::json j;
    j["device"] = win_->device_name();
    j["validation_messages"] = win_->validation_messages();
    j["frames_presented"] = win_->frames_presented();
    j["sections"] = snap->state.sections.curves.size();
    j["faces"] = snap->state.model.faces.size();
    j["strokes"] = pen_up_.size();
    j["preview_latency_ms"] = preview_ms_;
    j["preview_latency"] = summary(preview_ms_);
    j["rebuild_ms"] = snap->rebuild_ms;
    j["rebuild"] = summary(snap->rebuild_ms);
    j["ui_busy_per_frame"] = summary(busy_ms_);
    j["ui_work_per_frame"] = summary(work_ms_);  // busy minus present: input, journal, hand-over, scene
    j["present_ms"] = summary(present_ms_);
    j["guides_ms"] = summary(guides_ms_);  // crossing points and model section of the selected plane
    j["previews_published"] = worker_->published();
    j["previews_superseded"] = worker_->superseded();
    std::ofstream f(o_.report);
    f << j.dump(2) << "\n";
    if (!f) throw ps::app::CommandFailed(o_.report + ": cannot write report");
  }

  Options o_;
  int width_, height_;
  std::atomic<bool> live_files_{false};  // read by the save handler on the worker thread (before worker_)
  std::unique_ptr<ps::engine::WindowPresenter> win_;
  std::unique_ptr<ps::app::PreviewWorker> worker_;  // after win_: stops before GLFW ends
  std::shared_ptr<const ps::app::PreviewSnapshot> shown_;
  std::optional<ps::StrokeRecorder> recorder_;
  std::optional<ps::StrokeLog> replayed_;
  std::vector<ps::TimedEvent> startup_opens_;  // files opened before the journal, journaled first
  ps::StrokeGrouper grouper_;
  std::vector<ps::Vec3> live_;
  std::size_t seen_messages_ = 0, seen_notices_ = 0;
  std::pair<std::string, bool> last_message_;  // newest refusal (true) or notice (false), for the panel
  // === Sketching guides of the selected plane (cached per snapshot, plane and mode)
  ps::app::SketchGuides guides_;
  std::optional<std::tuple<const ps::app::PreviewSnapshot*, std::string, ps::Vec3, double, bool>> guides_key_;
  std::shared_ptr<const ps::app::PreviewSnapshot> guides_snap_;
  std::vector<double> guides_ms_;
  std::map<int, bool> keys_;
  bool left_was_down_ = false, right_was_down_ = false, eraser_ = false;
  double last_x_ = 0, last_y_ = 0;
  std::optional<ps::Camera> orbit_cam_;
  // === Frame pacing and latency figures
  bool need_redraw_ = true;
  std::pair<int, int> last_fb_{0, 0};
  Clock::time_point last_present_{}, replay_t0_{};
  std::vector<Clock::time_point> pen_up_;  // per submitted stroke
  std::size_t presented_strokes_ = 0;      // strokes whose preview has been presented
  std::vector<double> preview_ms_, busy_ms_, work_ms_, present_ms_;
  // === Panel
  double panel_t_ = 0.0;  // log time of the frame's input (panel actions are journaled at it)
  std::map<std::string, std::pair<float, bool>> panel_values_;  // value shown, being edited
};

void setup(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("window", "Open the interactive window (needs a display)");
  cmd->add_option("--replay", o->replay, "Drive the window from a stroke log");
  cmd->add_option("--screenshot", o->screenshot, "After --replay, write the final view to this PNG and exit");
  cmd->add_option("--journal", o->journal, "Where to write the session's stroke log (default: ~/.local/state/planesketch)");
  cmd->add_option("--report", o->report, "At exit, write pen-up to preview latencies and frame times (JSON)");
  cmd->add_option("--size", o->size, "Window size WIDTHxHEIGHT");
  cmd->add_flag("--no-panel", o->no_panel, "No Dear ImGui panel over the canvas");
  cmd->add_option("--session", o->session, "Session file: loaded at start if it exists; Ctrl+S saves it, Ctrl+O reloads it");
  cmd->add_option("--export", o->export_path, "Ctrl+E exports the model here (.obj .off .ply .stl .glb)");
  cmd->add_option("--import", o->import_mesh, "Start from this mesh as the base (to sculpt or deform it)");
  cmd->add_option("--speed", o->speed, "Replay speed relative to the log's clock (0: as fast as frames allow)");
  cmd->callback([o] {
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
      throw ps::app::CommandFailed("window: no display (DISPLAY and WAYLAND_DISPLAY are unset); use 'planesketch replay' headless", 2);
    const auto [w, h] = parse_size(o->size);
    WindowApp app(*o, w, h);
    app.run();
  });
}

}  // namespace

PLANESKETCH_COMMAND(5, setup);
