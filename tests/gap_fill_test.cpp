// fill_planar_gaps (modeling/gap_fill.h): a planar hole is closed with consistent orientation;
// closed surfaces are left alone; a hole that is not planar is refused.
#include <gtest/gtest.h>

#include "modeling/face_intersections.h"
#include "modeling/gap_fill.h"
#include "modeling/mesh_topology.h"

namespace {

using ps::TriMesh;
using ps::Vec3;

// Unit cube, outward triangles; faces 0-1 lie in z = 0, faces 4-5 in y = 0, faces 8-9 in x = 0.
TriMesh cube() {
  TriMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(GapFill, ClosesAPlanarHoleWithConsistentOrientation) {
  TriMesh m = cube();
  m.faces.erase(m.faces.begin(), m.faces.begin() + 2);  // the square z = 0
  ASSERT_FALSE(ps::mesh_topology(m).closed);
  std::vector<int> added;
  EXPECT_EQ(ps::fill_planar_gaps(m, 1e-12, &added), 1);
  EXPECT_EQ(added.size(), 2u);
  const ps::MeshTopology t = ps::mesh_topology(m);
  EXPECT_TRUE(t.closed) << t.problem;
  EXPECT_TRUE(t.manifold()) << t.problem;
  EXPECT_TRUE(t.consistently_oriented) << t.problem;
  EXPECT_NEAR(t.signed_volume, 1.0, 1e-12);
  for (int f : added)
    for (int v : m.faces[static_cast<std::size_t>(f)]) EXPECT_EQ(m.vertices[static_cast<std::size_t>(v)].z(), 0.0);
  EXPECT_TRUE(ps::intersecting_face_pairs(m.vertices, m.faces, added).empty());
}

TEST(GapFill, LeavesClosedSurfacesAndRefusesHolesOutOfPlane) {
  TriMesh closed = cube();
  EXPECT_EQ(ps::fill_planar_gaps(closed, 1e-12), 0);
  EXPECT_EQ(closed.faces.size(), 12u);
  // One triangle of z = 0 and the adjacent one of y = 0 removed: the hole bends over the edge.
  TriMesh bent = cube();
  bent.faces.erase(bent.faces.begin() + 4);  // {0, 1, 4} in y = 0
  bent.faces.erase(bent.faces.begin());      // {0, 2, 1} in z = 0
  const TriMesh copy = bent;
  EXPECT_EQ(ps::fill_planar_gaps(bent, 1e-12), -1);
  EXPECT_EQ(bent.faces, copy.faces);  // unchanged on refusal
  // With a tolerance the size of the cube it is accepted as planar: the tolerance decides.
  EXPECT_EQ(ps::fill_planar_gaps(bent, 2.0), 1);
}

}  // namespace
