// The zone union's last resort, all frusta at once through Nef polyhedra
// (modeling/nef_union.h), on the real zone of tests/data/zone_nudge_seed9: where corefinement
// unites, the exact union at once is the same solid; where two frusta touch without
// overlapping, it is refused as non-manifold unless asked for the touching triangles.
#include "modeling/nef_union.h"

#include <gtest/gtest.h>

#include "modeling/frustum_nudge.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/zone_union.h"
#include "tests/zone_fixture.h"

namespace ps {
namespace {

double volume(const TriMesh& m) { return signed_volume(m, m.vertices.front()); }

TEST(NefUnion, SameSolidAsCorefinementWhereCorefinementUnites) {
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta();
  ASSERT_EQ(frusta.size(), 6u);
  int nudged = 0;
  const auto leaned = with_overlap_nudges(frusta, planes, &nudged);
  ASSERT_EQ(nudged, 1);
  for (const auto& set : {std::vector<SnappedSolid>{frusta[0], frusta[2]}, leaned}) {
    auto pairwise = union_snapped_solids(set, planes);
    ASSERT_TRUE(pairwise) << pairwise.message();
    bool manifold = false;
    auto at_once = union_snapped_solids_at_once(set, planes, false, &manifold);
    ASSERT_TRUE(at_once) << at_once.message();
    EXPECT_TRUE(manifold);
    const auto g = check_guarantees(*at_once);
    EXPECT_TRUE(g.valid()) << g.problem();
    EXPECT_EQ(g.topology.components, check_guarantees(*pairwise).topology.components);
    // The same point set: equal volumes (to rounding of the exact points), and every vertex of
    // one on the other's surface.
    EXPECT_NEAR(volume(*at_once), volume(*pairwise), 1e-12 * std::abs(volume(*pairwise)));
    const double diag = bounding_box(pairwise->vertices).diagonal();
    EXPECT_LE(max_distance_to_surface(*pairwise, at_once->vertices), 1e-12 * diag);
    EXPECT_LE(max_distance_to_surface(*at_once, pairwise->vertices), 1e-12 * diag);
  }
}

TEST(NefUnion, TouchingFrustaAreRefusedOrReturnedWithTheirContact) {
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta();
  ASSERT_EQ(frusta.size(), 6u);
  // Frusta 4 and 5 share a zone edge and touch along it without overlapping (README.md).
  const std::vector<SnappedSolid> pair{frusta[4], frusta[5]};
  ASSERT_FALSE(union_snapped_solids(pair, planes));
  bool manifold = true;
  auto refused = union_snapped_solids_at_once(pair, planes, false, &manifold);
  EXPECT_FALSE(refused);
  EXPECT_FALSE(manifold);
  EXPECT_NE(refused.message().find("not a 2-manifold"), std::string::npos) << refused.message();
  auto touching = union_snapped_solids_at_once(pair, planes, true, &manifold);
  ASSERT_TRUE(touching) << touching.message();
  EXPECT_FALSE(manifold);
  const MeshTopology t = mesh_topology(*touching);
  EXPECT_TRUE(t.closed) << t.problem;
  EXPECT_FALSE(t.manifold());  // the contact
  EXPECT_GT(t.nonmanifold_edges + t.nonmanifold_vertices, 0);
  // Nothing lost or doubled: the two frusta meet on a set of no volume.
  const double sum = volume(frusta[4].mesh) + volume(frusta[5].mesh);
  EXPECT_NEAR(volume(*touching), sum, 1e-9 * sum);
}

TEST(NefUnion, UnusableOperandIsNamed) {
  const auto planes = testing::read_seed9_planes();
  auto frusta = testing::read_seed9_frusta();
  ASSERT_EQ(frusta.size(), 6u);
  frusta[1].mesh.faces.pop_back();  // open
  auto r = union_snapped_solids_at_once({frusta[0], frusta[1]}, planes);
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("frustum 1"), std::string::npos) << r.message();
}

}  // namespace
}  // namespace ps
