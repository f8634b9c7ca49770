// Input validation of cross sections (stroke rules) and nesting per plane.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "modeling/reconstruct.h"
#include "modeling/section_validate.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

SectionSet square_on_z(double z = 0.0, double size = 1.0) {
  SectionSet s;
  s.planes.push_back(Plane{Vec3::UnitZ(), z});
  s.curves.push_back(CrossSection{0, {Vec3(0, 0, z), Vec3(size, 0, z), Vec3(size, size, z), Vec3(0, size, z)}});
  return s;
}

void expect_error(const SectionSet& s, const std::string& fragment) {
  auto r = validate_sections(s);
  ASSERT_FALSE(r) << "expected an error containing '" << fragment << "'";
  EXPECT_NE(r.message().find(fragment), std::string::npos) << r.message();
  // reconstruct refuses it with the same message.
  ReconstructOptions o;
  o.improve = false;
  auto m = reconstruct(s, o);
  ASSERT_FALSE(m);
  EXPECT_EQ(m.message(), r.message());
}

TEST(ReconValidate, EmptySet) { expect_error(SectionSet{}, "empty"); }

TEST(ReconValidate, NonFiniteCoordinate) {
  SectionSet s = square_on_z();
  s.curves[0].points[2].x() = std::numeric_limits<double>::quiet_NaN();
  expect_error(s, "curve 0: point 2 is not a finite number");
  s = square_on_z();
  s.curves[0].points[1].y() = std::numeric_limits<double>::infinity();
  expect_error(s, "curve 0: point 1 is not a finite number");
}

TEST(ReconValidate, TooFewPoints) {
  SectionSet s = square_on_z();
  s.curves[0].points.resize(2);
  expect_error(s, "curve 0: has 2 points");
}

TEST(ReconValidate, DuplicateConsecutivePoints) {
  SectionSet s = square_on_z();
  s.curves[0].points.insert(s.curves[0].points.begin() + 2, s.curves[0].points[1]);
  expect_error(s, "curve 0: points 1 and 2 coincide");
  s = square_on_z();
  s.curves[0].points.push_back(s.curves[0].points[0] + Vec3(1e-12, 0, 0));
  expect_error(s, "curve 0: points 4 and 0 coincide");
}

TEST(ReconValidate, ZeroArea) {
  SectionSet s;
  s.planes.push_back(Plane{Vec3::UnitZ(), 0.0});
  s.curves.push_back(CrossSection{0, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}});
  expect_error(s, "curve 0: encloses zero area");
}

TEST(ReconValidate, OffPlaneErrorWarningAndSilentProjection) {
  SectionSet s = square_on_z();
  s.curves[0].points[2].z() = 0.01;  // 0.007 of the diagonal ~1.42: error
  expect_error(s, "curve 0: lies off its plane 0");

  s = square_on_z();
  s.curves[0].points[2].z() = 1e-4;  // between 1e-6 and 1e-3 of the diagonal: warning
  auto r = validate_sections(s);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_NE(r->warnings[0].find("curve 0: projected"), std::string::npos);
  EXPECT_EQ(r->sections.curves[0].points[2].z(), 0.0);

  s = square_on_z();
  s.curves[0].points[2].z() = 1e-9;  // silent
  r = validate_sections(s);
  ASSERT_TRUE(r) << r.message();
  EXPECT_TRUE(r->warnings.empty());
  EXPECT_EQ(r->sections.curves[0].points[2].z(), 0.0);
}

TEST(ReconValidate, SelfCrossing) {
  SectionSet s;
  s.planes.push_back(Plane{Vec3::UnitZ(), 0.0});
  s.curves.push_back(CrossSection{0, {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}});
  expect_error(s, "curve 0 crosses itself");
  // Folding back along an edge is a self-overlap.
  s.curves[0].points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};
  expect_error(s, "curve 0 crosses itself");
}

TEST(ReconValidate, CurvesOnOnePlaneCross) {
  SectionSet s = square_on_z();
  s.curves.push_back(CrossSection{0, {Vec3(0.5, 0.5, 0), Vec3(1.5, 0.5, 0), Vec3(1.5, 1.5, 0), Vec3(0.5, 1.5, 0)}});
  expect_error(s, "curves 0 and 1 on plane 0 cross");
}

TEST(ReconValidate, ZeroNormal) {
  SectionSet s = square_on_z();
  s.planes[0].normal = Vec3::Zero();
  expect_error(s, "plane 0: zero normal");
}

TEST(ReconValidate, BadPlaneIndex) {
  SectionSet s = square_on_z();
  s.curves[0].plane = 3;
  expect_error(s, "curve 0: plane index 3 does not exist");
}

TEST(ReconValidate, CoincidentPlanesAreMerged) {
  SectionSet s = square_on_z(0.0, 1.0);
  s.planes.push_back(Plane{-Vec3::UnitZ() * 2.0, 0.0});  // same plane, other orientation, not unit
  s.curves.push_back(CrossSection{1, {Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(4, 1, 0), Vec3(3, 1, 0)}});
  auto r = validate_sections(s);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->sections.curves[1].plane, 0);
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_NE(r->warnings[0].find("coincide"), std::string::npos);
  EXPECT_EQ(r->regions.size(), 2u);
}

TEST(ReconValidate, NormalsAreCanonical) {
  SectionSet s = square_on_z(0.5);
  s.planes[0] = Plane{Vec3(0, 0, -4.0), -2.0};  // z = 0.5 written as -4 z = -2
  auto r = validate_sections(s);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->sections.planes[0].normal, Vec3::UnitZ());
  EXPECT_EQ(r->sections.planes[0].offset, 0.5);
}

TEST(ReconValidate, NestingDepthAndRegions) {
  // Three nested circles and a separate one on z = 0, one circle on x = 0.
  SectionSet s;
  s.planes.push_back(Plane{Vec3::UnitZ(), 0.0});
  s.planes.push_back(Plane{Vec3::UnitX(), 0.0});
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0, 0, 0, 0.6, 0.6, 24)});
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0, 0, 0, 1.0, 1.0, 24)});
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0, 0, 0, 0.3, 0.3, 24)});
  s.curves.push_back(CrossSection{0, testing::ellipse(2, 0, 3, 0, 0.5, 0.5, 24)});
  s.curves.push_back(CrossSection{1, testing::ellipse(0, 0, 0, 0, 0.5, 0.5, 24)});
  auto r = validate_sections(s);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->depth, (std::vector<int>{1, 0, 2, 0, 0}));
  EXPECT_EQ(r->parent, (std::vector<int>{1, -1, 0, -1, -1}));
  ASSERT_EQ(r->regions.size(), 4u);  // ring (1 with hole 0), island 2, circle 3, circle 4
  EXPECT_EQ(r->regions[0].outer, 1);
  EXPECT_EQ(r->regions[0].holes, std::vector<int>{0});
  EXPECT_EQ(r->regions[1].outer, 2);
  EXPECT_TRUE(r->regions[1].holes.empty());
  EXPECT_EQ(r->regions[2].outer, 3);
  EXPECT_EQ(r->regions[3].outer, 4);
}

TEST(ReconValidate, SewingMakesOneSharedCrossingPoint) {
  // A square on z = 0 crossing the line {z = 0, x = 0.5} at y = 0 and y = 1; a square on x = 0.5
  // crossing the same line at y = 0.001 and y = 1.002.
  SectionSet s;
  s.planes.push_back(Plane{Vec3::UnitZ(), 0.0});
  s.planes.push_back(Plane{Vec3::UnitX(), 0.5});
  s.curves.push_back(CrossSection{0, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}});
  s.curves.push_back(CrossSection{1, {Vec3(0.5, 0.001, -0.5), Vec3(0.5, 1.002, -0.5), Vec3(0.5, 1.002, 0.5),
                                      Vec3(0.5, 0.001, 0.5)}});
  auto v = validate_sections(s);
  ASSERT_TRUE(v) << v.message();
  SectionSet sewn = v->sections;
  std::vector<std::string> warnings;
  EXPECT_EQ(sew_crossings(sewn, 0.02 * v->diagonal, &warnings), 2);
  EXPECT_TRUE(warnings.empty());
  // Both curves now hold the same two points on the line, half way between the crossings.
  for (const Vec3& p : {Vec3(0.5, 0.0005, 0.0), Vec3(0.5, 1.001, 0.0)}) {
    for (const auto& c : sewn.curves) {
      bool found = false;
      for (const auto& q : c.points) found = found || (q - p).norm() < 1e-15;
      EXPECT_TRUE(found) << p.transpose();
    }
  }
  EXPECT_EQ(sewn.curves[0].points.size(), 6u);
  EXPECT_TRUE(validate_sections(sewn));

  // A partner too far away is not sewn but reported.
  SectionSet far = v->sections;
  far.curves[1].points = {Vec3(0.5, 0.3, -0.5), Vec3(0.5, 1.002, -0.5), Vec3(0.5, 1.002, 0.5), Vec3(0.5, 0.3, 0.5)};
  warnings.clear();
  EXPECT_EQ(sew_crossings(far, 0.02 * v->diagonal, &warnings), 1);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("rule 4"), std::string::npos);
}

}  // namespace
}  // namespace ps
