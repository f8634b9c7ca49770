// Mesh slicer: closed, simple curves on their planes and on the mesh surface; rule 4 at shared
// lines; plane-set helpers; determinism and metamorphic properties.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "modeling/contour_io.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_slicer.h"

using namespace ps;

namespace {

std::string cgal_mesh(const char* name) { return std::string(PLANESKETCH_CGAL_DATA) + "/" + name; }

std::vector<std::vector<Vec2>> flat_curves(const SectionSet& s, int plane) {
  Vec3 u, v;
  s.planes[static_cast<std::size_t>(plane)].basis(u, v);
  std::vector<std::vector<Vec2>> out;
  for (const auto& c : s.curves) {
    if (c.plane != plane) continue;
    std::vector<Vec2> f;
    for (const auto& q : c.points) f.emplace_back(q.dot(u), q.dot(v));
    out.push_back(std::move(f));
  }
  return out;
}

// Every invariant a slice result must satisfy.
void check_slices(const TriMesh& mesh, const SectionSet& s) {
  const double diag = bounding_box(mesh.vertices).diagonal();
  ASSERT_FALSE(s.curves.empty());
  for (std::size_t p = 0; p < s.planes.size(); ++p) {
    EXPECT_NEAR(s.planes[p].normal.norm(), 1.0, 1e-15);
    EXPECT_TRUE(polygons_are_simple(flat_curves(s, static_cast<int>(p)))) << "plane " << p;
  }
  for (const auto& c : s.curves) {
    ASSERT_GE(c.points.size(), 8u);
    const Plane& pl = s.planes[static_cast<std::size_t>(c.plane)];
    for (const auto& q : c.points) EXPECT_LE(std::abs(pl.signed_distance(q)), 1e-12 * diag);
    // Not absurdly dense: mean spacing at least a quarter of the target (diag / 60).
    double len = 0;
    for (std::size_t k = 0; k < c.points.size(); ++k) len += (c.points[(k + 1) % c.points.size()] - c.points[k]).norm();
    EXPECT_GE(len / static_cast<double>(c.points.size()), std::min(diag / 240.0, len / 8.0 - 1e-12));
  }
  EXPECT_LE(max_distance_to_surface(mesh, s.all_points()), 1e-7 * diag);
}

}  // namespace

TEST(FormatsSlicer, AxisPlanesAreEvenlySpacedInsideTheBox) {
  Box3 b;
  b.extend(Vec3(0, 0, 0));
  b.extend(Vec3(3, 6, 9));
  const auto planes = axis_planes(b, {2, 3, 0});
  ASSERT_EQ(planes.size(), 5u);
  EXPECT_EQ(planes[0].normal, Vec3::UnitX());
  EXPECT_DOUBLE_EQ(planes[0].offset, 1.0);
  EXPECT_DOUBLE_EQ(planes[1].offset, 2.0);
  EXPECT_EQ(planes[2].normal, Vec3::UnitY());
  EXPECT_DOUBLE_EQ(planes[2].offset, 1.5);
  EXPECT_DOUBLE_EQ(planes[4].offset, 4.5);
}

TEST(FormatsSlicer, RandomPlanesAreDeterministicBySeedAndPassThroughTheBox) {
  Box3 b;
  b.extend(Vec3(-1, -2, -3));
  b.extend(Vec3(1, 2, 3));
  const auto a = random_planes(b, 20, 7), c = random_planes(b, 20, 7), d = random_planes(b, 20, 8);
  ASSERT_EQ(a.size(), 20u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].normal, c[i].normal);
    EXPECT_EQ(a[i].offset, c[i].offset);
    EXPECT_NEAR(a[i].normal.norm(), 1.0, 1e-15);
    // The plane meets the box: box corners on both sides.
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (int k = 0; k < 8; ++k) {
      const Vec3 q((k & 1) ? 1 : -1, (k & 2) ? 2 : -2, (k & 4) ? 3 : -3);
      lo = std::min(lo, a[i].signed_distance(q));
      hi = std::max(hi, a[i].signed_distance(q));
    }
    EXPECT_LT(lo, 0);
    EXPECT_GT(hi, 0);
  }
  EXPECT_NE(a[0].normal, d[0].normal);
}

TEST(FormatsSlicer, Sphere966AxisSlicesAreClosedSimpleAndOnTheSurface) {
  auto mesh = read_mesh(cgal_mesh("sphere966.off"));
  if (!mesh) GTEST_SKIP() << mesh.message();
  std::vector<std::string> w;
  auto s = slice_mesh(*mesh, axis_planes(bounding_box(mesh->vertices), {3, 3, 3}), {}, &w);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(s->planes.size(), 9u);
  EXPECT_EQ(s->curves.size(), 9u);  // one loop per plane on a sphere
  check_slices(*mesh, *s);
}

TEST(FormatsSlicer, DoubleTorusSlicesIncludeNestedLoopsAndMeetOnSharedLines) {
  auto mesh = read_mesh(cgal_mesh("double-torus-example.off"));
  if (!mesh) GTEST_SKIP() << mesh.message();
  const Box3 box = bounding_box(mesh->vertices);
  auto s = slice_mesh(*mesh, axis_planes(box, {2, 2, 3}));
  ASSERT_TRUE(s) << s.message();
  check_slices(*mesh, *s);
  EXPECT_GT(s->curves.size(), s->planes.size());  // holes: some plane has several loops
  // Stroke rule 4: a point of a curve on plane i that lies on plane j is matched by a point of
  // a curve on plane j.
  const double diag = box.diagonal();
  int shared = 0;
  for (const auto& a : s->curves)
    for (const auto& q : a.points)
      for (std::size_t j = 0; j < s->planes.size(); ++j) {
        if (static_cast<int>(j) == a.plane || std::abs(s->planes[j].signed_distance(q)) > 1e-12 * diag) continue;
        double best = HUGE_VAL;
        for (const auto& b : s->curves)
          if (b.plane == static_cast<int>(j))
            for (const auto& r : b.points) best = std::min(best, (r - q).norm());
        EXPECT_LE(best, 1e-9 * diag);
        ++shared;
      }
  EXPECT_GT(shared, 10);
}

TEST(FormatsSlicer, RandomObliquePlanesOnDoubleTorusAreDeterministic) {
  auto mesh = read_mesh(cgal_mesh("double-torus-example.off"));
  if (!mesh) GTEST_SKIP() << mesh.message();
  const auto planes = random_planes(bounding_box(mesh->vertices), 5, 42);
  auto a = slice_mesh(*mesh, planes), b = slice_mesh(*mesh, planes);
  ASSERT_TRUE(a) << a.message();
  ASSERT_TRUE(b);
  check_slices(*mesh, *a);
  ASSERT_EQ(a->curves.size(), b->curves.size());
  for (std::size_t c = 0; c < a->curves.size(); ++c) EXPECT_EQ(a->curves[c].points, b->curves[c].points);
}

TEST(FormatsSlicer, TranslatingMeshAndPlanesTranslatesTheCurves) {
  auto mesh = read_mesh(cgal_mesh("sphere966.off"));
  if (!mesh) GTEST_SKIP() << mesh.message();
  const auto planes = axis_planes(bounding_box(mesh->vertices), {2, 1, 2});
  const Vec3 shift(10.5, -3.25, 7.0);
  TriMesh moved = *mesh;
  for (auto& v : moved.vertices) v += shift;
  auto moved_planes = planes;
  for (auto& p : moved_planes) p.offset += p.normal.dot(shift);
  auto a = slice_mesh(*mesh, planes), b = slice_mesh(moved, moved_planes);
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->curves.size(), b->curves.size());
  const double diag = bounding_box(mesh->vertices).diagonal();
  for (std::size_t c = 0; c < a->curves.size(); ++c) {
    ASSERT_EQ(a->curves[c].points.size(), b->curves[c].points.size());
    for (std::size_t k = 0; k < a->curves[c].points.size(); ++k)
      EXPECT_LE((a->curves[c].points[k] + shift - b->curves[c].points[k]).norm(), 1e-9 * diag);
  }
}

TEST(FormatsSlicer, OpenOrEmptyMeshesAreRefused) {
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  Plane p{Vec3(0, 0, 1), 0.25};
  auto ok = slice_mesh(tet, {p});
  ASSERT_TRUE(ok) << ok.message();
  ASSERT_EQ(ok->curves.size(), 1u);
  TriMesh open = tet;
  open.faces.pop_back();
  auto r = slice_mesh(open, {p});
  ASSERT_FALSE(r);
  EXPECT_NE(r.message().find("not closed"), std::string::npos);
  EXPECT_FALSE(slice_mesh(TriMesh{}, {p}));
}

TEST(FormatsSlicer, SimplicityCheckFindsCrossingsTouchingAndFolds) {
  const std::vector<Vec2> square = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  const std::vector<Vec2> bowtie = {Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)};
  const std::vector<Vec2> inner = {Vec2(0.25, 0.25), Vec2(0.75, 0.25), Vec2(0.75, 0.75)};
  const std::vector<Vec2> touching = {Vec2(1, 0.5), Vec2(2, 0), Vec2(2, 1)};
  const std::vector<Vec2> fold = {Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(1, 1)};
  EXPECT_TRUE(polygons_are_simple({square, inner}));
  EXPECT_FALSE(polygons_are_simple({bowtie}));
  std::vector<int> bad;
  EXPECT_FALSE(polygons_are_simple({square, inner, touching}, &bad));
  EXPECT_EQ(bad, (std::vector<int>{0, 2}));
  EXPECT_FALSE(polygons_are_simple({fold}));
}

TEST(FormatsSlicer, SliceCommandWritesReadableSectionsOrFailsCleanly) {
  const std::string mesh = cgal_mesh("blobby.off");
  if (!std::filesystem::exists(mesh)) GTEST_SKIP() << "no " << mesh;
  const auto dir = std::filesystem::temp_directory_path() / ("planesketch-formats-slice-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "blobby.contour").string();
  const std::string bin = PLANESKETCH_BINARY;
  ASSERT_EQ(std::system((bin + " slice " + mesh + " -o " + out + " --random-planes 4 --seed 5 2>/dev/null").c_str()), 0);
  auto r = read_sections(out);
  ASSERT_TRUE(r) << r.message();
  EXPECT_GE(r->planes.size(), 2u);
  auto m = read_mesh(mesh);
  ASSERT_TRUE(m);
  EXPECT_LE(max_distance_to_surface(*m, r->all_points()), 1e-6 * bounding_box(m->vertices).diagonal());
  const std::string open = cgal_mesh("cube-ouvert.off");
  const std::string bad = (dir / "open.json").string();
  EXPECT_NE(std::system((bin + " slice " + open + " -o " + bad + " 2>/dev/null").c_str()), 0);
  EXPECT_FALSE(std::filesystem::exists(bad));
  std::filesystem::remove_all(dir);
}
