// Reconstruction benchmark: per-stage time of a full reconstruction of ~20 orthogonal sections
// (an ellipsoid sliced by 7 planes per axis), and progressive-update latency (adding one section
// to that model). Prints medians and p95 over repetitions.
//
//   build/release/bench/recon_bench [repetitions]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "modeling/progressive_reconstructor.h"
#include "modeling/reconstruct.h"
#include "tests/recon_synthetic.h"
#include "modeling/allocator_policy.h"

namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  using namespace ps;
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  std::vector<testing::SliceSpec> slices;
  for (int k = 0; k < 3; ++k)
    for (double o : {-0.72, -0.48, -0.24, 0.02, 0.26, 0.5, 0.74}) slices.push_back({k, o});
  const Vec3 radii(1.0, 0.85, 0.9);
  const SectionSet model = testing::ellipsoid_slices(Vec3::Zero(), radii, slices, 48);
  std::printf("input: %zu sections, %zu points\n", model.curves.size(), model.all_points().size());

  ReconstructOptions opt;
  opt.improve = false;
  std::vector<double> validate, partition, primitives, unions, stitch, total;
  ReconstructReport rep;
  for (int r = 0; r < reps; ++r) {
    auto m = reconstruct(model, opt, &rep);
    if (!m) {
      std::fprintf(stderr, "reconstruction failed: %s\n", m.message().c_str());
      return 1;
    }
    validate.push_back(rep.timings.validate_ms);
    partition.push_back(rep.timings.partition_ms);
    primitives.push_back(rep.timings.primitives_ms);
    unions.push_back(rep.timings.union_ms);
    stitch.push_back(rep.timings.stitch_ms);
    total.push_back(rep.timings.total_ms);
    if (r == 0)
      std::printf("zones %d (empty %d, end %d, body %d; filled by whole-face prisms %d), primitives %d, mesh %zu vertices %zu faces\n",
                  rep.zones, rep.empty_zones, rep.end_zones, rep.body_zones, rep.zones_filled, rep.primitives,
                  m->vertices.size(), m->faces.size());
  }
  std::printf("full reconstruction, median of %d (ms): validate %.1f  partition %.1f  primitives %.1f  union %.1f  "
              "stitch %.1f  total %.1f (p95 %.1f)\n",
              reps, percentile(validate, 0.5), percentile(partition, 0.5), percentile(primitives, 0.5),
              percentile(unions, 0.5), percentile(stitch, 0.5), percentile(total, 0.5), percentile(total, 0.95));

  // === Progressive: add one section to the 21-section model and take it away again.
  auto progressive = [&](const char* what, const SectionSet& extra_plane_set) {
    ProgressiveReconstructor pr(opt);
    Box3 box;
    box.min = Vec3::Constant(-2.0);
    box.max = Vec3::Constant(2.0);
    pr.set_box(box);
    if (!pr.update(model)) return;
    std::vector<double> add_ms, remove_ms, recomputed, filled;
    std::vector<double> s_validate, s_partition, s_primitives, s_union, s_stitch;
    for (int r = 0; r < reps * 3; ++r) {
      ReconstructReport a;
      auto m = pr.update(extra_plane_set, &a);
      if (!m) {
        std::fprintf(stderr, "progressive update failed: %s\n", m.message().c_str());
        return;
      }
      add_ms.push_back(a.timings.total_ms);
      s_validate.push_back(a.timings.validate_ms);
      s_partition.push_back(a.timings.partition_ms);
      s_primitives.push_back(a.timings.primitives_ms);
      s_union.push_back(a.timings.union_ms);
      s_stitch.push_back(a.timings.stitch_ms);
      recomputed.push_back(a.zones_recomputed);
      filled.push_back(a.zones_filled);
      ReconstructReport b;
      if (!pr.update(model, &b)) return;
      remove_ms.push_back(b.timings.total_ms);
    }
    std::printf("progressive add (%s): median %.1f ms, p95 %.1f ms, zones recomputed %.0f (filled %.0f); remove: median %.1f ms\n",
                what, percentile(add_ms, 0.5), percentile(add_ms, 0.95), percentile(recomputed, 0.5),
                percentile(filled, 0.5), percentile(remove_ms, 0.5));
    std::printf("  add, stage medians (ms): validate %.1f  partition %.1f  primitives %.1f  union %.1f  stitch and checks %.1f\n",
                percentile(s_validate, 0.5), percentile(s_partition, 0.5), percentile(s_primitives, 0.5),
                percentile(s_union, 0.5), percentile(s_stitch, 0.5));
  };
  SectionSet on_existing = model;
  testing::add_circle(on_existing, 2, 0.02, 1.35, 1.35, 0.25, 32);
  progressive("circle on an existing plane", on_existing);
  SectionSet on_new = model;
  testing::add_circle(on_new, 0, 1.5, 0.0, 0.0, 0.2, 32);
  progressive("circle on a new plane", on_new);
  return 0;
}
