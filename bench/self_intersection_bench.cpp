// Time of the self-intersection check (intersecting_face_pairs, modeling/face_intersections.h)
// on mesh files, as mesh improvement runs it after every refinement and smoothing step: all
// faces queried, and a query of every other face (the moved faces of a smoothing round are most
// of them; a refinement's flipped faces about half). Median of `runs` runs each, with the
// default broad phase (the parallel grid, which may decline to CGAL's sweep) and with CGAL's
// sweep forced, so that a change to either shows as a ratio measured in one run.
// Usage: self_intersection_bench [--runs N] MESH [MESH ...]   (.obj .off .ply .stl)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_stats.h"
#include "modeling/face_intersections.h"
#include "modeling/mesh_io.h"

namespace {

struct Timed {
  double ms = 0;
  std::size_t pairs = 0;
};

Timed time_query(const ps::TriMesh& m, const std::vector<int>& query, ps::BroadPhase bp, int runs) {
  std::vector<double> t;
  std::size_t pairs = 0;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    pairs = ps::intersecting_face_pairs(m.vertices, m.faces, query, bp).size();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return {ps::bench::median(t), pairs};
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--runs N] MESH [MESH ...]\n", argv[0]);
    return 2;
  }
  int failed = 0;
  for (const std::string& file : files) {
    const auto mesh = ps::read_mesh(file);
    if (!mesh) {
      std::fprintf(stderr, "self_intersection_bench: %s: %s\n", file.c_str(), mesh.message().c_str());
      failed = 1;
      continue;
    }
    const int nf = static_cast<int>(mesh->faces.size());
    std::vector<int> all(static_cast<std::size_t>(nf)), half;
    for (int f = 0; f < nf; ++f) {
      all[static_cast<std::size_t>(f)] = f;
      if (f % 2 == 0) half.push_back(f);
    }
    const Timed a = time_query(*mesh, all, ps::BroadPhase::kAuto, runs);
    const Timed h = time_query(*mesh, half, ps::BroadPhase::kAuto, runs);
    const Timed s = time_query(*mesh, all, ps::BroadPhase::kSweep, std::max(1, runs / 2));
    std::printf("%s faces %d | all: %.1f ms (%zu pairs) | half: %.1f ms (%zu pairs) | all, sweep: %.1f ms (%zu pairs)\n",
                file.c_str(), nf, a.ms, a.pairs, h.ms, h.pairs, s.ms, s.pairs);
    if (a.pairs != s.pairs) {
      std::fprintf(stderr, "self_intersection_bench: %s: the broad phases disagree (%zu and %zu pairs)\n", file.c_str(),
                   a.pairs, s.pairs);
      failed = 1;
    }
  }
  return failed;
}
