// The interactive window: presents scenes through a swapchain, with and without the ImGui
// panel, survives resizes, validation clean. Needs an X display; without one the test re-runs
// itself under xvfb-run when that is installed (Debian: xvfb), and is skipped otherwise.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/renderer.h"
#include "engine/window_presenter.h"

namespace ps::engine {
namespace {

bool has_display() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

std::string self_path() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

Scene test_scene() {
  TriMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  Scene s = default_scene(m, View::iso, 320, 200);
  s.preview = MeshVisual{m, {0.3f, 0.5f, 0.9f, 0.4f}, false};
  return s;
}

// Without a display: this test again, under xvfb-run (skipped without it).
void rerun_under_xvfb(const std::string& test_name) {
  if (std::getenv("PLANESKETCH_UNDER_XVFB")) GTEST_SKIP() << "xvfb-run gave no DISPLAY";
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
  const std::string cmd = "PLANESKETCH_UNDER_XVFB=1 xvfb-run -a -s '-screen 0 1280x800x24' '" + self_path() +
                          "' --gtest_filter=" + test_name;
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << "the test under xvfb-run did not exit normally";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the test failed under xvfb-run (output above)";
}

Result<std::unique_ptr<WindowPresenter>> open_window(bool panel) {
  WindowOptions o;
  o.width = 320;
  o.height = 200;
  o.validation = true;
  o.prefer_gpu = false;
  o.panel = panel;
  return WindowPresenter::create(o);
}

TEST(EngineWindow, PresentsAndResizes) {
  if (!has_display()) return rerun_under_xvfb("EngineWindow.PresentsAndResizes");
  auto w = open_window(false);
  ASSERT_TRUE(w.is_ok()) << w.message();
  WindowPresenter& win = **w;
  const Scene scene = test_scene();
  for (int i = 0; i < 3; ++i) {
    win.poll_events();
    const Status st = win.present(scene);
    ASSERT_TRUE(st.is_ok()) << st.message();
  }
  EXPECT_EQ(win.frames_presented(), 3u);
  EXPECT_EQ(win.swapchain_recreations(), 1u);

  // Resize: the next frames use a new swapchain of the new size.
  glfwSetWindowSize(win.window(), 400, 260);
  for (int i = 0; i < 250 && win.framebuffer_size() != std::pair{400, 260}; ++i) {  // up to 5 s
    glfwWaitEventsTimeout(0.02);
  }
  ASSERT_EQ(win.framebuffer_size(), (std::pair{400, 260}));
  for (int i = 0; i < 3; ++i) {
    win.poll_events();
    const Status st = win.present(scene);
    ASSERT_TRUE(st.is_ok()) << st.message();
  }
  EXPECT_GE(win.swapchain_recreations(), 2u);
  EXPECT_GE(win.frames_presented(), 5u);
  EXPECT_FALSE(win.should_close());
  EXPECT_EQ(win.validation_messages(), 0u);
}

// One frame with a panel like the app's: radio buttons, a slider, a drag field, text.
Status panel_frame(WindowPresenter& win, const Scene& scene, float& value, int& mode) {
  win.poll_events();
  if (win.begin_panel()) {
    ImGui::Begin("panel", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    for (int i = 0; i < 3; ++i) {
      if (ImGui::RadioButton(("mode " + std::to_string(i)).c_str(), mode == i)) mode = i;
      ImGui::SameLine();
    }
    ImGui::NewLine();
    ImGui::SliderFloat("lambda", &value, 0.0f, 1.0f);
    ImGui::DragFloat("offset", &value, 0.01f);
    ImGui::Text("%d faces", static_cast<int>(scene.solid ? scene.solid->mesh.faces.size() : 0));
    ImGui::End();
  }
  return win.present(scene);
}

// The Dear ImGui panel (WindowOptions::panel): frames with panel widgets present through the
// swapchain before and after a resize (new framebuffers for the new images), a frame begun and
// not presented is dropped, frames without begin_panel() still present; validation clean.
TEST(EngineWindow, PresentsWithThePanelAndResizes) {
  if (!has_display()) return rerun_under_xvfb("EngineWindow.PresentsWithThePanelAndResizes");
  auto w = open_window(true);
  ASSERT_TRUE(w.is_ok()) << w.message();
  WindowPresenter& win = **w;
  const Scene scene = test_scene();
  // No swapchain before the first present, so no panel yet.
  EXPECT_FALSE(win.begin_panel());
  float value = 0.5f;
  int mode = 0;
  for (int i = 0; i < 4; ++i) {
    const Status st = panel_frame(win, scene, value, mode);
    ASSERT_TRUE(st.is_ok()) << st.message();
  }
  EXPECT_TRUE(win.begin_panel());  // a panel frame begun and not presented is dropped...
  EXPECT_TRUE(win.begin_panel());  // ...by the next begin_panel
  ASSERT_TRUE(win.present(scene).is_ok());
  ASSERT_TRUE(win.present(scene).is_ok());  // and a frame without the panel
  EXPECT_FALSE(win.panel_wants_keyboard());

  glfwSetWindowSize(win.window(), 400, 260);
  for (int i = 0; i < 250 && win.framebuffer_size() != std::pair{400, 260}; ++i) glfwWaitEventsTimeout(0.02);
  ASSERT_EQ(win.framebuffer_size(), (std::pair{400, 260}));
  for (int i = 0; i < 3; ++i) {
    const Status st = panel_frame(win, scene, value, mode);
    ASSERT_TRUE(st.is_ok()) << st.message();
  }
  EXPECT_GE(win.swapchain_recreations(), 2u);
  EXPECT_GE(win.frames_presented(), 8u);
  EXPECT_EQ(win.validation_messages(), 0u);
}

}  // namespace
}  // namespace ps::engine
