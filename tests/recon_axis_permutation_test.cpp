// Metamorphic tests of the orthogonal reconstruction (thesis chapter 4) under a renaming of the
// axes: a cyclic permutation of x, y and z is a rotation that is exact in doubles, so the
// reconstruction of the permuted input must be the permuted reconstruction. Before the 4.3 pull
// factors were tied to the axes' ranks instead of their names (cylinder_builder.cpp,
// axis_ranks), the volumes of generated inputs moved by up to 0.5% under this permutation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/reconstruct.h"
#include "modeling/section_generator.h"
#include "recon_synthetic.h"

using namespace ps;
using namespace ps::testing;

namespace {

// (x, y, z) -> (z, x, y): the rotation by 120 degrees about (1, 1, 1).
Eigen::Matrix3d cyclic() {
  Eigen::Matrix3d r;
  r << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return r;
}

SectionSet generated(std::uint64_t seed) {
  GeneratorOptions g;
  g.seed = seed;
  g.orthogonal_planes = 2 + static_cast<int>(seed % 3);
  g.oblique_planes = 0;
  g.min_curve_points = 24;
  g.max_curve_points = 60;
  return generate_sections(g).sections;
}

}  // namespace

// The exact permutation applied twice more gives the input back: a check of the test's tool.
TEST(AxisPermutation, ThreeCyclesAreTheIdentity) {
  const SectionSet s = generated(3);
  const Eigen::Matrix3d r = cyclic();
  const SectionSet back = moved_sections(moved_sections(moved_sections(s, r, Vec3::Zero()), r, Vec3::Zero()), r,
                                         Vec3::Zero());
  ASSERT_EQ(back.curves.size(), s.curves.size());
  for (std::size_t c = 0; c < s.curves.size(); ++c) EXPECT_EQ(back.curves[c].points, s.curves[c].points);
}

// Generated unions of ellipsoids and tori cut by two to four axis planes per axis: the permuted
// input's mesh, mapped back, is the input's mesh as a surface (every vertex of each within 1e-12 of
// the diagonal of the other), with the same volume, area, components and genus to rounding.
TEST(AxisPermutation, PermutedAxesGiveThePermutedMesh) {
  const Eigen::Matrix3d r = cyclic();
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const SectionSet s = generated(seed);
    if (s.curves.empty()) continue;
    auto a = reconstruct(s, no_improve());
    ASSERT_TRUE(a) << "seed " << seed << ": " << a.message();
    for (int turns = 1; turns <= 2; ++turns) {
      SectionSet p = s;
      Eigen::Matrix3d rt = Eigen::Matrix3d::Identity();
      for (int i = 0; i < turns; ++i) {
        p = moved_sections(p, r, Vec3::Zero());
        rt = r * rt;
      }
      ReconstructReport rep;
      auto b = reconstruct(p, no_improve(), &rep);
      ASSERT_TRUE(b) << "seed " << seed << ": " << b.message();
      EXPECT_FALSE(rep.rotated_frame) << "seed " << seed << ": axis planes need no frame";
      TriMesh back = *b;
      for (auto& v : back.vertices) v = rt.transpose() * v;  // exact: a permutation
      const auto ta = mesh_topology(*a), tb = mesh_topology(back);
      EXPECT_NEAR(tb.signed_volume / ta.signed_volume, 1.0, 1e-12) << "seed " << seed << ", turns " << turns;
      EXPECT_NEAR(tb.area / ta.area, 1.0, 1e-12) << "seed " << seed << ", turns " << turns;
      EXPECT_EQ(tb.components, ta.components) << "seed " << seed;
      EXPECT_EQ(tb.genus, ta.genus) << "seed " << seed;
      // The same surface: every vertex of each on the other. (Not the same vertices: the zone
      // unions meet their operands in another order, and an exact union's triangulation follows
      // the order of its operations.)
      const double diag = bounding_box(s.all_points()).diagonal();
      EXPECT_LE(max_distance_to_surface(back, a->vertices), 1e-12 * diag) << "seed " << seed << ", turns " << turns;
      EXPECT_LE(max_distance_to_surface(*a, back.vertices), 1e-12 * diag) << "seed " << seed << ", turns " << turns;
      ++compared;
    }
  }
  EXPECT_GE(compared, 20);
}

