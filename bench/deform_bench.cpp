// Deformation benchmark: planesketch's EdgeGraphDeformer (edge graph and primal domain) against
// CGAL's Surface_mesh_deformation (ORIGINAL_ARAP, SRE_ARAP) in the same run, on the same meshes,
// ROIs, handles and targets (thesis table 5.1 sizes: ~900, ~2.8k, ~9.2k ROI vertices).
//
//   build/release/bench/deform_bench [repetitions=5]
//
// Prints wall-clock medians and minima and process-CPU medians (ms) of: total (build + factor + converge from the rest shape, including the
// per-mesh set-up), and one drag update (one warm-started iteration + solve). CGAL's headers
// stay in this file only.
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>
#include <tbb/global_control.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "bench/bench_stats.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh_io.h"
#include "modeling/allocator_policy.h"

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SM = CGAL::Surface_mesh<Kernel::Point_3>;
using VD = SM::Vertex_index;
using Clock = std::chrono::steady_clock;

// Process CPU time (all threads), ms: a load-independent companion to wall time on a shared VM.
double cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}
double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }
using ps::bench::median;

struct Case {
  std::string mesh;
  int center;
  int roi_size;
};

struct Setup {
  ps::TriMesh mesh;
  std::vector<int> roi;      // free vertices
  std::vector<int> handles;  // control vertices
  std::vector<ps::Vec3> targets, drag_targets;
};

// ROI: the roi_size vertices nearest to `center` along mesh edges (Dijkstra); handles: the
// nearest 4% of them, moved by a translation plus a 20-degree turn about their centroid.
Setup make_setup(const ps::TriMesh& m, int center, int roi_size) {
  Setup s;
  s.mesh = m;
  const std::size_t n = m.vertices.size();
  std::vector<std::vector<int>> adj(n);
  for (const auto& f : m.faces)
    for (std::size_t k = 0; k < 3; ++k) adj[static_cast<std::size_t>(f[k])].push_back(f[(k + 1) % 3]), adj[static_cast<std::size_t>(f[(k + 1) % 3])].push_back(f[k]);
  std::vector<double> dist(n, 1e300);
  std::vector<int> order;
  using QE = std::pair<double, int>;
  std::priority_queue<QE, std::vector<QE>, std::greater<>> q;
  dist[static_cast<std::size_t>(center)] = 0;
  q.push({0, center});
  std::vector<char> done(n, 0);
  while (!q.empty() && static_cast<int>(order.size()) < roi_size) {
    auto [d, v] = q.top();
    q.pop();
    if (done[static_cast<std::size_t>(v)]) continue;
    done[static_cast<std::size_t>(v)] = 1;
    order.push_back(v);
    for (int w : adj[static_cast<std::size_t>(v)]) {
      const double nd = d + (m.vertices[static_cast<std::size_t>(v)] - m.vertices[static_cast<std::size_t>(w)]).norm();
      if (nd < dist[static_cast<std::size_t>(w)]) dist[static_cast<std::size_t>(w)] = nd, q.push({nd, w});
    }
  }
  const std::size_t nh = std::max<std::size_t>(4, order.size() / 25);
  s.handles.assign(order.begin(), order.begin() + static_cast<long>(nh));
  s.roi.assign(order.begin() + static_cast<long>(nh), order.end());
  ps::Vec3 c = ps::Vec3::Zero();
  for (int h : s.handles) c += m.vertices[static_cast<std::size_t>(h)];
  c /= static_cast<double>(nh);
  double radius = 0;
  for (int v : order) radius = std::max(radius, (m.vertices[static_cast<std::size_t>(v)] - c).norm());
  auto motion = [&](double f) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translate(c + ps::Vec3(0.25, 0.15, 0.1) * radius * f);
    t.rotate(Eigen::AngleAxisd(0.35 * f, ps::Vec3(1, 1, 0).normalized()));
    t.translate(-c);
    return t;
  };
  for (int h : s.handles) s.targets.push_back(motion(1.0) * m.vertices[static_cast<std::size_t>(h)]);
  for (int h : s.handles) s.drag_targets.push_back(motion(1.05) * m.vertices[static_cast<std::size_t>(h)]);
  return s;
}

SM to_surface_mesh(const ps::TriMesh& m) {
  SM sm;
  for (const auto& v : m.vertices) sm.add_vertex(Kernel::Point_3(v.x(), v.y(), v.z()));
  for (const auto& f : m.faces) sm.add_face(VD(static_cast<SM::size_type>(f[0])), VD(static_cast<SM::size_type>(f[1])), VD(static_cast<SM::size_type>(f[2])));
  return sm;
}

// Iteration cap for every method (ours and CGAL's deform(max_iterations, tolerance)); the
// second command-line argument changes it: 10 is table 5.1's setting, where neither solver
// reaches the tolerance; a large cap measures the time to converge to it.
int max_iterations = 10;
constexpr double kTolerance = 1e-5;

struct Timing {
  double total = 0, drag = 0, setup = 0, total_cpu = 0, drag_cpu = 0;
  int iterations = 0;
  double energy = std::nan("");  // ours: the exact energy of the result
};

template <CGAL::Deformation_algorithm_tag Tag>
Timing run_cgal(const Setup& s) {
  Timing t;
  SM sm = to_surface_mesh(s.mesh);
  const double c0 = cpu_ms();
  const auto t0 = Clock::now();
  CGAL::Surface_mesh_deformation<SM, CGAL::Default, CGAL::Default, Tag> d(sm);
  for (int v : s.roi) d.insert_roi_vertex(VD(static_cast<SM::size_type>(v)));
  for (int h : s.handles) d.insert_control_vertex(VD(static_cast<SM::size_type>(h)));
  if (!d.preprocess()) {
    std::fprintf(stderr, "CGAL preprocess failed\n");
    std::exit(1);
  }
  for (std::size_t k = 0; k < s.handles.size(); ++k) {
    const auto& p = s.targets[k];
    d.set_target_position(VD(static_cast<SM::size_type>(s.handles[k])), Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  d.deform(static_cast<unsigned int>(max_iterations), kTolerance);
  const auto t1 = Clock::now();
  t.total = ms(t0, t1);
  t.total_cpu = cpu_ms() - c0;
  for (std::size_t k = 0; k < s.handles.size(); ++k) {
    const auto& p = s.drag_targets[k];
    d.set_target_position(VD(static_cast<SM::size_type>(s.handles[k])), Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  const double c2 = cpu_ms();
  const auto t2 = Clock::now();
  d.deform(1, 0.0);
  t.drag = ms(t2, Clock::now());
  t.drag_cpu = cpu_ms() - c2;
  return t;
}

// window: Anderson acceleration's history (0: the plain local/global alternation).
Timing run_ours(const Setup& s, ps::DeformDomain domain, double lambda, int window = ps::DeformParameters{}.anderson_window) {
  Timing t;
  const double c0 = cpu_ms();
  const auto t0 = Clock::now();
  ps::EdgeGraphDeformer d;
  if (!d.set_mesh(s.mesh)) std::exit(1);
  ps::DeformParameters p;
  p.domain = domain;
  p.lambda = lambda;
  p.max_iterations = max_iterations;
  p.tolerance = kTolerance;
  p.anderson_window = window;
  auto st = d.set_region(s.roi, s.handles, p);
  if (!st) {
    std::fprintf(stderr, "%s\n", st.message().c_str());
    std::exit(1);
  }
  if (!d.deform(s.targets)) std::exit(1);
  const auto t1 = Clock::now();
  t.total = ms(t0, t1);
  t.total_cpu = cpu_ms() - c0;
  t.iterations = d.stats().iterations;
  t.energy = d.stats().energies.empty() ? std::nan("") : d.stats().energies.back();
  t.setup = d.stats().mesh_ms + d.stats().build_ms + d.stats().factor_ms;
  if (std::getenv("DEFORM_BENCH_VERBOSE")) {
    const auto& q = d.stats();
    double it = 0;
    for (double x : q.iteration_ms) it += x;
    std::printf("    [mesh %.1f build %.1f factor %.1f initial %.1f iterations %.1f (%d; %d accelerated, %d rejected) [local %.1f solve %.1f energy %.1f] nnz %lld L %lld nodes %d]\n",
                q.mesh_ms, q.build_ms, q.factor_ms, q.initial_solve_ms, it, q.iterations, q.accelerated_iterations,
                q.rejected_accelerations, q.local_ms, q.solve_ms, q.energy_ms, q.matrix_nonzeros, q.factor_nonzeros, q.nodes);
    std::printf("    [energies");
    for (double e : q.energies) std::printf(" %.6g", e);
    std::printf("]\n");
  }
  const double c2 = cpu_ms();
  const auto t2 = Clock::now();
  if (!d.drag(s.drag_targets, 1)) std::exit(1);
  t.drag = ms(t2, Clock::now());
  t.drag_cpu = cpu_ms() - c2;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  if (argc > 2) max_iterations = std::max(1, std::atoi(argv[2]));
  std::printf("deform_bench: %d repetitions, at most %d iterations, tolerance %g\n", reps, max_iterations, kTolerance);
  const int nthreads = std::getenv("DEFORM_BENCH_THREADS") ? std::atoi(std::getenv("DEFORM_BENCH_THREADS")) : 2;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::max(1, nthreads)));
  const std::string data = PLANESKETCH_CGAL_DATA;
  const std::vector<Case> cases = {{"elephant.off", 100, 900}, {"dino.off", 100, 2800}, {"armadillo.off", 100, 9200}};
  // iters and energy: our iterations run and the exact energy of the result (plain rows: the
  // local/global alternation without Anderson acceleration, for the same energy comparison).
  std::printf("%-14s %6s %-24s %9s %9s %9s %9s %9s %9s %6s %11s\n", "mesh", "roi", "method", "total", "total_min",
              "total_cpu", "drag", "drag_min", "drag_cpu", "iters", "energy");
  // DEFORM_BENCH_ONLY=elephant runs only the meshes whose name contains it (for profiling).
  const char* only = std::getenv("DEFORM_BENCH_ONLY");
  for (const auto& c : cases) {
    if (only && c.mesh.find(only) == std::string::npos) continue;
    const std::string path = data + "/" + c.mesh;
    if (!std::filesystem::exists(path)) {
      std::printf("%-14s missing, skipped\n", c.mesh.c_str());
      continue;
    }
    auto mesh = ps::read_mesh(path);
    if (!mesh) {
      std::fprintf(stderr, "%s\n", mesh.message().c_str());
      return 1;
    }
    const Setup s = make_setup(*mesh, c.center, c.roi_size);
    const int roi_total = static_cast<int>(s.roi.size() + s.handles.size());
    struct Method {
      const char* name;
      std::function<Timing()> run;
    };
    const std::vector<Method> methods = {
        {"edge-graph lambda=0.5", [&] { return run_ours(s, ps::DeformDomain::kEdgeGraph, 0.5); }},
        {"edge-graph lambda=1", [&] { return run_ours(s, ps::DeformDomain::kEdgeGraph, 1.0); }},
        {"edge-graph 0.5 plain", [&] { return run_ours(s, ps::DeformDomain::kEdgeGraph, 0.5, 0); }},
        {"edge-graph 1 plain", [&] { return run_ours(s, ps::DeformDomain::kEdgeGraph, 1.0, 0); }},
        {"primal lambda=0.5", [&] { return run_ours(s, ps::DeformDomain::kPrimal, 0.5); }},
        {"CGAL ORIGINAL_ARAP", [&] { return run_cgal<CGAL::ORIGINAL_ARAP>(s); }},
        {"CGAL SRE_ARAP", [&] { return run_cgal<CGAL::SRE_ARAP>(s); }},
    };
    for (const auto& m : methods) {
      std::vector<double> total, drag, total_cpu, drag_cpu;
      int iters = 0;
      double energy = std::nan("");
      for (int r = 0; r < reps; ++r) {
        const Timing t = m.run();
        total.push_back(t.total);
        drag.push_back(t.drag);
        total_cpu.push_back(t.total_cpu);
        drag_cpu.push_back(t.drag_cpu);
        iters = t.iterations;
        energy = t.energy;
      }
      std::printf("%-14s %6d %-24s %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %6d %11.5g\n", c.mesh.c_str(), roi_total, m.name,
                  median(total), *std::min_element(total.begin(), total.end()), median(total_cpu), median(drag),
                  *std::min_element(drag.begin(), drag.end()), median(drag_cpu), iters, energy);
      std::fflush(stdout);
    }
  }
  return 0;
}
