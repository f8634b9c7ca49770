// fill_curveless_cavities (modeling/cavity_fill.h) on boxes built here: an inward shell with no
// curve vertex is removed, one with a curve vertex and every outward part are kept.
#include "modeling/cavity_fill.h"

#include <gtest/gtest.h>

#include "modeling/mesh_topology.h"

namespace {

// Axis box [lo, hi]^3 appended to m, outward (or inward when `inward`).
void add_box(ps::TriMesh& m, double lo, double hi, bool inward) {
  const int base = static_cast<int>(m.vertices.size());
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(ps::Vec3(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo));
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 5}, {0, 5, 4},
                            {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& f : faces)
    m.faces.push_back(inward ? ps::Face{base + f[0], base + f[2], base + f[1]} : ps::Face{base + f[0], base + f[1], base + f[2]});
}

TEST(CavityFill, AnInwardShellWithoutCurvesIsFilled) {
  ps::TriMesh m;
  add_box(m, 0.0, 3.0, false);
  add_box(m, 1.0, 2.0, true);  // a pocket of volume 1 inside
  ASSERT_NEAR(ps::mesh_topology(m).signed_volume, 26.0, 1e-12);
  double volume = 0.0;
  EXPECT_EQ(ps::fill_curveless_cavities(m, std::vector<bool>(16, false), volume), 1);
  EXPECT_NEAR(volume, 1.0, 1e-12);
  const auto t = ps::mesh_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(m.vertices.size(), 8u);  // the pocket's vertices are gone
  EXPECT_NEAR(t.signed_volume, 27.0, 1e-12);
  EXPECT_TRUE(t.closed && t.manifold() && t.consistently_oriented);
}

TEST(CavityFill, ACavityWithACurveOnItAndSeparatePartsAreKept) {
  ps::TriMesh m;
  add_box(m, 0.0, 3.0, false);
  add_box(m, 1.0, 2.0, true);
  add_box(m, 5.0, 6.0, false);  // a separate part
  std::vector<bool> on_curve(24, false);
  on_curve[9] = true;  // a vertex of the pocket lies on an input curve: the sections made it
  const ps::TriMesh copy = m;
  double volume = -1.0;
  EXPECT_EQ(ps::fill_curveless_cavities(m, on_curve, volume), 0);
  EXPECT_EQ(volume, 0.0);
  EXPECT_EQ(m.faces, copy.faces);
  // Without the curve vertex only the pocket goes; the separate part stays.
  EXPECT_EQ(ps::fill_curveless_cavities(m, std::vector<bool>(24, false), volume), 1);
  EXPECT_EQ(ps::mesh_topology(m).components, 2);
  EXPECT_NEAR(ps::mesh_topology(m).signed_volume, 28.0, 1e-12);
}

}  // namespace
