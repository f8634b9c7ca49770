// `planesketch render`: renders real meshes to PNG; bad input gives one clear line, a non-zero
// exit status (never a signal) and no output file.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/image.h"

namespace {

namespace fs = std::filesystem;

// Single-quoted for the shell (paths here contain no quotes).
std::string q(const std::string& s) {
  std::string r;
  r.reserve(s.size() + 2);
  r += '\'';
  r += s;
  r += '\'';
  return r;
}

struct CliRun {
  int exit_code = -1;
  bool signalled = false;
  std::string err;
};

class EngineCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ps_engine_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliRun run(const std::string& args) {
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd =
        q(PLANESKETCH_BINARY) + " render " + args + " 2>" + q(err.string()) + " >/dev/null";
    const int status = std::system(cmd.c_str());
    CliRun r;
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    // The shell reports a child killed by a signal as 128 + n.
    r.signalled = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) > 128);
    std::ifstream in(err);
    std::stringstream ss;
    ss << in.rdbuf();
    r.err = ss.str();
    return r;
  }
  static std::string data(const std::string& name) {
    return std::string(PLANESKETCH_CGAL_DATA) + "/" + name;
  }
  std::string out(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// Lines of stderr that are not the device report.
std::vector<std::string> error_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string l; std::getline(in, l);)
    if (l.find("Vulkan device:") == std::string::npos) lines.push_back(l);
  return lines;
}

TEST_F(EngineCli, RendersElephantWithValidation) {
  if (!fs::exists(data("elephant.off"))) GTEST_SKIP() << "CGAL data is absent";
  const std::string png = out("elephant.png");
  const CliRun r = run(q(data("elephant.off")) + " --png " + q(png) + " --size 320x200 --view iso --validation");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto img = ps::engine::read_png(png);
  ASSERT_TRUE(img.is_ok()) << img.message();
  EXPECT_EQ(img->width, 320);
  EXPECT_EQ(img->height, 200);
  // The elephant covers part of the image: the centre is not background.
  const uint8_t* c = img->pixel(160, 100);
  EXPECT_FALSE(c[0] == 255 && c[1] == 255 && c[2] == 255);

  // --wireframe changes the image; every view renders.
  const std::string wire = out("wire.png");
  ASSERT_EQ(run(q(data("elephant.off")) + " --png " + q(wire) + " --size 320x200 --wireframe")
                .exit_code,
            0);
  auto w = ps::engine::read_png(wire);
  ASSERT_TRUE(w.is_ok());
  EXPECT_GT(ps::engine::compare_images(*img, *w).differing_pixels, 100u);
  for (const char* v : {"x", "y", "z"})
    EXPECT_EQ(run(q(data("elephant.off")) + " --png " + q(out(std::string(v) + ".png")) +
                  " --size 64x48 --view " + v)
                  .exit_code,
              0)
        << v;
}

TEST_F(EngineCli, BadInputGivesOneLineAndNoFile) {
  const std::string png = out("x.png");
  struct Case {
    std::string args;
    std::string expect;  // part of the message
  };
  // A valid mesh of its own (the cases below are about the other arguments), so the test needs
  // no data set.
  const std::string mesh = out("tet.off");
  std::ofstream(mesh) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  fs::create_directories(dir_ / "adir");
  std::ofstream(dir_ / "garbage.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";  // truncated
  const std::vector<Case> cases = {
      {q(out("missing.obj")) + " --png " + q(png), "missing.obj"},
      {q(out("garbage.off")) + " --png " + q(png), "garbage.off"},
      {q(mesh) + " --png " + q(png) + " --size 12", "--size"},
      {q(mesh) + " --png " + q(png) + " --size 0x10", "--size"},
      {q(mesh) + " --png " + q(png) + " --view top", "--view"},
      {q(mesh) + " --png " + q(out("no/such/dir.png")), "does not exist"},
      {q(mesh) + " --png " + q(out("adir")), "directory"},
  };
  for (const auto& c : cases) {
    const CliRun r = run(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_FALSE(r.signalled) << c.args;
    const auto lines = error_lines(r.err);
    EXPECT_EQ(lines.size(), 1u) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(png)) << c.args;
  }
  // No temporary files left behind either.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_TRUE(e.path().filename() == "stderr.txt" || e.path().filename() == "garbage.off" ||
                e.path().filename() == "tet.off" || e.path().filename() == "adir")
        << e.path();
}

}  // namespace
