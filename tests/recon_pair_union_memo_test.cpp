// Remembered pair unions (modeling/pair_union_memo.h), on the zone of stress seed 9
// (tests/data/zone_nudge_seed9/README.md): the same answers as corefinement, each pair computed
// once, and a changed frustum never answered from the memo.
#include "modeling/pair_union_memo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "modeling/frustum_connectors.h"
#include "modeling/frustum_nudge.h"
#include "modeling/zone_stitch.h"
#include "tests/zone_fixture.h"

namespace ps {
namespace {

// The same frusta, one by one.
void expect_same_frusta(const std::vector<SnappedSolid>& a, const std::vector<SnappedSolid>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t f = 0; f < a.size(); ++f) EXPECT_TRUE(same_solid(a[f], b[f])) << f;
}

TEST(PairUnionMemo, AnswersAsCorefinementAndComputesEachPairOnce) {
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta_offset();
  ASSERT_EQ(frusta.size(), 6u);
  PairUnionMemo memo(planes);
  int refused = 0;
  for (std::size_t i = 0; i < frusta.size(); ++i)
    for (std::size_t j = i + 1; j < frusta.size(); ++j) {
      const bool direct = static_cast<bool>(union_snapped_solids({frusta[i], frusta[j]}, planes));
      EXPECT_EQ(memo.unites(frusta[i], frusta[j]), direct) << i << " " << j;
      refused += direct ? 0 : 1;
    }
  EXPECT_GE(refused, 1);  // pair (4, 5) is refused as it is (frustum_nudge_test)
  EXPECT_EQ(memo.computed(), 15u);
  EXPECT_EQ(memo.hits(), 0u);
  // Asked again (copies, not the same objects): answered from the memo.
  const auto copies = frusta;
  for (std::size_t i = 0; i < copies.size(); ++i)
    for (std::size_t j = i + 1; j < copies.size(); ++j)
      EXPECT_EQ(memo.unites(copies[i], copies[j]), memo.unites(frusta[i], frusta[j]));
  EXPECT_EQ(memo.computed(), 15u);
  EXPECT_EQ(memo.hits(), 30u);
}

TEST(PairUnionMemo, AChangedFrustumIsComputedAgain) {
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta_offset();
  PairUnionMemo memo(planes);
  ASSERT_FALSE(memo.unites(frusta[4], frusta[5]));
  // One top coordinate moved by one ulp: another solid, so another corefinement.
  auto moved = frusta[5];
  const std::size_t top = moved.mesh.vertices.size() - 1;
  moved.mesh.vertices[top].x() = std::nextafter(moved.mesh.vertices[top].x(), std::numeric_limits<double>::infinity());
  EXPECT_FALSE(same_solid(moved, frusta[5]));
  memo.unites(frusta[4], moved);
  EXPECT_EQ(memo.computed(), 2u);
  // A tag changed: another solid too.
  auto retagged = frusta[5];
  retagged.tags[0][2] = retagged.tags[0][2] < 0 ? 0 : -1;
  EXPECT_FALSE(same_solid(retagged, frusta[5]));
  // The pair in the other order is another request.
  memo.unites(frusta[5], frusta[4]);
  EXPECT_EQ(memo.computed(), 3u);
  EXPECT_EQ(memo.hits(), 0u);
}

TEST(PairUnionMemo, RepairsGiveTheSameFrustaWithAndWithoutIt) {
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta_offset();
  PairUnionMemo memo(planes);
  int c1 = -1, c2 = -1, n1 = -1, n2 = -1;
  const auto connected = with_frustum_connectors(frusta, planes, &c1);
  const auto connected_memo = with_frustum_connectors(frusta, planes, &c2, &memo);
  EXPECT_EQ(c1, c2);
  expect_same_frusta(connected, connected_memo);
  const std::size_t computed_by_connectors = memo.computed();
  const auto leaned = with_overlap_nudges(frusta, planes, &n1);
  const auto leaned_memo = with_overlap_nudges(frusta, planes, &n2, &memo);
  EXPECT_EQ(n1, n2);
  EXPECT_EQ(n1, 1);
  expect_same_frusta(leaned, leaned_memo);
  // The nudges asked about pairs the connectors had already asked about.
  EXPECT_GE(computed_by_connectors, 1u);
  EXPECT_GE(memo.hits(), 1u);
}

TEST(SolidVerdicts, RemembersByContentAndForgetsTheOldest) {
  auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta_offset();
  ASSERT_GE(frusta.size(), 6u);
  SolidVerdicts v(4);
  EXPECT_EQ(v.find(frusta[0], planes), -1);
  v.add(frusta[0], planes, true);
  v.add(frusta[1], planes, false);
  const auto copy = frusta[0];
  EXPECT_EQ(v.find(copy, planes), 1);
  EXPECT_EQ(v.find(frusta[1], planes), 0);
  // Another solid, or the same solid on other planes: not known.
  auto moved = frusta[0];
  moved.mesh.vertices[0].z() = std::nextafter(moved.mesh.vertices[0].z(), 0.0);
  EXPECT_EQ(v.find(moved, planes), -1);
  auto other_planes = planes;
  other_planes.back().offset = std::nextafter(other_planes.back().offset, 1e300);
  EXPECT_EQ(v.find(frusta[0], other_planes), -1);
  // -0 and +0 are the same coordinate.
  auto zero = frusta[2];
  zero.mesh.vertices[0].x() = 0.0;
  v.add(zero, planes, true);
  auto negative_zero = zero;
  negative_zero.mesh.vertices[0].x() = -0.0;
  EXPECT_EQ(v.find(negative_zero, planes), 1);
  // Full: the oldest half goes first.
  v.add(frusta[3], planes, false);
  v.add(frusta[4], planes, true);
  EXPECT_LE(v.size(), 4u);
  EXPECT_EQ(v.find(frusta[0], planes), -1);
  EXPECT_EQ(v.find(frusta[4], planes), 1);
}

TEST(SolidVerdicts, RepeatedUnionsAnswerAlike) {
  // union_snapped_solids remembers its operands' self-intersection tests per thread: the same
  // request gives the same result the second time, and a refused pair stays refused. (The raw
  // numbering of a corefinement's output follows the operands' addresses; the reconstruction
  // canonicalizes every zone's union, and so does this comparison.)
  const auto planes = testing::read_seed9_planes();
  const auto frusta = testing::read_seed9_frusta_offset();
  for (int round = 0; round < 2; ++round) {
    auto all = union_snapped_solids(frusta, planes);
    EXPECT_FALSE(all) << round;
    auto pair = union_snapped_solids({frusta[0], frusta[2]}, planes);
    ASSERT_TRUE(pair) << round;
    canonicalize(*pair);
    static TriMesh first;
    if (round == 0) first = *pair;
    else {
      EXPECT_EQ(pair->faces, first.faces);
      EXPECT_EQ(pair->vertices, first.vertices);
    }
  }
}

SnappedSolid unit_cube(const Vec3& shift) {
  SnappedSolid c;
  for (int i = 0; i < 8; ++i) c.mesh.vertices.push_back(shift + Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  c.mesh.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                  {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  c.tags.assign(8, {-1, -1, -1});
  return c;
}

TEST(SolidVerdicts, ASelfIntersectingOperandIsRefusedEveryTime) {
  const std::vector<Plane> planes{Plane{}};
  SnappedSolid folded = unit_cube(Vec3::Zero());
  folded.mesh.vertices[7] = Vec3(0.5, 0.5, -2.0);  // the top corner pushed through the bottom
  const SnappedSolid cube = unit_cube(Vec3(3, 0, 0));
  ASSERT_TRUE(union_snapped_solids({cube}, planes));
  for (int round = 0; round < 3; ++round) {
    auto alone = union_snapped_solids({folded}, planes);
    ASSERT_FALSE(alone) << round;
    EXPECT_NE(alone.message().find("intersects itself"), std::string::npos) << alone.message();
    auto both = union_snapped_solids({cube, folded}, planes);
    ASSERT_FALSE(both) << round;
    EXPECT_NE(both.message().find("frustum 1 intersects itself"), std::string::npos) << both.message();
    EXPECT_TRUE(union_snapped_solids({cube}, planes)) << round;
  }
}

}  // namespace
}  // namespace ps
