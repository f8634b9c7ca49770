// Sculpting benchmark (issue 6 point 9): cutting, tunnelling, scratch-out smoothing, extrusion
// (also on a turned plane) and digging (a pocket, a bent tunnel) on a
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
#include <optional>
#include <vector>

#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/sculpt_smooth.h"
#include "modeling/solid_check.h"
#include "tests/mesh_fixtures.h"
#include "modeling/allocator_policy.h"

namespace {

double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// Each operation twice: on a model the process has not checked yet (the memo of checked solids
// cleared before every repetition: the first operation after an import or a reconstruction),
// and on a model it has (what an operation sees after a cut, tunnel, extrusion or dig: the model
// is that operation's checked result; solid_check.h).
void run(const char* name, int reps, const std::function<ps::Status()>& op) {
  for (const bool fresh : {true, false}) {
    std::vector<double> wall, cpu;
    for (int r = 0; r < reps; ++r) {
      if (fresh) ps::forget_checked_solids();
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
    std::printf("%-28s %-14s median %8.1f ms  min %8.1f ms  cpu median %8.1f ms  (%d reps)\n", name,
                fresh ? "(new model)" : "(checked)", wall[wall.size() / 2], wall.front(), cpu[cpu.size() / 2], reps);
  }
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
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
  // The session builds the plane when the base stroke is drawn (and the window when it shows it).
  run("extrusion plane (base)", reps, [&] { return extrusion_reference_plane(model, base, cam).status(); });
  // The silhouette is drawn under a camera facing the reference plane: uv(t, width), t in
  // [0, 1], in plane coordinates (u along `across` from the middle of the base, whose width
  // there is `width`; v along the normal axis), sampled at n + 1 points.
  struct Drawn {
    ExtrudeOptions options;
    std::vector<Vec2> silhouette;
  };
  auto draw = [&](double spin, double tilt, int n, const std::function<Vec2(double, double)>& uv) -> std::optional<Drawn> {
    Drawn d;
    d.options.spin = spin;
    d.options.tilt = tilt;
    const auto plane = extrusion_reference_plane(model, base, cam, d.options);
    if (!plane) {
      std::printf("extrusion plane: refused: %s\n", plane.message().c_str());
      return std::nullopt;
    }
    Camera side = cam;
    side.eye = plane->centre + 4.0 * plane->plane.normal;
    side.target = plane->centre;
    side.up = plane->normal_axis;
    d.options.silhouette_camera = side;
    double lo = 1e300, hi = -1e300;
    for (const auto& q : plane->base_curve) {
      lo = std::min(lo, (q - plane->centre).dot(plane->across));
      hi = std::max(hi, (q - plane->centre).dot(plane->across));
    }
    for (int i = 0; i <= n; ++i) {
      const Vec2 q = uv(static_cast<double>(i) / n, hi - lo);
      const Vec3 p = plane->centre + (0.5 * (lo + hi) + q.x()) * plane->across + q.y() * plane->normal_axis;
      const auto w = side.project(p);
      d.silhouette.emplace_back(w->x(), w->y());
    }
    return d;
  };
  // Half an ellipse across 0.95 of the base, `height` high (negative: into the model).
  auto arch = [](double height) {
    return [height](double t, double width) {
      return Vec2(-0.475 * width * std::cos(M_PI * t), height * std::sin(M_PI * t));
    };
  };
  // A U 2.4 deep through the sphere and out at its back, sides 0.9 of the base apart, its
  // bottom moved 0.8 along `across` (by 0.8 f^2 at the fraction f of the depth): a bent tunnel.
  auto bent_u = [](double t, double width) {
    const double depth = 2.4, r = 0.45 * width, s = 3.0 * t;
    Vec2 q = s < 1.0   ? Vec2(-r, -(depth - r) * s)
             : s < 2.0 ? Vec2(-r * std::cos(M_PI * (s - 1.0)), -(depth - r) - r * std::sin(M_PI * (s - 1.0)))
                       : Vec2(r, -(depth - r) * (3.0 - s));
    q.x() += 0.8 * std::pow(-q.y() / depth, 2);
    return q;
  };
  struct Case {
    const char* name;
    std::optional<Drawn> drawn;
  };
  const Case cases[] = {
      {"extrude (loop + silhouette)", draw(0.0, 0.0, 40, arch(0.5))},
      {"extrude (turned plane)", draw(0.6, 0.5, 40, arch(0.5))},
      {"dig (pocket 0.5 deep)", draw(0.0, 0.0, 40, arch(-0.5))},
      {"dig (bent tunnel)", draw(0.0, 0.0, 60, bent_u)},
  };
  for (const auto& c : cases) {
    if (!c.drawn) return 1;
    run(c.name, reps, [&] { return extrude_by_strokes(model, base, c.drawn->silhouette, cam, c.drawn->options).status(); });
  }
  return 0;
}
