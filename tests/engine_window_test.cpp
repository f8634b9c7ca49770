// The interactive window: presents scenes through a swapchain, survives resizes, validation
// clean. Needs an X display; without one the test re-runs itself under xvfb-run when that is
// installed (Debian: xvfb), and is skipped otherwise.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

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

TEST(EngineWindow, PresentsAndResizes) {
  if (!has_display()) {
    if (std::getenv("PLANESKETCH_UNDER_XVFB")) GTEST_SKIP() << "xvfb-run gave no DISPLAY";
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string cmd = "PLANESKETCH_UNDER_XVFB=1 xvfb-run -a -s '-screen 0 1280x800x24' '" +
                            self_path() + "' --gtest_filter=EngineWindow.PresentsAndResizes";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << "the test under xvfb-run did not exit normally";
    EXPECT_EQ(WEXITSTATUS(status), 0) << "the test failed under xvfb-run (output above)";
    return;
  }
  WindowOptions o;
  o.width = 320;
  o.height = 200;
  o.validation = true;
  o.prefer_gpu = false;
  auto w = WindowPresenter::create(o);
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

}  // namespace
}  // namespace ps::engine
