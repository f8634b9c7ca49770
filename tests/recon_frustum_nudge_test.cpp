// Overlap nudges for frusta whose walls coincide to rounding (modeling/frustum_nudge.h), on the
// zone where they were found (tests/data/zone_nudge_seed9/README.md).
#include "modeling/frustum_nudge.h"

#include <gtest/gtest.h>

#include <string>

#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/zone_union.h"
#include "tests/zone_fixture.h"

namespace ps {
namespace {

std::vector<Plane> read_planes() { return testing::read_seed9_planes(); }
std::vector<SnappedSolid> read_frusta() { return testing::read_seed9_frusta_offset(); }

TEST(FrustumNudge, TheDumpedZoneUnitesWithItsWallsAligned) {
  // As dumped, the two walls coincide to rounding; coincident_walls.h makes them one before the
  // union, so no nudge is needed (before it, CGAL refused this zone).
  const auto planes = read_planes();
  const auto frusta = testing::read_seed9_frusta();
  ASSERT_EQ(frusta.size(), 6u);
  EXPECT_TRUE(union_snapped_solids(frusta, planes));
  int nudged = -1;
  with_overlap_nudges(frusta, planes, &nudged);
  EXPECT_EQ(nudged, 0);
}

TEST(FrustumNudge, CoincidentWallsLeanIntoEachOtherAndTheZoneUnites) {
  const auto planes = read_planes();
  const auto frusta = read_frusta();  // walls coinciding to 1e-12 of the diagonal
  ASSERT_EQ(frusta.size(), 6u);
  // The premise: CGAL refuses this zone and this pair as they are.
  ASSERT_FALSE(union_snapped_solids(frusta, planes));
  ASSERT_FALSE(union_snapped_solids({frusta[4], frusta[5]}, planes));

  int nudged = 0;
  const auto leaned = with_overlap_nudges(frusta, planes, &nudged);
  EXPECT_EQ(nudged, 1);
  ASSERT_EQ(leaned.size(), frusta.size());
  // Only free top points moved, and only a little: bottoms and tagged points are as they were.
  for (std::size_t f = 0; f < frusta.size(); ++f) {
    ASSERT_EQ(leaned[f].mesh.vertices.size(), frusta[f].mesh.vertices.size());
    EXPECT_EQ(leaned[f].mesh.faces, frusta[f].mesh.faces);
    const std::size_t half = frusta[f].mesh.vertices.size() / 2;
    for (std::size_t v = 0; v < frusta[f].mesh.vertices.size(); ++v) {
      const bool tagged = frusta[f].tags[v][0] >= 0;
      if (v < half || tagged) EXPECT_EQ(leaned[f].mesh.vertices[v], frusta[f].mesh.vertices[v]) << f << " " << v;
      else EXPECT_LT((leaned[f].mesh.vertices[v] - frusta[f].mesh.vertices[v]).norm(), 0.01);
    }
  }
  auto u = union_snapped_solids(leaned, planes);
  ASSERT_TRUE(u) << u.message();
  const auto g = check_guarantees(*u);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(g.topology.components, 1);
  // Nothing lost: the union holds at least the largest frustum.
  double largest = 0.0;
  for (const auto& f : frusta) largest = std::max(largest, signed_volume(f.mesh, f.mesh.vertices[0]));
  EXPECT_GT(g.topology.signed_volume, largest);
}

TEST(FrustumNudge, PairsThatUniteOrShareNothingAreLeftAlone) {
  const auto planes = read_planes();
  const auto frusta = read_frusta();
  ASSERT_EQ(frusta.size(), 6u);
  int nudged = -1;
  // Frusta 0 and 1 share no point; 0 and 2 share two and unite as they are.
  for (const auto& pair : {std::vector<SnappedSolid>{frusta[0], frusta[1]}, std::vector<SnappedSolid>{frusta[0], frusta[2]}}) {
    const auto out = with_overlap_nudges(pair, planes, &nudged);
    EXPECT_EQ(nudged, 0);
    for (std::size_t f = 0; f < pair.size(); ++f) EXPECT_EQ(out[f].mesh.vertices, pair[f].mesh.vertices);
  }
}

}  // namespace
}  // namespace ps
