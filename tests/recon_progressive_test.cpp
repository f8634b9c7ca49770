// Progressive reconstruction (thesis 4.6): order independence, locality, thread-count
// independence and caching.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>
#include <tuple>

#include "modeling/mesh_queries.h"
#include "modeling/progressive_reconstructor.h"
#include "modeling/reconstruct.h"
#include "modeling/section_validate.h"
#include "modeling/zone_partition.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

using ps::testing::no_improve;

SectionSet five_sections() {
  return testing::ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 0.6),
                                   {{0, -0.3}, {0, 0.4}, {1, 0.1}, {2, -0.2}, {2, 0.25}}, 20);
}

// The sections permuted: curves reordered, each curve on its own plane entry.
SectionSet permuted(const SectionSet& s, const std::vector<int>& order) {
  SectionSet out;
  for (int i : order) {
    const auto& c = s.curves[static_cast<std::size_t>(i)];
    out.planes.push_back(s.planes[static_cast<std::size_t>(c.plane)]);
    out.curves.push_back(CrossSection{static_cast<int>(out.planes.size()) - 1, c.points});
  }
  return out;
}

void expect_identical(const TriMesh& a, const TriMesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.faces.size(), b.faces.size());
  EXPECT_TRUE(a.vertices == b.vertices);
  EXPECT_TRUE(a.faces == b.faces);
}

TEST(ReconProgressive, EveryPermutationGivesTheIdenticalMesh) {
  const SectionSet s = five_sections();
  ASSERT_EQ(s.curves.size(), 5u);
  auto reference = reconstruct(s, no_improve());
  ASSERT_TRUE(reference) << reference.message();
  EXPECT_TRUE(check_guarantees(*reference).valid());
  // One reconstructor for all 120 orders: the zone cache makes this cheap, and a cache hit must
  // give the same mesh as a fresh computation.
  ProgressiveReconstructor r(no_improve());
  std::vector<int> order(5);
  std::iota(order.begin(), order.end(), 0);
  int count = 0;
  do {
    auto m = r.update(permuted(s, order));
    ASSERT_TRUE(m) << m.message();
    expect_identical(*reference, *m);
    ++count;
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(count, 120);
}

TEST(ReconProgressive, AddingInAnyOrderEndsWithTheSameMesh) {
  const SectionSet s = five_sections();
  Box3 box;
  box.min = Vec3::Constant(-2.0);
  box.max = Vec3::Constant(2.0);
  TriMesh first;
  const std::vector<std::vector<int>> orders{{0, 1, 2, 3, 4}, {4, 3, 2, 1, 0}, {2, 0, 4, 1, 3}};
  for (std::size_t o = 0; o < orders.size(); ++o) {
    ProgressiveReconstructor r(no_improve());
    r.set_box(box);
    Result<TriMesh> m = TriMesh{};
    for (int i : orders[o]) {
      const auto& c = s.curves[static_cast<std::size_t>(i)];
      m = r.add(s.planes[static_cast<std::size_t>(c.plane)], c.points);
      ASSERT_TRUE(m) << m.message();
      EXPECT_TRUE(check_guarantees(*m).valid());
    }
    if (o == 0)
      first = *m;
    else
      expect_identical(first, *m);
  }
}

TEST(ReconProgressive, FarSectionLeavesDistantZonesBitIdentical) {
  const SectionSet s = testing::ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 0.6), {{0, 0.0}, {1, 0.0}, {2, 0.0}}, 32);
  ProgressiveReconstructor r(no_improve());
  Box3 box;
  box.min = Vec3::Constant(-3.0);
  box.max = Vec3::Constant(3.0);
  r.set_box(box);
  auto before = r.update(s);
  ASSERT_TRUE(before) << before.message();
  // A small circle on the existing plane z = 0, far away in the octant x > 0, y > 0.
  SectionSet t = s;
  t.curves.push_back(CrossSection{2, testing::ellipse(2, 0.0, 2.2, 2.2, 0.3, 0.3, 24)});
  ReconstructReport rep;
  auto after = r.update(t, &rep);
  ASSERT_TRUE(after) << after.message();
  EXPECT_TRUE(check_guarantees(*after).valid());
  EXPECT_EQ(rep.zones_recomputed, 2);  // the two zones touching the new piece
  auto far = [](const TriMesh& m) {
    std::vector<std::tuple<double, double, double>> out;
    for (const auto& v : m.vertices)
      if (v.x() < -1e-9 || v.y() < -1e-9) out.emplace_back(v.x(), v.y(), v.z());
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto a = far(*before), b = far(*after);
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a == b);
}

// The clipping cache: a partition built with the clippings of another set is the fresh one.
// The added plane x = -1.5 lies below every other region's cells along x, so the cached
// clippings of the y and z sections come back with cell indices shifted by one.
TEST(ReconProgressive, CachedClippingsGiveTheFreshPartition) {
  const SectionSet s = five_sections();
  SectionSet t = s;
  testing::add_circle(t, 0, -1.5, 0.0, 0.0, 0.2, 24);
  Box3 box;
  box.min = Vec3::Constant(-2.0);
  box.max = Vec3::Constant(2.0);
  const auto vs = validate_sections(s);
  const auto vt = validate_sections(t);
  ASSERT_TRUE(vs) << vs.message();
  ASSERT_TRUE(vt) << vt.message();
  ClipCache first, second;
  ASSERT_TRUE(partition_zones(*vs, box, nullptr, &first));
  const auto cached = partition_zones(*vt, box, &first, &second);
  const auto fresh = partition_zones(*vt, box);
  ASSERT_TRUE(cached);
  ASSERT_TRUE(fresh);
  int reused = 0;
  for (const auto& [hash, entry] : second.entries) reused += first.find(hash, entry.first) != nullptr ? 1 : 0;
  EXPECT_EQ(reused, static_cast<int>(vs->regions.size()));
  ASSERT_EQ(cached->pieces.size(), fresh->pieces.size());
  for (std::size_t i = 0; i < fresh->pieces.size(); ++i) {
    const SectionPiece &a = cached->pieces[i], &b = fresh->pieces[i];
    EXPECT_EQ(a.plane, b.plane);
    EXPECT_EQ(a.layer, b.layer);
    EXPECT_EQ(a.cell, b.cell);
    EXPECT_TRUE(a.loops == b.loops) << "piece " << i;
  }
  ASSERT_EQ(cached->zones.size(), fresh->zones.size());
  for (std::size_t z = 0; z < fresh->zones.size(); ++z) {
    EXPECT_EQ(cached->zones[z].face_pieces, fresh->zones[z].face_pieces) << "zone " << z;
    EXPECT_EQ(cached->zones[z].type, fresh->zones[z].type) << "zone " << z;
  }
}

TEST(ReconProgressive, EditAndDeleteRecomputeOnlyAffectedZones) {
  const SectionSet s = five_sections();
  ProgressiveReconstructor r(no_improve());
  ReconstructReport rep;
  ASSERT_TRUE(r.update(s, &rep));
  const int all = rep.zones_recomputed;
  ASSERT_TRUE(r.update(s, &rep));
  EXPECT_EQ(rep.zones_recomputed, 0);
  // Removing a curve and adding it back restores the same mesh from the cache... for the zones
  // it did not touch; the result equals a fresh reconstruction.
  const TriMesh full = r.mesh();
  auto removed = r.remove(4, &rep);
  ASSERT_TRUE(removed) << removed.message();
  EXPECT_LT(rep.zones_recomputed, all);
  EXPECT_TRUE(check_guarantees(*removed).valid());
  const auto& c = s.curves[4];
  auto back = r.add(s.planes[static_cast<std::size_t>(c.plane)], c.points, &rep);
  ASSERT_TRUE(back) << back.message();
  expect_identical(full, *back);
}

TEST(ReconProgressive, RefusedInputLeavesStateUnchanged) {
  const SectionSet s = five_sections();
  ProgressiveReconstructor r(no_improve());
  ASSERT_TRUE(r.update(s));
  const TriMesh before = r.mesh();
  std::vector<Vec3> bad{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};  // bow tie
  auto m = r.add(Plane{Vec3::UnitZ(), 0.0}, bad);
  ASSERT_FALSE(m);
  EXPECT_NE(m.message().find("crosses itself"), std::string::npos) << m.message();
  EXPECT_EQ(r.sections().curves.size(), 5u);
  expect_identical(before, r.mesh());
}

TEST(ReconProgressive, SameResultWithOneAndTwoThreads) {
  const SectionSet s = testing::torus_slices(1.0, 0.35, 40);
  TriMesh one, two;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    auto m = reconstruct(s, no_improve());
    ASSERT_TRUE(m) << m.message();
    one = *m;
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    ReconstructOptions o = no_improve();
    o.threads = 2;
    auto m = reconstruct(s, o);
    ASSERT_TRUE(m) << m.message();
    two = *m;
  }
  expect_identical(one, two);
}

}  // namespace
}  // namespace ps
