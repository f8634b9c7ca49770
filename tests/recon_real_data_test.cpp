// Reconstruction of real meshes from CGAL's data set, sliced by 2-3 axis-aligned planes per
// axis with the project's slicer (modeling/mesh_slicer.h). Asserts the guarantees of the
// reconstruction issue on every result, plus a Hausdorff bound to the original mesh.
//
// The Hausdorff bound: the reconstruction only knows the mesh through a handful of sections,
// so between sections it can differ from the original by up to the gap between planes, and
// its end zones reach out to the reconstruction's box (twice the points' box, thesis 4.4); we
// measure the error relative to the original's bounding-box diagonal and bound it by 0.6,
// which fails for a surface that misses or wildly overshoots the shape. Measured 0.30-0.42
// (2026-12-06: sphere966 0.30, double torus 0.37, spool 0.39, blobby 0.40, bunny00 0.42); the
// values are printed.
#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <filesystem>

#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_slicer.h"
#include "modeling/reconstruct.h"

using namespace ps;

namespace {

struct Case {
  const char* mesh;
  std::array<int, 3> planes;
};

class RealData : public ::testing::TestWithParam<Case> {};

TEST_P(RealData, SlicedMeshReconstructsWithGuarantees) {
  const Case c = GetParam();
  const std::string path = std::string(PLANESKETCH_CGAL_DATA) + "/" + c.mesh;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "CGAL data mesh absent: " << path;
  auto mesh = read_mesh(path);
  ASSERT_TRUE(mesh) << mesh.message();
  const Box3 box = bounding_box(mesh->vertices);
  std::vector<std::string> warnings;
  auto sections = slice_mesh(*mesh, axis_planes(box, c.planes), SliceOptions{}, &warnings);
  ASSERT_TRUE(sections) << sections.message();
  ASSERT_GE(sections->curves.size(), 3u);

  ReconstructReport report;
  const auto t0 = std::chrono::steady_clock::now();
  ReconstructOptions options;
  options.improve = false;  // the initial union: improvement is tested on its own (improve_*_test)
  auto result = reconstruct(*sections, options, &report);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(result) << c.mesh << ": " << result.message();

  const auto g = check_guarantees(*result);
  EXPECT_TRUE(g.valid()) << c.mesh << ": " << g.problem();
  const auto pts = sections->all_points();
  const double diag = bounding_box(pts).diagonal();
  const double curve_dist = max_distance_to_surface(*result, pts);
  EXPECT_LE(curve_dist, 1e-6 * diag) << c.mesh;
  const double h = hausdorff_distance(*result, *mesh, 4000) / box.diagonal();
  EXPECT_LT(h, 0.6) << c.mesh;
  std::printf("%s: %zu sections, %zu faces, %d components, genus %d, %.1f ms, Hausdorff %.4f of diagonal\n",
              c.mesh, sections->curves.size(), result->faces.size(), g.topology.components, g.topology.genus,
              ms, h);
}

std::string case_name(const ::testing::TestParamInfo<Case>& case_info) {
  std::string n = case_info.param.mesh;
  n = n.substr(0, n.find('.'));
  for (auto& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(CgalMeshes, RealData,
                         ::testing::Values(Case{"blobby.off", {3, 2, 2}},
                                           Case{"double-torus-example.off", {3, 2, 2}},
                                           Case{"sphere966.off", {2, 2, 2}},
                                           // a planar gap left by the stitching is closed (gap_fill.h)
                                           Case{"bunny00.off", {2, 2, 2}},
                                           // refused until 2026-12-06 ("the stitched surface
                                           // intersects itself where two vertices almost
                                           // coincide"): flat slivers folded by rounding, now
                                           // removed on this path too (sliver_repair.h)
                                           Case{"spool.off", {2, 2, 3}}),
                         case_name);

}  // namespace
