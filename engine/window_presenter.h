#pragma once
// An interactive window (GLFW + Vulkan swapchain) presenting the same Scene as the offscreen
// renderer: the scene pass renders into its colour target, which is blitted to the acquired
// swapchain image. Resizing recreates the swapchain and targets; a minimised window skips
// frames. vsync = FIFO present mode; without vsync MAILBOX, else IMMEDIATE, else FIFO.
//
//   auto w = ps::engine::WindowPresenter::create({.title = "planesketch"});
//   while (!(*w)->should_close()) {
//     (*w)->poll_events();
//     scene.camera.width/height are set from the framebuffer size by present();
//     if (auto st = (*w)->present(scene); !st) report(st.message());
//   }
//
// With `panel`, a Dear ImGui layer (Debian's libimgui-dev 1.86 with its GLFW and Vulkan
// backends, as shipped compiled in libimgui.a) is drawn over the scene in a render pass on the
// swapchain image after the blit. The app builds its widgets between begin_panel() and
// present(); the panel's input is read by ImGui's GLFW callbacks (the previous callbacks are
// chained), and panel_wants_mouse()/panel_wants_keyboard() tell the app which input is not
// for the canvas.
//
// Runs under Xvfb with lavapipe (xvfb-run -a -s "-screen 0 1280x800x24").
// One frame in flight: present() waits for the previous frame before it reuses the scene
// pass's buffers, so RAII owners can be replaced between frames without a deletion queue.
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "engine/scene.h"
#include "modeling/status.h"

struct GLFWwindow;

namespace ps::engine {

struct WindowOptions {
  int width = 1280;
  int height = 800;
  std::string title = "planesketch";
  bool vsync = true;
  bool validation = false;  // also on when PLANESKETCH_VALIDATION=1
  bool prefer_gpu = true;
  bool panel = false;  // a Dear ImGui panel over the scene (see above)
  std::function<void(const std::string&)> log;  // null: stderr
};

class WindowPresenter {
 public:
  static Result<std::unique_ptr<WindowPresenter>> create(const WindowOptions& options);
  ~WindowPresenter();
  WindowPresenter(const WindowPresenter&) = delete;
  WindowPresenter& operator=(const WindowPresenter&) = delete;

  bool should_close() const;
  void poll_events();
  // Framebuffer size in pixels (0 x 0 when minimised).
  std::pair<int, int> framebuffer_size() const;
  // Render `scene` (its camera size is replaced by the framebuffer size) and present it.
  // Recreates the swapchain when the window was resized or the surface went out of date.
  Status present(Scene scene);
  // Starts the panel's frame: ImGui widgets made from here to present() are drawn by it.
  // False (and no ImGui frame) without `panel`.
  bool begin_panel();
  bool panel_wants_mouse() const;
  bool panel_wants_keyboard() const;

  GLFWwindow* window() const;  // for the app's input callbacks
  std::string device_name() const;
  std::size_t validation_messages() const;
  std::size_t frames_presented() const;
  std::size_t swapchain_recreations() const;

  struct Impl;

 private:
  explicit WindowPresenter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ps::engine
