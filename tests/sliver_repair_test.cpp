// remove_folded_slivers (modeling/sliver_repair.h) on small meshes built here: a closed box
// whose crease carries a cap turned over by a rounding-sized displacement, zipped back into a
// closed, crossing-free box with the same vertices; and the cases it must leave alone.
#include <gtest/gtest.h>

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/sliver_repair.h"

namespace {

std::vector<std::array<int, 2>> crossings(const ps::TriMesh& m) {
  std::vector<int> all(m.faces.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return ps::intersecting_face_pairs(m.vertices, m.faces, all);
}

// Unit cube [0,1]^3 with outward faces; the edge from (0,0,1) to (1,0,1) (top face y = 0 side)
// carries an extra vertex w at (t, dy, 1 + dz). The top face is fanned through w; the front face
// (y = 0) keeps the whole edge, and the cap (0,0,1)-(1,0,1)-w closes the seam.
ps::TriMesh box_with_cap(double t, double dy, double dz) {
  ps::TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back(ps::Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  m.vertices.push_back(ps::Vec3(t, dy, 1.0 + dz));  // 8 = w
  // Vertex i = (x, y, z) bits (1, 2, 4). Bottom z=0, sides; top z=1 uses 4,5,6,7 and w.
  m.faces = {{0, 2, 1}, {1, 2, 3},                  // z = 0 (normal -z)
             {0, 1, 5}, {0, 5, 4},                  // y = 0 (normal -y), edge 4-5 whole
             {2, 6, 7}, {2, 7, 3},                  // y = 1
             {0, 4, 6}, {0, 6, 2},                  // x = 0
             {1, 3, 7}, {1, 7, 5},                  // x = 1
             {4, 8, 6}, {8, 7, 6}, {8, 5, 7},       // z = 1 (normal +z), fanned through w
             {4, 5, 8}};                            // the cap on edge 4-5
  return m;
}

TEST(SliverRepair, FoldedCapOnACreaseIsRemovedAndTheSeamZipped) {
  // w a rounding step outside the edge (y < 0) in the top plane: the cap, flat, now lies folded
  // onto the top fan (coplanar, opposite orientation).
  ps::TriMesh m = box_with_cap(0.4, -3e-17, 0.0);
  const auto before = ps::mesh_topology(m);
  ASSERT_TRUE(before.closed && before.manifold() && before.consistently_oriented);
  const auto crossing = crossings(m);
  ASSERT_FALSE(crossing.empty()) << "the fixture must cross itself";
  const auto vertices = m.vertices;
  EXPECT_EQ(ps::remove_folded_slivers(m, crossing, 1e-12), 1);
  const auto after = ps::mesh_topology(m);
  EXPECT_TRUE(after.closed && after.manifold() && after.consistently_oriented) << after.problem;
  EXPECT_TRUE(crossings(m).empty());
  EXPECT_EQ(m.vertices, vertices);  // no vertex moved, none dropped
  EXPECT_NEAR(after.signed_volume, 1.0, 1e-12);
}

// Unit cube whose top-front edge (4-5) is split at x = 0.4 on each side, at two vertices a
// rounding step apart: u = 9 exactly on the edge (front face), w = 8 just outside it (top
// fan). Two flat caps (4, u, w) and (u, 5, w) close the seam.
ps::TriMesh box_with_split_seam(double dy) {
  ps::TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back(ps::Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  m.vertices.push_back(ps::Vec3(0.4, dy, 1.0));   // 8 = w
  m.vertices.push_back(ps::Vec3(0.4, 0.0, 1.0));  // 9 = u
  m.faces = {{0, 2, 1}, {1, 2, 3},                  // z = 0
             {0, 1, 5}, {0, 5, 9}, {0, 9, 4},       // y = 0, through u
             {2, 6, 7}, {2, 7, 3},                  // y = 1
             {0, 4, 6}, {0, 6, 2},                  // x = 0
             {1, 3, 7}, {1, 7, 5},                  // x = 1
             {4, 8, 6}, {8, 7, 6}, {8, 5, 7},       // z = 1, fanned through w
             {4, 9, 8}, {9, 5, 8}};                 // the two caps
  return m;
}

TEST(SliverRepair, SeamWhoseSidesMeetAtSeparateVerticesIsClosed) {
  // Stress seed 38: after the caps go, the seam's two sides are 4-w-5 and 5-u-4, with w and u
  // 3e-17 apart, which no T-junction split can zip: the two are merged.
  ps::TriMesh m = box_with_split_seam(-3e-17);
  const auto before = ps::mesh_topology(m);
  ASSERT_TRUE(before.closed && before.manifold() && before.consistently_oriented) << before.problem;
  EXPECT_EQ(ps::remove_folded_slivers(m, {{11, 13}}, 1e-12), 2);
  const auto after = ps::mesh_topology(m);
  EXPECT_TRUE(after.closed && after.manifold() && after.consistently_oriented) << after.problem;
  EXPECT_TRUE(crossings(m).empty());
  EXPECT_NEAR(after.signed_volume, 1.0, 1e-12);
  for (const auto& f : m.faces)
    for (int c : f) EXPECT_NE(c, 9) << "u is merged into w (the smaller index)";
}

TEST(SliverRepair, SeamVerticesFartherThanTheToleranceStayApart) {
  // The same seam with w 1e-6 off the edge: the caps are not flat, nothing is removed.
  ps::TriMesh m = box_with_split_seam(-1e-6);
  const ps::TriMesh copy = m;
  EXPECT_EQ(ps::remove_folded_slivers(m, {{11, 13}}, 1e-12), 0);
  EXPECT_EQ(m.faces, copy.faces);
}

TEST(SliverRepair, LeavesFacesThickerThanTheToleranceAlone) {
  // The same cap 1e-6 high: a real feature, not a rounding fold.
  ps::TriMesh m = box_with_cap(0.4, -1e-6, 0.0);
  const ps::TriMesh copy = m;
  const std::vector<std::array<int, 2>> crossing = {{13, 10}};
  EXPECT_EQ(ps::remove_folded_slivers(m, crossing, 1e-12), 0);
  EXPECT_EQ(m.faces, copy.faces);
}

TEST(SliverRepair, OnlySliversNearTheCrossingsAreTouched) {
  // A flat cap with no crossing face around it is not a candidate.
  ps::TriMesh m = box_with_cap(0.4, 0.0, 0.0);
  const ps::TriMesh copy = m;
  EXPECT_EQ(ps::remove_folded_slivers(m, {}, 1e-12), 0);
  EXPECT_EQ(m.faces, copy.faces);
  EXPECT_EQ(ps::remove_folded_slivers(m, {{0, 1}}, 1e-12), 0);  // crossing far away (bottom)
  EXPECT_EQ(m.faces, copy.faces);
}

TEST(SliverRepair, FaceHeight) {
  ps::TriMesh m;
  m.vertices = {ps::Vec3(0, 0, 0), ps::Vec3(2, 0, 0), ps::Vec3(1, 0.5, 0), ps::Vec3(1, 0, 0)};
  EXPECT_DOUBLE_EQ(ps::face_height(m, {0, 1, 2}), 0.5);
  EXPECT_DOUBLE_EQ(ps::face_height(m, {0, 1, 3}), 0.0);
  EXPECT_DOUBLE_EQ(ps::face_height(m, {0, 0, 1}), 0.0);
}

}  // namespace
