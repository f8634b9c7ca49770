// planesketch window [--replay LOG] [--screenshot FILE] [--journal FILE] [--size WxH]
// The interactive window: GLFW + Vulkan swapchain (engine/window_presenter.h), pen input from
// libinput when the seat allows it, else the mouse (pressure 1), every event journaled to a
// stroke log as it happens (fsync per stroke, end marker on a clean exit) and applied through the same SessionDriver that
// headless replay uses.
//
// Keys: 1/2/3 select the x/y/z plane (the view turns to face it), Up/Down move the selected plane
// by 0.04, Ctrl+Z undo, Ctrl+Y redo, E toggles the mouse eraser, Esc quits. Left drag sketches;
// right drag orbits the camera (arcball about the target).
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <regex>
#include <thread>

#include "app/commands.h"
#include "app/journal.h"
#include "app/session_driver.h"
#include "app/session_scene.h"
#include "engine/image.h"
#include "engine/renderer.h"
#include "engine/window_presenter.h"
#include "input/pen_input.h"
#include "input/stroke_log_io.h"
#include "input/stroke_recorder.h"

namespace {

struct Options {
  std::string replay, screenshot, journal, size = "1280x800";
  double speed = 0.0;  // replay speed; 0: as fast as frames allow
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
    auto presenter = ps::engine::WindowPresenter::create(wo);
    if (!presenter) throw ps::app::CommandFailed("cannot open the window: " + presenter.message());
    win_ = std::move(*presenter);

    if (!o_.replay.empty()) {
      run_replay();
      // With a screenshot requested the run is a test: stop here. Otherwise keep the window
      // open for sketching on top of the replayed model.
      if (!o_.screenshot.empty() || win_->should_close()) return;
    } else {
      start_session();
    }
    run_live();
  }

 private:
  // === Replay through the window: the same driver, paced by frames (or real time with --speed).
  void run_replay() {
    std::vector<std::string> warnings;
    auto log = ps::read_stroke_log(o_.replay, &warnings);
    if (!log) throw ps::app::CommandFailed(log.message());
    for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";
    replayed_ = *log;
    ps::StrokeReplayer replayer(std::move(*log));
    const auto t0 = std::chrono::steady_clock::now();
    while (!win_->should_close() && !replayer.done()) {
      win_->poll_events();
      if (o_.speed > 0.0) {
        const double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        replayer.replay_until(elapsed * o_.speed, driver_);
      } else {
        replayer.replay_until(replayer.clock_ms() + 2000.0, driver_);  // two log seconds per frame
      }
      present(driver_.input().camera);
    }
    if (replayer.done()) replayer.replay_all(driver_);  // delivers the end of the log
    for (const auto& m : driver_.messages()) std::cerr << "planesketch: t=" << m.t << " ms: " << m.text << "\n";
    present(driver_.input().camera);
    if (!o_.screenshot.empty()) screenshot();
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
    driver_.on_header(header);
  }

  // === Live input (journaled)
  void run_live() {
    ps::LogHeader header;
    header.viewport_width = width_;
    header.viewport_height = height_;
    header.camera = driver_.input().camera;
    header.camera.width = width_;
    header.camera.height = height_;
    header.planes = driver_.input().planes;
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

    const auto t0 = std::chrono::steady_clock::now();
    GLFWwindow* gw = win_->window();
    while (!win_->should_close()) {
      win_->poll_events();
      const double t = t_origin + std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      handle_keys(gw, t);
      if (tablet) {
        std::vector<ps::PenSample> samples;
        if (auto st = (*tablet)->poll(samples); st)
          for (const auto& s : samples) pen(s);
      }
      handle_mouse(gw, t);
      present(driver_.input().camera);
    }
    // A clean exit: the end marker tells crash recovery this session needs none.
    if (auto st = recorder_->finish(); !st) std::cerr << "planesketch: journal: " << st.message() << "\n";
  }

  void act(double t, const ps::Event& e) {
    if (recorder_) (void)recorder_->record(t, e);  // journal first: nothing is lost on a crash
    ps::TimedEvent te{t, 0, e};
    driver_.on_action(te);
  }

  void pen(const ps::PenSample& s) {
    if (recorder_) (void)recorder_->record(s);
    driver_.on_pen_sample(s);
    if (auto stroke = grouper_.add(s)) {
      driver_.on_stroke(*stroke);
      for (std::size_t i = seen_messages_; i < driver_.messages().size(); ++i)
        std::cerr << "planesketch: " << driver_.messages()[i].text << "\n";
      seen_messages_ = driver_.messages().size();
      live_.clear();
    } else if (grouper_.in_stroke()) {
      if (auto p = driver_.input().lift(s.x, s.y)) live_.push_back(*p);
    }
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
    const int sel = driver_.input().selected_plane;
    if (pressed(GLFW_KEY_UP) || pressed(GLFW_KEY_DOWN)) {
      const double step = glfwGetKey(gw, GLFW_KEY_UP) == GLFW_PRESS ? 0.04 : -0.04;
      const auto plane = driver_.input().current_plane();
      if (plane) act(t, ps::TranslatePlane{sel, plane->offset + step});
    }
    if (ctrl && pressed(GLFW_KEY_Z)) act(t, ps::Undo{});
    if (ctrl && pressed(GLFW_KEY_Y)) act(t, ps::Redo{});
    if (pressed(GLFW_KEY_E)) eraser_ = !eraser_;
    if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(gw, GLFW_TRUE);
  }

  // Turn the view to face the selected plane (3.2.1), keeping the distance to the target.
  void face_selected_plane(double t) {
    const auto plane = driver_.input().current_plane();
    if (!plane) return;
    ps::Camera cam = driver_.input().camera;
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
    const bool left = glfwGetMouseButton(gw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    if (left || left_was_down_) {
      ps::PenSample s = ps::pointer_sample(t, x, y, left, left_was_down_);
      if (eraser_) s.tool = ps::Tool::kEraser;
      pen(s);
    }
    left_was_down_ = left;
    // Arcball-style orbit with the right button.
    const bool right = glfwGetMouseButton(gw, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (right && right_was_down_) {
      ps::Camera cam = driver_.input().camera;
      const ps::Vec3 off = cam.eye - cam.target;
      const double dx = (x - last_x_) * 0.01, dy = (y - last_y_) * 0.01;
      ps::Vec3 o = rotate(off, cam.up.normalized(), -dx);
      const ps::Vec3 side = o.cross(cam.up).normalized();
      o = rotate(o, side, -dy);
      cam.eye = cam.target + o;
      orbit_cam_ = cam;
      driver_.on_action(ps::TimedEvent{t, 0, ps::CameraChange{cam}});
    }
    if (!right && right_was_down_ && orbit_cam_) {
      if (recorder_) (void)recorder_->record(t, ps::CameraChange{*orbit_cam_});
      orbit_cam_.reset();
    }
    right_was_down_ = right;
    last_x_ = x;
    last_y_ = y;
  }

  void present(ps::Camera cam) {
    auto [fw, fh] = win_->framebuffer_size();
    if (fw <= 0 || fh <= 0) return;
    cam.width = fw;
    cam.height = fh;
    if (auto st = win_->present(ps::app::session_scene(driver_, cam, live_)); !st)
      std::cerr << "planesketch: " << st.message() << "\n";
  }

  void screenshot() {
    auto [fw, fh] = win_->framebuffer_size();
    ps::Camera cam = driver_.input().camera;
    cam.width = fw > 0 ? fw : width_;
    cam.height = fh > 0 ? fh : height_;
    ps::engine::RendererOptions ro;
    ro.width = cam.width;
    ro.height = cam.height;
    auto r = ps::engine::create_offscreen_renderer(ro);
    if (!r) throw ps::app::CommandFailed("screenshot: " + r.message());
    auto img = (*r)->render(ps::app::session_scene(driver_, cam));
    if (!img) throw ps::app::CommandFailed("screenshot: " + img.message());
    if (auto st = ps::engine::write_png(o_.screenshot, *img); !st) throw ps::app::CommandFailed(st.message());
  }

  Options o_;
  int width_, height_;
  std::unique_ptr<ps::engine::WindowPresenter> win_;
  ps::app::SessionDriver driver_;
  std::optional<ps::StrokeRecorder> recorder_;
  std::optional<ps::StrokeLog> replayed_;
  ps::StrokeGrouper grouper_;
  std::vector<ps::Vec3> live_;
  std::size_t seen_messages_ = 0;
  std::map<int, bool> keys_;
  bool left_was_down_ = false, right_was_down_ = false, eraser_ = false;
  double last_x_ = 0, last_y_ = 0;
  std::optional<ps::Camera> orbit_cam_;
};

void setup(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("window", "Open the interactive window (needs a display)");
  cmd->add_option("--replay", o->replay, "Drive the window from a stroke log");
  cmd->add_option("--screenshot", o->screenshot, "After --replay, write the final view to this PNG and exit");
  cmd->add_option("--journal", o->journal, "Where to write the session's stroke log (default: ~/.local/state/planesketch)");
  cmd->add_option("--size", o->size, "Window size WIDTHxHEIGHT");
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
