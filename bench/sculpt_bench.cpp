// Sculpting benchmark (issue 6 point 9): cutting, tunnelling, scratch-out smoothing and extrusion on a
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
#include "modeling/sculpt_extrude.h"
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
  // The centred circle is symmetric with the sphere's tessellation and needs one retry (the
  // first rounded result folds a sliver); a circle off the symmetry shows the usual cost.
  std::vector<Vec2> off_circle = circle;
  for (auto& p : off_circle) p += Vec2(7.3, -4.1);
  run("tunnel (off-centre stroke)", reps, [&] { return tunnel_by_stroke(model, off_circle, cam).status(); });
  run("smooth (scratch-out)", reps, [&] { return smooth_by_scratch(model, zigzag, cam).status(); });
  // Extrusion: a closed stroke of 50 px radius off the view centre, a half-ellipse silhouette
  // 0.5 high drawn on the reference plane under a camera facing it.
  const std::vector<Vec2> base = [] {
    std::vector<Vec2> s;
    for (int i = 0; i < 48; ++i) s.push_back(Vec2(350, 220) + 50.0 * Vec2(std::cos(2 * M_PI * i / 48), std::sin(2 * M_PI * i / 48)));
    return s;
  }();
  const auto plane = extrusion_reference_plane(model, base, cam);
  if (!plane) {
    std::printf("extrusion plane: refused: %s\n", plane.message().c_str());
    return 1;
  }
  ExtrudeOptions eo;
  Camera side = cam;
  side.eye = plane->centre + 4.0 * plane->plane.normal;
  side.target = plane->centre;
  side.up = plane->normal_axis;
  eo.silhouette_camera = side;
  double lo = 1e300, hi = -1e300;
  for (const auto& q : plane->base_curve) {
    lo = std::min(lo, (q - plane->centre).dot(plane->across));
    hi = std::max(hi, (q - plane->centre).dot(plane->across));
  }
  std::vector<Vec2> silhouette;
  for (int i = 0; i <= 40; ++i) {
    const double t = M_PI * i / 40;
    const Vec3 p = plane->centre + (0.5 * (lo + hi) - 0.475 * (hi - lo) * std::cos(t)) * plane->across +
                   0.5 * std::sin(t) * plane->normal_axis;
    const auto w = side.project(p);
    silhouette.emplace_back(w->x(), w->y());
  }
  run("extrude (loop + silhouette)", reps, [&] { return extrude_by_strokes(model, base, silhouette, cam, eo).status(); });
  return 0;
}
