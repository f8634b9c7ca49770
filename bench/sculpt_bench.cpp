// Sculpting benchmark (issue 6 point 9): cutting, tunnelling and scratch-out smoothing on a
// 20k-triangle closed model (a UV sphere of 19 800 triangles), through the same functions the
// session calls. Prints the median and minimum wall time and the CPU time of each operation.
//
//   build/release/bench/sculpt_bench [repetitions]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <vector>

#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_smooth.h"
#include "tests/mesh_fixtures.h"

namespace {

double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

void run(const char* name, int reps, const std::function<ps::Status()>& op) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < reps; ++r) {
    const double c0 = cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    if (const ps::Status st = op(); !st) {
      std::printf("%s: refused: %s\n", name, st.message().c_str());
      std::exit(1);
    }
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_ms() - c0);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("%-28s median %8.1f ms  min %8.1f ms  cpu median %8.1f ms  (%d reps)\n", name, wall[wall.size() / 2],
              wall.front(), cpu[cpu.size() / 2], reps);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ps;
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const TriMesh model = testing::uv_sphere(Vec3::Zero(), 1.0, 100, 100);
  std::printf("model: %zu vertices, %zu triangles\n", model.vertices.size(), model.faces.size());
  Camera cam;
  cam.eye = Vec3(0, 0, 4);
  cam.target = Vec3::Zero();
  cam.width = 640;
  cam.height = 480;
  std::vector<Vec2> line, circle, zigzag;
  for (int i = 0; i <= 40; ++i) line.emplace_back(360.0, 20.0 + 11.0 * i);
  for (int i = 0; i < 48; ++i) circle.push_back(Vec2(320, 240) + 50.0 * Vec2(std::cos(2 * M_PI * i / 48), std::sin(2 * M_PI * i / 48)));
  for (int i = 0; i <= 8; ++i) zigzag.emplace_back(i % 2 ? 360 : 280, 210 + 7.5 * i);
  run("cut (open stroke + side)", reps, [&] { return cut_by_stroke(model, line, Vec2(600, 240), cam).status(); });
  run("tunnel (closed stroke)", reps, [&] { return tunnel_by_stroke(model, circle, cam).status(); });
  run("smooth (scratch-out)", reps, [&] { return smooth_by_scratch(model, zigzag, cam).status(); });
  return 0;
}
