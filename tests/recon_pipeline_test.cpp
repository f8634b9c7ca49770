// Reconstruction from orthogonal cross sections (thesis chapter 4) on analytic inputs: every
// result must be closed, 2-manifold, outward, free of self-intersections and contain every
// input curve point within 1e-6 of the bounding-box diagonal.
#include <gtest/gtest.h>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/reconstruct.h"
#include "modeling/zone_partition.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

using testing::add_circle;
using testing::ellipsoid_slices;
using testing::torus_slices;

using ps::testing::no_improve;

MeshGuarantees expect_valid(const SectionSet& s, const TriMesh& m) {
  const MeshGuarantees g = check_guarantees(m);
  EXPECT_TRUE(g.valid()) << g.problem();
  const auto pts = s.all_points();
  const double diag = bounding_box(pts).diagonal();
  EXPECT_LE(max_distance_to_surface(m, pts), 1e-6 * diag);
  return g;
}

TEST(ReconPipeline, SingleSection) {
  SectionSet s;
  add_circle(s, 2, 0.0, 0.0, 0.0, 1.0);
  ReconstructReport rep;
  auto m = reconstruct(s, no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 0);
  EXPECT_EQ(rep.zones, 2);
  EXPECT_EQ(rep.end_zones, 2);
  EXPECT_EQ(rep.primitives, 2);
}

TEST(ReconPipeline, TwoParallelSections) {
  const SectionSet s = ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 1.2), {{2, -0.4}, {2, 0.5}});
  ReconstructReport rep;
  auto m = reconstruct(s, no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 0);
  EXPECT_EQ(rep.body_zones, 1);
  EXPECT_EQ(rep.end_zones, 2);
}

TEST(ReconPipeline, ThreeOrthogonalSectionsOfAnEllipsoid) {
  const SectionSet s = ellipsoid_slices(Vec3(0.1, -0.2, 0.3), Vec3(1.0, 0.7, 0.5), {{0, 0.1}, {1, -0.2}, {2, 0.3}});
  ReconstructReport rep;
  auto m = reconstruct(s, no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 0);
  EXPECT_EQ(rep.zones, 8);
  EXPECT_EQ(rep.body_zones, 8);
}

TEST(ReconPipeline, OffCentreSlicesOfAnEllipsoid) {
  const SectionSet s = ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.8, 0.6),
                                        {{0, -0.4}, {0, 0.35}, {1, 0.2}, {2, -0.1}, {2, 0.3}});
  auto m = reconstruct(s, no_improve());
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 0);
}

TEST(ReconPipeline, TorusSlicesGiveGenusOne) {
  const SectionSet s = torus_slices(1.0, 0.35);
  auto m = reconstruct(s, no_improve());
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 1);
}

TEST(ReconPipeline, NestedCurvesRingAndIsland) {
  SectionSet s;
  add_circle(s, 2, 0.0, 0.0, 0.0, 1.0);
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0.0, 0.0, 0.0, 0.6, 0.6, 40)});
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0.0, 0.0, 0.0, 0.3, 0.3, 40)});
  ReconstructReport rep;
  auto m = reconstruct(s, no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  // A ring (genus 1) and an island inside its hole (genus 0): two components, a hint.
  EXPECT_EQ(g.topology.components, 2);
  EXPECT_EQ(g.topology.genus, 1);
  bool hinted = false;
  for (const auto& w : rep.warnings) hinted = hinted || w.find("2 components") != std::string::npos;
  EXPECT_TRUE(hinted);
}

TEST(ReconPipeline, EndZoneExtensionJoinsParts) {
  // A on z = 0 sits in an end zone whose far face (z = 1) carries a section only elsewhere (B);
  // its cylinder is stretched into the next zone, where it meets the cylinder of S (x = 1).
  SectionSet s;
  add_circle(s, 2, 0.0, 0.0, 0.0, 0.5);   // A
  add_circle(s, 2, 1.0, 2.0, 0.0, 0.5);   // B on z = 1, x in [1.5, 2.5]
  add_circle(s, 0, 1.0, 0.0, 1.5, 0.3);   // S on x = 1, (y, z) centred (0, 1.5)
  ReconstructReport rep;
  auto m = reconstruct(s, no_improve(), &rep);
  ASSERT_TRUE(m) << m.message();
  const auto g = expect_valid(s, *m);
  EXPECT_EQ(g.topology.components, 1);
  // The stretched cylinder of A rises above z = 1 near the z axis.
  double top = -1e9;
  for (const auto& v : m->vertices)
    if (std::abs(v.x()) < 0.5 && std::abs(v.y()) < 0.5) top = std::max(top, v.z());
  EXPECT_GT(top, 1.0);
}

TEST(ReconPipeline, ReportsCurveVerticesAndEdges) {
  const SectionSet s = ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.7, 0.5), {{0, 0.0}, {2, 0.1}});
  ReconstructOptions o;  // improvement on, no hook connected
  ReconstructReport rep;
  auto m = reconstruct(s, o, &rep);
  ASSERT_TRUE(m) << m.message();
  if (!improve_hook()) {
    bool warned = false;
    for (const auto& w : rep.warnings) warned = warned || w == "mesh improvement unavailable";
    EXPECT_TRUE(warned);
  }
  ASSERT_EQ(rep.curve_vertex.size(), m->vertices.size());
  // Every input point is a flagged vertex; every curve edge joins flagged vertices.
  for (const auto& c : s.curves)
    for (const auto& p : c.points) {
      bool found = false;
      for (std::size_t v = 0; v < m->vertices.size() && !found; ++v)
        found = rep.curve_vertex[v] && (m->vertices[v] - p).norm() == 0.0;
      EXPECT_TRUE(found) << p.transpose();
    }
  std::size_t curve_points = 0;
  for (const auto& c : s.curves) curve_points += c.points.size();
  EXPECT_GE(rep.curve_edges.size(), curve_points);
  for (const auto& e : rep.curve_edges) {
    EXPECT_TRUE(rep.curve_vertex[static_cast<std::size_t>(e[0])]);
    EXPECT_TRUE(rep.curve_vertex[static_cast<std::size_t>(e[1])]);
  }
}

TEST(ReconPipeline, TranslatedAndScaledInputGivesTransformedMesh) {
  const SectionSet s = ellipsoid_slices(Vec3::Zero(), Vec3(1.0, 0.7, 0.5), {{0, 0.0}, {1, 0.1}, {2, 0.1}}, 32);
  SectionSet t = s;
  // Power-of-two scale and translation keep every coordinate exact.
  const Vec3 shift(4.0, -2.0, 8.0);
  for (auto& p : t.planes) p.offset = 2.0 * p.offset + p.normal.dot(shift);
  for (auto& c : t.curves)
    for (auto& p : c.points) p = 2.0 * p + shift;
  auto a = reconstruct(s, no_improve());
  auto b = reconstruct(t, no_improve());
  ASSERT_TRUE(a) << a.message();
  ASSERT_TRUE(b) << b.message();
  EXPECT_EQ(a->faces.size(), b->faces.size());
  EXPECT_NEAR(8.0 * signed_volume(*a), signed_volume(*b), 1e-9 * signed_volume(*b));
}

TEST(ReconPipeline, DisagreeingCrossingsAreSewn) {
  // Slices sampled independently: where two planes meet, the curves cross the shared line at
  // slightly different points (stroke rule 4 only approximately); sewing makes them agree.
  SectionSet s;
  const Vec3 r(1.0, 0.8, 0.6);
  for (const auto& [k, o] : std::vector<std::pair<int, double>>{{0, -0.4}, {0, 0.35}, {1, 0.2}, {2, -0.1}, {2, 0.3}}) {
    const double t = 1 - std::pow(o / r[k], 2);
    Plane p;
    p.normal = Vec3::Unit(k);
    p.offset = o;
    s.planes.push_back(p);
    s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1,
                                    testing::ellipse(k, o, 0.0, 0.0, r[(k + 1) % 3] * std::sqrt(t), r[(k + 2) % 3] * std::sqrt(t), 40)});
  }
  auto m = reconstruct(s, no_improve());
  ASSERT_TRUE(m) << m.message();
  const MeshGuarantees g = check_guarantees(*m);
  EXPECT_TRUE(g.valid()) << g.problem();
  EXPECT_EQ(g.topology.components, 1);
  EXPECT_EQ(g.topology.genus, 0);
  // Input points that were not moved by sewing lie on the surface; moved ones (only those within
  // 1e-6 of the diagonal of a crossing) stay within that distance.
  const double diag = bounding_box(s.all_points()).diagonal();
  EXPECT_LE(max_distance_to_surface(*m, s.all_points()), 1e-6 * diag);
}

}  // namespace
}  // namespace ps
