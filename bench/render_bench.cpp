// Frame time of the offscreen renderer (lavapipe when there is no GPU) at 1280x800.
// Prints the median and minimum over repetitions for: render only (draw + GPU wait) and
// render + read-back, for a translucent ~100k-triangle sphere with the three basic planes,
// the same sphere opaque, and the planes alone (fixed per-frame cost).
//
//   build/release/bench/render_bench [repetitions]      (default 15)
// Results: bench/results/render.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <ctime>
#include <vector>

#include "bench/bench_stats.h"
#include "engine/frame_geometry.h"
#include "engine/renderer.h"
#include "engine/scene.h"
#include "tests/mesh_fixtures.h"
#include "modeling/allocator_policy.h"

namespace {

using ps::Vec3;

ps::TriMesh uv_sphere(double r, int rings, int segments) { return ps::testing::uv_sphere(Vec3::Zero(), r, rings, segments); }

struct Figures {
  double median_ms, min_ms, median_cpu_ms;
};

using ps::bench::median;

// CPU time of the whole process, all threads (lavapipe's rasterizer threads included).
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

template <class F>
Figures time_it(int reps, F&& f) {
  for (int i = 0; i < 3; ++i) f();  // warm-up: JIT compilation of shaders, first uploads
  std::vector<double> ms, cpu;
  for (int i = 0; i < reps; ++i) {
    const double c0 = process_cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    f();
    const auto t1 = std::chrono::steady_clock::now();
    cpu.push_back(process_cpu_ms() - c0);
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return {median(ms), *std::min_element(ms.begin(), ms.end()), median(cpu)};
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  const int reps = argc > 1 ? std::max(3, std::atoi(argv[1])) : 15;
  constexpr int kW = 1280, kH = 800;
  ps::engine::RendererOptions o;
  o.width = kW;
  o.height = kH;
  std::string device;
  o.log = [&](const std::string& line) { device = line; };
  auto r = ps::engine::create_offscreen_renderer(o);
  if (!r) {
    std::fprintf(stderr, "render_bench: %s\n", r.message().c_str());
    return 1;
  }
  ps::engine::Renderer& renderer = **r;

  const ps::TriMesh sphere = uv_sphere(1.0, 225, 224);
  ps::engine::Scene translucent = ps::engine::default_scene(sphere, ps::engine::View::iso, kW, kH);
  translucent.preview = ps::engine::MeshVisual{sphere, {0.3f, 0.5f, 0.9f, 0.45f}, false};
  translucent.solid.reset();
  ps::engine::Scene opaque = ps::engine::default_scene(sphere, ps::engine::View::iso, kW, kH);
  ps::engine::Scene planes_only = opaque;
  planes_only.solid.reset();

  const char* threads = std::getenv("LP_NUM_THREADS");
  std::printf("device: %s\n", device.c_str());
  std::printf("LP_NUM_THREADS: %s\n", threads ? threads : "(unset: one per core)");
  std::printf("mesh: %zu triangles, %zu vertices; image %dx%d; %d repetitions\n",
              sphere.num_faces(), sphere.num_vertices(), kW, kH, reps);
  std::printf("%-48s %10s %10s %8s %12s\n", "scene", "median ms", "min ms", "fps",
              "CPU ms/frame");
  // Optional second argument: run only the scenes whose name contains it (for profiling).
  const std::string only = argc > 2 ? argv[2] : "";
  const auto report = [&](const char* name, const ps::engine::Scene& s, bool readback) {
    if (!only.empty() && std::string(name).find(only) == std::string::npos) return;
    bool ok = true;
    const Figures f = time_it(reps, [&] {
      if (readback) {
        ok = ok && renderer.render(s).is_ok();
      } else {
        ok = ok && renderer.draw(s).is_ok();
      }
    });
    if (!ok) {
      std::fprintf(stderr, "render_bench: rendering '%s' failed\n", name);
      std::exit(1);
    }
    std::printf("%-48s %10.2f %10.2f %8.1f %12.2f\n", name, f.median_ms, f.min_ms,
                1000.0 / f.median_ms, f.median_cpu_ms);
  };
  report("translucent 100k sphere + 3 planes (render)", translucent, false);
  report("translucent 100k sphere + 3 planes (+readback)", translucent, true);
  report("opaque 100k sphere + 3 planes (render)", opaque, false);
  report("opaque 100k sphere + 3 planes (+readback)", opaque, true);
  report("3 planes only (render)", planes_only, false);

  // CPU-side per-frame work alone: the mesh fingerprint that detects changed meshes.
  const auto t0 = std::chrono::steady_clock::now();
  const auto s = ps::engine::mesh_fingerprint(sphere);
  const auto t1 = std::chrono::steady_clock::now();
  std::printf("mesh fingerprint (per frame, per mesh): %.2f ms (%llx)\n",
              std::chrono::duration<double, std::milli>(t1 - t0).count(),
              static_cast<unsigned long long>(s));
  return 0;
}
