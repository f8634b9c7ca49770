// Deformation from the sketch session (issue 5 point 6): the wall time of one SketchSession::deform
// on a model the session reconstructed from cross sections (handle stroke, target stroke, radius
// ROI, lambda 0.5), its stages, and the drag update (one warm-started local/global iteration) on
// the same region. Medians and minima over repetitions.
//
//   build/release/bench/session_deform_bench [repetitions]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <vector>

#include "modeling/deform_tool.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/sketch_session.h"
#include "tests/section_fixtures.h"
#include "modeling/allocator_policy.h"

namespace {

using namespace ps;

double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

struct Stat {
  double median = 0, min = 0;
};
Stat stat(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v.front()};
}

Camera look(const Vec3& eye, const Vec3& target, const Vec3& up) { return testing::look_at(eye, target, up, 1280, 800); }

// Horizontal slices of the unit sphere at `heights`, improved like the interactive preview.
SketchSession stack(const std::vector<double>& heights, int points) {
  SketchSession s;
  for (double z : heights) {
    const Status st = s.add_section(testing::axis_plane(2, z), testing::circle(2, z, std::sqrt(1 - z * z), points));
    if (!st) {
      std::printf("section z = %g refused: %s\n", z, st.message().c_str());
      std::exit(1);
    }
  }
  return s;
}

void run(const char* name, SketchSession base, int reps) {
  const TriMesh& model = base.state().model;
  std::printf("\n%s: %zu vertices, %zu triangles\n", name, model.vertices.size(), model.faces.size());
  // The handle across the top seen from above; the target: the surface under it raised 0.3,
  // drawn looking down -y (facing the base plane).
  const Camera above = look(Vec3(0, 0, 9), Vec3::Zero(), Vec3::UnitY());
  const Camera side = look(Vec3(0, 9, 0.5), Vec3(0, 0, 0.5), Vec3::UnitZ());
  DeformOp op;
  op.handle_camera = above;
  op.target_camera = side;
  for (int i = 0; i <= 20; ++i) op.handle.emplace_back(577.0 + 6.3 * i, 333.0);
  const MeshRayCaster caster(model);
  for (Vec3 p : project_stroke(caster, above, op.handle)) op.target.push_back(side.project(p + Vec3(0, 0, 0.3))->head<2>());
  op.roi.method = VertexSelection::Method::kRadius;
  op.roi.radius = 0.1;
  op.lambda = base.params().lambda;

  std::vector<double> wall, cpu, selecting, solve, check;
  DeformOpReport report;
  for (int r = 0; r < reps; ++r) {
    SketchSession s = base;  // not timed: the session's state before the stroke
    const double c0 = cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    const Status st = s.deform(op);
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_ms() - c0);
    if (!st) {
      std::printf("deform refused: %s\n", st.message().c_str());
      return;
    }
    // The stages, from the same operation on the same model (apply_deform is what deform runs).
    auto out = apply_deform(model, {}, op, &report);
    selecting.push_back(report.select_ms);
    solve.push_back(report.solver.mesh_ms + report.solver.build_ms + report.solver.factor_ms +
                    report.solver.initial_solve_ms + report.solver.local_ms + report.solver.solve_ms);
    check.push_back(report.check_ms);
  }
  const DeformStats& so = report.solver;
  std::printf("ROI %zu free vertices, %zu handle vertices; %d iterations\n", report.roi.size(), report.handles.size(),
              so.iterations);
  const Stat w = stat(wall), c = stat(cpu);
  std::printf("%-44s median %8.1f ms  min %8.1f ms  cpu median %8.1f ms  (%d reps)\n", "SketchSession::deform (whole op)",
              w.median, w.min, c.median, reps);
  std::printf("  %-42s median %8.1f ms\n", "select (rays, planes, target, ROI)", stat(selecting).median);
  std::printf("  %-42s median %8.1f ms  (last: mesh %.1f, build %.1f, factor %.1f, iterations %.1f)\n",
              "solve (set_mesh + set_region + deform)", stat(solve).median, so.mesh_ms, so.build_ms, so.factor_ms,
              so.local_ms + so.solve_ms + so.initial_solve_ms);
  std::printf("  %-42s median %8.1f ms\n", "self-intersection check", stat(check).median);

  // === Drag: the factored system kept, the targets moved 0.005 further up per frame, one
  // warm-started local/global iteration each (what a live target preview would run).
  EdgeGraphDeformer d;
  DeformParameters params;
  params.lambda = op.lambda;
  if (!d.set_mesh(model) || !d.set_region(report.roi, report.handles, params) || !d.deform(report.targets)) {
    std::printf("drag set-up refused\n");
    std::exit(1);
  }
  std::vector<double> drag, drag_cpu;
  std::vector<Vec3> targets = report.targets;
  for (int f = 0; f < 5 * reps; ++f) {
    for (auto& p : targets) p.z() += 0.005;
    const double c0 = cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    if (!d.drag(targets, 1)) {
      std::printf("drag refused\n");
      std::exit(1);
    }
    drag.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    drag_cpu.push_back(cpu_ms() - c0);
  }
  const Stat dw = stat(drag), dc = stat(drag_cpu);
  std::printf("%-44s median %8.2f ms  min %8.2f ms  cpu median %8.2f ms  (%d frames)\n", "drag (1 warm iteration + solve)",
              dw.median, dw.min, dc.median, 5 * reps);
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  run("stack of 3 sections (z = -0.6, 0, 0.6)", stack({-0.6, 0.0, 0.6}, 96), reps);
  run("stack of 5 sections (z = -0.8 .. 0.8)", stack({-0.8, -0.4, 0.0, 0.4, 0.8}, 96), reps);
  return 0;
}
