// Formats benchmarks: reading and writing contour files, slicing meshes, generating random
// sections, encoding glTF. Prints medians over repetitions (figures go to
// bench/results/formats.md). Usage: formats_bench [repetitions, default 7]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bench/bench_stats.h"
#include "modeling/contour_io.h"
#include "modeling/gltf_export.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_slicer.h"
#include "modeling/section_generator.h"
#include "modeling/allocator_policy.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

double median_ms(int reps, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  return ps::bench::median(std::move(t));
}

}  // namespace

int main(int argc, char** argv) {
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  std::printf("formats_bench: medians over %d repetitions\n", reps);

  // === Reading every published CSL file, and JSON/CSL/.contour writing + reading of the largest.
  const fs::path csl = fs::path(PLANESKETCH_SHARED_DIR) / "data/csl";
  if (fs::exists(csl)) {
    std::vector<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(csl))
      if (e.path().extension() == ".csl") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    std::size_t points = 0;
    for (const auto& f : files) points += read_sections(f)->all_points().size();
    const double all = median_ms(reps, [&] {
      for (const auto& f : files) (void)read_sections(f);
    });
    std::printf("read all %zu CSL files (%zu points): %.1f ms (%.2f Mpoints/s)\n", files.size(), points, all,
                static_cast<double>(points) / all / 1e3);
    const std::string big = (csl / "without_ref/Abdomen.csl").string();
    if (fs::exists(big)) {
      const SectionSet s = *read_sections(big);
      const std::size_t n = s.all_points().size();
      for (auto f : {ContourFormat::Json, ContourFormat::Csl, ContourFormat::Ctr2Suf}) {
        std::string text;
        const double w = median_ms(reps, [&] {
          text = f == ContourFormat::Json ? format_contour_json(s) : f == ContourFormat::Csl ? format_csl(s) : format_ctr2suf(s);
        });
        const double r = median_ms(reps, [&] { (void)parse_sections(text, f, "bench"); });
        std::printf("Abdomen (%zu points, %zu curves) as %s: format %.1f ms, parse %.1f ms, %zu bytes\n", n,
                    s.curves.size(), contour_format_extension(f), w, r, text.size());
      }
    }
  } else {
    std::printf("no CSL data at %s: skipped\n", csl.c_str());
  }

  // === Slicing CGAL data meshes.
  for (const char* name : {"sphere966.off", "double-torus-example.off", "bunny00.off", "elephant.off"}) {
    auto mesh = read_mesh(std::string(PLANESKETCH_CGAL_DATA) + "/" + name);
    if (!mesh) {
      std::printf("%s: %s\n", name, mesh.message().c_str());
      continue;
    }
    const Box3 box = bounding_box(mesh->vertices);
    SectionSet s;
    const double axis = median_ms(reps, [&] { s = *slice_mesh(*mesh, axis_planes(box, {3, 3, 3})); });
    const std::size_t c1 = s.curves.size(), p1 = s.all_points().size();
    const double rnd = median_ms(reps, [&] { s = *slice_mesh(*mesh, random_planes(box, 10, 1)); });
    std::printf("slice %s (%zu faces): 3x3x3 axis planes %.1f ms (%zu curves, %zu points); 10 random planes %.1f ms (%zu curves)\n",
                name, mesh->num_faces(), axis, c1, p1, rnd, s.curves.size());
    const double glb = median_ms(reps, [&] { (void)encode_glb(*mesh); });
    std::printf("encode_glb %s: %.2f ms\n", name, glb);
  }

  // === Random sections.
  std::size_t curves = 0;
  const double gen = median_ms(reps, [&] {
    curves = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      GeneratorOptions o;
      o.seed = seed;
      curves += generate_sections(o).sections.curves.size();
    }
  });
  std::printf("generate_sections seeds 1..10 (4 orthogonal + 2 oblique planes each): %.1f ms total, %zu curves\n", gen, curves);
  return 0;
}
