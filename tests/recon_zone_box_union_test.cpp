// The union of a zone filled by six whole-face prisms (zone_box_union.h) equals the exact union
// (CGAL corefinement) on every zone of a real reconstruction input where it applies, and it
// refuses what it cannot prove.
#include <gtest/gtest.h>

#include "modeling/cylinder_builder.h"
#include "modeling/section_validate.h"
#include "modeling/zone_box_union.h"
#include "modeling/zone_partition.h"
#include "modeling/zone_stitch.h"
#include "modeling/zone_union.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

struct Input {
  Partition partition;
  std::vector<ZonePrimitives> primitives;
};

// The benchmark's input (bench/recon_bench.cpp): an ellipsoid sliced by 7 planes per axis.
Input ellipsoid_input() {
  std::vector<testing::SliceSpec> slices;
  for (int k = 0; k < 3; ++k)
    for (double o : {-0.72, -0.48, -0.24, 0.02, 0.26, 0.5, 0.74}) slices.push_back({k, o});
  const SectionSet model = testing::ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.85, 0.9), slices, 48);
  auto v = validate_sections(model);
  EXPECT_TRUE(v) << v.message();
  Box3 box;
  box.min = Vec3::Constant(-2.0);
  box.max = Vec3::Constant(2.0);
  auto p = partition_zones(*v, box);
  EXPECT_TRUE(p) << p.message();
  Input in{*p, {}};
  in.primitives = build_cylinders(in.partition);
  return in;
}

TEST(ZoneBoxUnion, EqualsTheExactUnionWhereverItApplies) {
  const Input in = ellipsoid_input();
  int applied = 0;
  for (std::size_t z = 0; z < in.primitives.size(); ++z) {
    auto filled = filled_zone_union(in.partition.zones[z], in.primitives[z]);
    if (!filled) continue;
    ++applied;
    auto exact = union_solids(in.primitives[z].solids);
    ASSERT_TRUE(exact) << exact.message();
    TriMesh a = *filled, b = *exact;
    canonicalize(a);
    canonicalize(b);
    EXPECT_EQ(a.vertices, b.vertices) << "zone " << z;
    EXPECT_EQ(a.faces, b.faces) << "zone " << z;
  }
  // Inside the ellipsoid every zone face is covered: 109 of the 369 body zones.
  EXPECT_EQ(applied, 109);
}

TEST(ZoneBoxUnion, RefusesWhatItCannotProve) {
  const Input in = ellipsoid_input();
  std::size_t z = 0;
  while (z < in.primitives.size() && !filled_zone_union(in.partition.zones[z], in.primitives[z])) ++z;
  ASSERT_LT(z, in.primitives.size());
  const Zone& zone = in.partition.zones[z];
  {  // Five prisms: a face left open.
    ZonePrimitives p = in.primitives[z];
    p.solids.pop_back();
    p.info.pop_back();
    EXPECT_FALSE(filled_zone_union(zone, p));
  }
  {  // A prism lowered below half the zone (as a split edit might shrink it).
    ZonePrimitives p = in.primitives[z];
    const int k = p.info[0].face / 2;
    const double base = p.solids[0].vertices[0][k];
    for (std::size_t v = 4; v < 8; ++v) p.solids[0].vertices[v][k] = base + 0.4 * (p.solids[0].vertices[v][k] - base);
    EXPECT_FALSE(filled_zone_union(zone, p));
  }
  {  // A top corner outside its bottom corner (pulled outward).
    ZonePrimitives p = in.primitives[z];
    const int a = (p.info[1].face / 2 + 1) % 3;
    const double bottom = p.solids[1].vertices[0][a];
    p.solids[1].vertices[4][a] = bottom + (bottom == zone.min[a] ? -1.0 : 1.0) * 1e-3 * zone.extent(a);
    EXPECT_FALSE(filled_zone_union(zone, p));
  }
  {  // A bottom corner off the face's corner.
    ZonePrimitives p = in.primitives[z];
    const int a = (p.info[2].face / 2 + 1) % 3;
    p.solids[2].vertices[0][a] = 0.5 * (zone.min[a] + zone.max[a]);
    EXPECT_FALSE(filled_zone_union(zone, p));
  }
  {  // Two prisms on one face.
    ZonePrimitives p = in.primitives[z];
    p.info[3].face = p.info[4].face;
    EXPECT_FALSE(filled_zone_union(zone, p));
  }
}

}  // namespace
}  // namespace ps
