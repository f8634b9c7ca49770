// Random cross-section generator: determinism by seed, curve sizes, simplicity, points on the
// implicit surface, orientation alternating with nesting depth, both plane kinds present, curves
// of different planes crossing their shared lines together (rule 4).
#include <gtest/gtest.h>

#include "modeling/contour_io.h"
#include "modeling/mesh_slicer.h"
#include "modeling/section_generator.h"
#include "modeling/section_validate.h"

using namespace ps;

namespace {

std::vector<Vec2> flat(const SectionSet& s, const CrossSection& c) {
  Vec3 u, v;
  s.planes[static_cast<std::size_t>(c.plane)].basis(u, v);
  std::vector<Vec2> f;
  for (const auto& q : c.points) f.emplace_back(q.dot(u), q.dot(v));
  return f;
}

double area2(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& x = p[i];
    const Vec2& y = p[(i + 1) % p.size()];
    a += x.x() * y.y() - x.y() * y.x();
  }
  return a;
}

bool inside(const Vec2& q, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
        q.x() < poly[i].x() + (q.y() - poly[i].y()) * (poly[j].x() - poly[i].x()) / (poly[j].y() - poly[i].y()))
      in = !in;
  return in;
}

}  // namespace

TEST(FormatsGenerator, SameSeedSameSectionsDifferentSeedDifferentSections) {
  GeneratorOptions o;
  o.seed = 11;
  const auto a = generate_sections(o), b = generate_sections(o);
  EXPECT_EQ(format_contour_json(a.sections), format_contour_json(b.sections));
  o.seed = 12;
  const auto c = generate_sections(o);
  EXPECT_NE(format_contour_json(a.sections), format_contour_json(c.sections));
}

TEST(FormatsGenerator, CurvesAreValidSimpleOnTheSurfaceAndConsistentlyOriented) {
  int oblique = 0, orthogonal = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    GeneratorOptions o;
    o.seed = seed;
    const auto g = generate_sections(o);
    const SectionSet& s = g.sections;
    ASSERT_FALSE(s.curves.empty()) << "seed " << seed;
    SectionSet copy = s;
    ASSERT_TRUE(finish_sections(copy, "generated")) << "seed " << seed;
    const double cell = g.shape.smallest_feature() / 8.0;
    for (const auto& p : s.planes) (p.axis() >= 0 ? orthogonal : oblique)++;
    for (std::size_t p = 0; p < s.planes.size(); ++p) {
      std::vector<std::vector<Vec2>> polys;
      for (const auto& c : s.curves)
        if (c.plane == static_cast<int>(p)) polys.push_back(flat(s, c));
      EXPECT_TRUE(polygons_are_simple(polys)) << "seed " << seed << " plane " << p;
      // Orientation: counter-clockwise at even nesting depth, clockwise at odd.
      for (std::size_t a = 0; a < polys.size(); ++a) {
        int depth = 0;
        for (std::size_t b = 0; b < polys.size(); ++b)
          if (a != b && inside(polys[a][0], polys[b])) ++depth;
        EXPECT_EQ(area2(polys[a]) > 0, depth % 2 == 0) << "seed " << seed << " plane " << p;
      }
    }
    for (const auto& c : s.curves) {
      EXPECT_GE(c.points.size(), 40u);
      EXPECT_LE(c.points.size(), 200u);
      for (const auto& q : c.points) {
        EXPECT_LE(std::abs(s.planes[static_cast<std::size_t>(c.plane)].signed_distance(q)), 1e-12);
        EXPECT_LE(std::abs(g.shape.value(q)), 1e-6 * cell) << "seed " << seed;
      }
    }
  }
  EXPECT_GT(orthogonal, 0);
  EXPECT_GT(oblique, 0);
}

TEST(FormatsGenerator, CurvesOfDifferentPlanesAgreeOnTheirSharedLines) {
  // Rule 4 as the reconstruction sews it: no crossing of a shared line without a partner on the
  // other plane (the mixed stress seeds 277, 397 and 558 had one before planes were checked).
  const std::uint64_t seeds[] = {1, 2, 3, 4, 5, 6, 7, 8, 277, 397, 558};
  for (std::uint64_t seed : seeds) {
    GeneratorOptions o;
    o.seed = seed;
    o.orthogonal_planes = 2 + static_cast<int>(seed % 5);
    o.oblique_planes = 1 + static_cast<int>(seed % 3);
    const auto g = generate_sections(o);
    auto checked = validate_sections(g.sections);
    ASSERT_TRUE(checked) << "seed " << seed << ": " << checked.message();
    SectionSet sewn = checked->sections;
    std::vector<std::string> warnings;
    sew_crossings(sewn, kSewTolerance * checked->diagonal, &warnings);
    for (const auto& w : warnings) EXPECT_EQ(w.find("(rule 4)"), std::string::npos) << "seed " << seed << ": " << w;
  }
}

TEST(FormatsGenerator, MarchingSquaresOnASphereGivesOneCircle) {
  ImplicitUnion u;
  Ellipsoid e;
  e.radii = Vec3(1, 1, 1);
  u.ellipsoids.push_back(e);
  const Plane p{Vec3(0, 0, 1), 0.6};
  const auto loops = contour_plane(u, p, 0.05);
  ASSERT_EQ(loops.size(), 1u);
  for (const auto& q : loops[0]) EXPECT_NEAR(Vec2(q.x(), q.y()).norm(), 0.8, 0.002);
  const auto far = contour_plane(u, Plane{Vec3(0, 0, 1), 1.5}, 0.05);
  EXPECT_TRUE(far.empty());
}

TEST(FormatsGenerator, TorusSliceThroughItsAxisGivesTwoDisks) {
  ImplicitUnion u;
  Torus t;
  t.major = 1.0;
  t.minor = 0.3;
  u.tori.push_back(t);
  // Through the axis: two circles of radius 0.3; across the axis at the centre: an annulus.
  EXPECT_EQ(contour_plane(u, Plane{Vec3(1, 0, 0), 0.0}, 0.03).size(), 2u);
  const auto ring = contour_plane(u, Plane{Vec3(0, 0, 1), 0.0}, 0.03);
  ASSERT_EQ(ring.size(), 2u);
  // Nested loops: the outer one (radius 1.3) counter-clockwise, the hole (radius 0.7) clockwise.
  SectionSet s;
  s.planes.push_back(Plane{Vec3(0, 0, 1), 0.0});
  for (const auto& loop : ring) s.curves.push_back({0, loop});
  const auto a = flat(s, s.curves[0]), b = flat(s, s.curves[1]);
  const bool a_outer = std::abs(area2(a)) > std::abs(area2(b));
  const auto& outer = a_outer ? a : b;
  const auto& hole = a_outer ? b : a;
  EXPECT_GT(area2(outer), 0);
  EXPECT_LT(area2(hole), 0);
  EXPECT_TRUE(inside(hole[0], outer));
  for (const auto& q : outer) EXPECT_NEAR(q.norm(), 1.3, 0.003);
  for (const auto& q : hole) EXPECT_NEAR(q.norm(), 0.7, 0.003);
}
