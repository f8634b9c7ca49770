// The 2D-arrangement union of stacked straight prisms (modeling/zone_stacked_union.h), against
// CGAL's exact 3D union of the same prisms: same solid (volume, area, genus), a closed oriented
// manifold without self-intersections, refused (std::nullopt) where its preconditions fail.
#include <gtest/gtest.h>

#include <cmath>

#include "modeling/cylinder_builder.h"
#include "modeling/face_intersections.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/reconstruct.h"
#include "modeling/section_validate.h"
#include "modeling/zone_partition.h"
#include "modeling/zone_stacked_union.h"
#include "modeling/zone_union.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

void add_curve(SectionSet& s, double z, std::vector<Vec3> pts) {
  Plane pl;
  pl.normal = Vec3::UnitZ();
  pl.offset = z;
  int plane = -1;
  for (std::size_t i = 0; i < s.planes.size(); ++i)
    if (s.planes[i].offset == z) plane = static_cast<int>(i);
  if (plane < 0) {
    s.planes.push_back(pl);
    plane = static_cast<int>(s.planes.size()) - 1;
  }
  s.curves.push_back(CrossSection{plane, std::move(pts)});
}

// Ellipses on z planes whose outlines cross their neighbours' (wide, then tall, then shifted),
// a ring (two circles on one plane, rule 2) and an ellipse crossing both of its loops.
SectionSet crossing_stack() {
  SectionSet s;
  add_curve(s, -0.75, testing::ellipse(2, -0.75, 0.0, 0.0, 1.0, 0.45, 60));
  add_curve(s, -0.25, testing::ellipse(2, -0.25, 0.05, 0.0, 0.45, 1.0, 64));
  add_curve(s, 0.25, testing::ellipse(2, 0.25, 0.0, 0.0, 0.9, 0.9, 72));
  add_curve(s, 0.25, testing::ellipse(2, 0.25, 0.0, 0.0, 0.4, 0.4, 40));
  add_curve(s, 0.75, testing::ellipse(2, 0.75, 0.3, -0.1, 1.1, 0.3, 56));
  return s;
}

struct Zones {
  Partition part;
  std::vector<ZonePrimitives> prims;
};

Zones zones_of(const SectionSet& s) {
  auto v = validate_sections(s);
  EXPECT_TRUE(v) << v.message();
  std::vector<Vec3> pts;
  for (const auto& c : v->sections.curves) pts.insert(pts.end(), c.points.begin(), c.points.end());
  auto p = partition_zones(*v, default_reconstruction_box(pts));
  EXPECT_TRUE(p) << p.message();
  Zones z{*p, {}};
  z.prims = build_cylinders(z.part);
  return z;
}

// Every zone the arrangement accepts gives the solid CGAL's union gives.
int expect_same_as_corefinement(const Zones& zs) {
  int stacked = 0;
  for (std::size_t z = 0; z < zs.prims.size(); ++z) {
    if (zs.prims[z].solids.empty()) continue;
    const auto ours = stacked_zone_union(zs.part, zs.part.zones[z], zs.prims[z]);
    if (!ours) continue;
    ++stacked;
    const MeshGuarantees g = check_guarantees(*ours);
    EXPECT_TRUE(g.valid()) << "zone " << z << ": " << g.problem();
    EXPECT_EQ(g.topology.degenerate_faces, 0) << "zone " << z;
    auto cgal = union_solids(zs.prims[z].solids);
    if (!cgal) {
      ADD_FAILURE() << "zone " << z << ": CGAL refused " << cgal.message();
      continue;
    }
    const MeshTopology t = mesh_topology(*cgal);
    EXPECT_NEAR(g.topology.signed_volume, t.signed_volume, 1e-12 * std::abs(t.signed_volume)) << "zone " << z;
    EXPECT_NEAR(g.topology.area, t.area, 1e-12 * t.area) << "zone " << z;
    EXPECT_EQ(g.topology.genus, t.genus) << "zone " << z;
    EXPECT_EQ(g.topology.components, t.components) << "zone " << z;
  }
  return stacked;
}

TEST(StackedUnion, SameSolidAsCorefinementWithCrossingOutlinesAndARing) {
  const Zones zs = zones_of(crossing_stack());
  // 3 slabs between the 4 planes hold prisms from both faces; the 2 outer ones from one face.
  EXPECT_EQ(expect_same_as_corefinement(zs), 5);
}

TEST(StackedUnion, SameSolidAsCorefinementOnNestedEllipsoidSlices) {
  // Parallel slices only: z planes of an ellipsoid, all nested outlines (no crossing).
  std::vector<testing::SliceSpec> slices;
  for (double o : {-0.6, -0.3, 0.0, 0.3, 0.6}) slices.push_back({2, o});
  const Zones zs = zones_of(testing::ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 0.9), slices, 48));
  EXPECT_EQ(expect_same_as_corefinement(zs), 6);
}

// Orthogonal sections give zones with prisms along several axes: not this construction's.
TEST(StackedUnion, ZonesWithPrismsAlongSeveralAxesAreLeftToCorefinement) {
  std::vector<testing::SliceSpec> slices = {{0, 0.0}, {1, 0.0}, {2, 0.0}};
  const Zones zs = zones_of(testing::ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 0.9), slices, 48));
  int several = 0;
  for (std::size_t z = 0; z < zs.prims.size(); ++z) {
    bool mixed = false;
    for (const auto& info : zs.prims[z].info) mixed |= info.face / 2 != zs.prims[z].info.front().face / 2;
    if (!mixed) continue;
    ++several;
    EXPECT_FALSE(stacked_zone_union(zs.part, zs.part.zones[z], zs.prims[z])) << "zone " << z;
  }
  EXPECT_GT(several, 0);
}

// Outlines that touch or overlap are refused, not approximated: identical squares on two planes
// (every wall overlaps), and a rectangle sharing part of one edge with the square.
TEST(StackedUnion, TouchingOrOverlappingOutlinesAreRefused) {
  auto rect = [](double z, double x0, double y0, double x1, double y1) {
    return std::vector<Vec3>{Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z)};
  };
  for (const bool identical : {true, false}) {
    SectionSet s;
    add_curve(s, -0.5, rect(-0.5, -0.5, -0.5, 0.5, 0.5));
    add_curve(s, 0.5, identical ? rect(0.5, -0.5, -0.5, 0.5, 0.5) : rect(0.5, 0.0, -0.5, 1.0, 0.25));
    const Zones zs = zones_of(s);
    int refused = 0;
    for (std::size_t z = 0; z < zs.prims.size(); ++z) {
      bool low = false, high = false;
      for (const auto& info : zs.prims[z].info) (info.face % 2 == 0 ? low : high) = true;
      if (!low || !high) continue;
      EXPECT_FALSE(stacked_zone_union(zs.part, zs.part.zones[z], zs.prims[z])) << "identical " << identical;
      ++refused;
    }
    EXPECT_EQ(refused, 1) << "identical " << identical;
    // The reconstruction still succeeds: that zone goes to the exact union.
    ReconstructReport rep;
    auto m = reconstruct(s, testing::no_improve(), &rep);
    ASSERT_TRUE(m) << m.message();
    EXPECT_TRUE(check_guarantees(*m).valid());
    EXPECT_EQ(rep.zones_stacked, 2) << "the two end zones (one face each)";
  }
}

// A prism changed after building (as a topology edit does) is not the straight prism over its
// piece: refused.
TEST(StackedUnion, APrismThatIsNotTheStraightPrismOverItsPieceIsRefused) {
  Zones zs = zones_of(crossing_stack());
  std::size_t z = 0;
  while (z < zs.prims.size() && !stacked_zone_union(zs.part, zs.part.zones[z], zs.prims[z])) ++z;
  ASSERT_LT(z, zs.prims.size());
  TriMesh& m = zs.prims[z].solids.front();
  m.vertices[m.vertices.size() - 1].x() += 1e-3;  // a top vertex moved
  EXPECT_FALSE(stacked_zone_union(zs.part, zs.part.zones[z], zs.prims[z]));
}

// Whole reconstructions: every slab zone of a parallel stack takes the 2D union; the result
// meets the guarantees, its volume matches the same input mirrored in x (the arrangement then
// meets every loop reversed, the other way round), and translating the input translates it.
TEST(StackedUnion, ReconstructionsOfParallelStacksAreValidAndEquivariant) {
  const SectionSet s = crossing_stack();
  ReconstructReport rep;
  auto m = reconstruct(s, testing::no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const MeshGuarantees g = check_guarantees(*m);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(rep.zones_stacked, rep.zones_recomputed);
  EXPECT_EQ(rep.zones_stacked, 5);

  SectionSet mirrored = s, moved = s;
  for (auto& c : mirrored.curves) {
    for (auto& p : c.points) p.x() = -p.x();
    std::reverse(c.points.begin(), c.points.end());
  }
  const Vec3 d(0.375, -1.25, 0.5);
  for (auto& pl : moved.planes) pl.offset += d.z();
  for (auto& c : moved.curves)
    for (auto& p : c.points) p += d;
  auto mm = reconstruct(mirrored, testing::no_improve());
  auto mt = reconstruct(moved, testing::no_improve());
  ASSERT_TRUE(mm && mt);
  EXPECT_TRUE(check_guarantees(*mm).valid());
  EXPECT_TRUE(check_guarantees(*mt).valid());
  const double v = g.topology.signed_volume;
  EXPECT_NEAR(mesh_topology(*mm).signed_volume, v, 1e-9 * v);
  EXPECT_NEAR(mesh_topology(*mt).signed_volume, v, 1e-9 * v);
}

}  // namespace
}  // namespace ps
