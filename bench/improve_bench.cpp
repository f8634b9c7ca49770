// Mesh improvement (thesis 4.5.1) timing and quality on jaggy staircase inputs.
// Usage: improve_bench [repetitions=7] [smoothing_steps] [normal_step] [evening 0|1] [which 0|1|2|3]
//                      [ramp_rounds] [iterations]
// Prints, per input: faces in/out, median / min wall time over the repetitions, stage times,
// triangle quality and smoothness before and after, distance to the analytic surface of
// revolution, volume change, and whether the result passes check_guarantees.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include "modeling/mesh_improve.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "tests/improve_fixtures.h"
#include "modeling/allocator_policy.h"

using namespace ps;

namespace {

// Area-weighted RMS and max of |r(centroid) - R(z)| over faces between the first and last curve.
std::pair<double, double> profile_error(const ps::testing::JaggyInput& in, const TriMesh& m) {
  const double z_hi = (in.slabs - 1) * in.h;
  double sq = 0, area = 0, worst = 0;
  for (const Face& f : m.faces) {
    const Vec3& a = m.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& b = m.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(f[2])];
    const Vec3 g = (a + b + c) / 3.0;
    if (g.z() < 0.0 || g.z() > z_hi) continue;
    const double w = 0.5 * (b - a).cross(c - a).norm();
    const double e = std::abs(std::hypot(g.x(), g.y()) - in.radius_at(g.z()));
    sq += w * e * e;
    area += w;
    worst = std::max(worst, e);
  }
  return {std::sqrt(sq / area), worst};
}

void run(const char* name, const ps::testing::JaggyInput& in, int reps, const ImproveOptions& opt) {
  std::vector<double> ms, cpu_ms;
  ImproveReport rep;
  TriMesh out;
  for (int r = 0; r < reps; ++r) {
    const std::clock_t c0 = std::clock();
    auto res = improve_mesh(in.mesh, in.fixed_vertex, in.fixed_edges, opt, &rep);
    cpu_ms.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    if (!res) {
      std::printf("%s: failed: %s\n", name, res.message().c_str());
      return;
    }
    ms.push_back(rep.ms);
    out = std::move(res).value();
  }
  std::sort(ms.begin(), ms.end());
  std::sort(cpu_ms.begin(), cpu_ms.end());
  const MeshQuality q0 = mesh_quality(in.mesh), q1 = mesh_quality(out);
  const auto [rms0, max0] = profile_error(in, in.mesh);
  const auto [rms1, max1] = profile_error(in, out);
  const double v0 = signed_volume(in.mesh), v1 = signed_volume(out);
  const MeshGuarantees g = check_guarantees(out);
  std::printf("%s: faces %d -> %d, wall median %.1f ms (min %.1f), CPU median %.1f ms (min %.1f), %d reps\n",
              name, rep.faces_in, rep.faces_out, ms[ms.size() / 2], ms.front(), cpu_ms[cpu_ms.size() / 2],
              cpu_ms.front(), reps);
  std::printf("  stages (last run, wall): refine %.1f ms, smooth %.1f ms, checks %.1f ms; splits %d, flips %d, "
              "refinement rollbacks %d, smoothing rollbacks %d\n",
              rep.refine_ms, rep.smooth_ms, rep.check_ms, rep.splits, rep.flips, rep.refinement_rollbacks,
              rep.smoothing_rollbacks);
  std::printf("  min angle %.2f -> %.2f deg, mean min angle %.2f -> %.2f deg, max aspect %.1f -> %.2f, "
              "mean aspect %.2f -> %.3f\n",
              q0.min_angle_deg, q1.min_angle_deg, q0.mean_min_angle_deg, q1.mean_min_angle_deg, q0.max_aspect,
              q1.max_aspect, q0.mean_aspect, q1.mean_aspect);
  std::printf("  dihedral max %.1f -> %.1f deg, rms %.2f -> %.2f deg\n", q0.max_dihedral_deg, q1.max_dihedral_deg,
              q0.rms_dihedral_deg, q1.rms_dihedral_deg);
  std::printf("  profile error rms %.4f -> %.4f, max %.4f -> %.4f; volume %.3f -> %.3f (%+.2f%%); guarantees %s\n",
              rms0, rms1, max0, max1, v0, v1, 100.0 * (v1 - v0) / v0, g.valid() ? "ok" : g.problem().c_str());
}

// Baseline: CGAL's PMP::isotropic_remeshing with the curve edges constrained and protected, the
// target length the mean curve edge length, 10 iterations (what the thesis's refinement could be
// replaced by). It projects onto the input surface, so it keeps the union's creases.
void run_cgal_baseline(const char* name, const ps::testing::JaggyInput& in, int reps) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  namespace PMP = CGAL::Polygon_mesh_processing;
  double target = 0;
  for (const auto& e : in.fixed_edges)
    target += (in.mesh.vertices[static_cast<std::size_t>(e[0])] - in.mesh.vertices[static_cast<std::size_t>(e[1])]).norm();
  target /= static_cast<double>(in.fixed_edges.size());
  std::vector<double> cpu_ms;
  TriMesh out;
  for (int r = 0; r < reps; ++r) {
    SM sm;
    std::vector<SM::Vertex_index> vid;
    for (const auto& v : in.mesh.vertices) vid.push_back(sm.add_vertex(K::Point_3(v.x(), v.y(), v.z())));
    for (const auto& f : in.mesh.faces)
      sm.add_face(vid[static_cast<std::size_t>(f[0])], vid[static_cast<std::size_t>(f[1])], vid[static_cast<std::size_t>(f[2])]);
    auto ecm = sm.add_property_map<SM::Edge_index, bool>("e:constrained", false).first;
    auto vcm = sm.add_property_map<SM::Vertex_index, bool>("v:constrained", false).first;
    for (const auto& e : in.fixed_edges) {
      const auto h = sm.halfedge(vid[static_cast<std::size_t>(e[0])], vid[static_cast<std::size_t>(e[1])]);
      put(ecm, sm.edge(h), true);
    }
    for (std::size_t v = 0; v < vid.size(); ++v)
      if (in.fixed_vertex[v]) put(vcm, vid[v], true);
    const std::clock_t c0 = std::clock();
    PMP::isotropic_remeshing(faces(sm), target, sm,
                             CGAL::parameters::number_of_iterations(10)
                                 .edge_is_constrained_map(ecm)
                                 .vertex_is_constrained_map(vcm)
                                 .protect_constraints(true));
    cpu_ms.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    sm.collect_garbage();
    out = TriMesh{};
    for (auto v : sm.vertices()) {
      const auto& p = sm.point(v);
      out.vertices.emplace_back(p.x(), p.y(), p.z());
    }
    for (auto f : sm.faces()) {
      Face fc{};
      int k = 0;
      for (auto v : vertices_around_face(sm.halfedge(f), sm)) fc[static_cast<std::size_t>(k++)] = static_cast<int>(v.idx());
      out.faces.push_back(fc);
    }
  }
  std::sort(cpu_ms.begin(), cpu_ms.end());
  const MeshQuality q = mesh_quality(out);
  const auto [rms, mx] = profile_error(in, out);
  const MeshGuarantees g = check_guarantees(out);
  std::printf("%s, CGAL isotropic_remeshing baseline: faces %zu, CPU median %.1f ms, min angle %.2f, "
              "mean min angle %.2f, max dihedral %.1f, rms dihedral %.2f, profile error rms %.4f max %.4f, %s\n",
              name, out.faces.size(), cpu_ms[cpu_ms.size() / 2], q.min_angle_deg, q.mean_min_angle_deg,
              q.max_dihedral_deg, q.rms_dihedral_deg, rms, mx, g.valid() ? "guarantees ok" : g.problem().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  const int reps = argc > 1 ? std::atoi(argv[1]) : 7;
  ImproveOptions opt;
  if (argc > 2) opt.smoothing_steps = std::atoi(argv[2]);
  if (argc > 3) opt.normal_step = std::atof(argv[3]);
  if (argc > 4) opt.curvature_evening = std::atoi(argv[4]) != 0;
  if (argc > 6) opt.ramp_rounds = std::atoi(argv[6]);
  if (argc > 7) opt.iterations = std::atoi(argv[7]);
  std::printf("options: iterations %d, smoothing steps %d, normal step %.2f, %s flow, alpha ramp over %d rounds\n",
              opt.iterations, opt.smoothing_steps, opt.normal_step,
              opt.curvature_evening ? "curvature-evening" : "mean-curvature", opt.ramp_rounds);
  const int which = argc > 5 ? std::atoi(argv[5]) : 0;  // 0 both, 1 small, 2 large, 3 small + CGAL
  if (which != 2) run("staircase 10 slabs x 48 (~3k triangles)", ps::testing::staircase(10, 48), reps, opt);
  if (which == 3) run_cgal_baseline("staircase 10 slabs x 48", ps::testing::staircase(10, 48), reps);
  if (which != 1)
    run("staircase 28 slabs x 120 (~20k triangles)", ps::testing::staircase(28, 120), std::max(1, reps / 2), opt);
  return 0;
}
