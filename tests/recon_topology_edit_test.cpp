// Topology editing by sketch (thesis 6.4): join and split on the orthogonal reconstruction's
// primitives, kept across updates, undoable, refused with a reason and no change.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/progressive_reconstructor.h"
#include "tests/recon_synthetic.h"

namespace ps {
namespace {

using ps::testing::no_improve;

// Two circles on z = 0 and z = 1. Overlapping in projection (offset 0.5): one part through the
// body zone between them. Apart (offset 2): two parts.
SectionSet two_circles(double dx) {
  SectionSet s;
  testing::add_circle(s, 2, 0.0, 0.0, 0.0, 0.5);
  testing::add_circle(s, 2, 1.0, dx, 0.0, 0.5);
  return s;
}

void expect_valid(const TriMesh& m, const SectionSet& s) {
  const auto g = check_guarantees(m);
  EXPECT_TRUE(g.valid());
  const double diag = bounding_box(m.vertices).diagonal();
  for (const auto& c : s.curves) EXPECT_LT(max_distance_to_surface(m, c.points), 1e-6 * diag);
}

int components(const TriMesh& m) { return mesh_topology(m).components; }

TEST(ReconTopologyEdit, SplitSeparatesTwoOverlappingFrusta) {
  const SectionSet s = two_circles(0.5);
  ProgressiveReconstructor r(no_improve());
  auto joined = r.update(s);
  ASSERT_TRUE(joined) << joined.message();
  ASSERT_EQ(components(*joined), 1);
  // A stroke across the part, half way up.
  auto split = r.split({Vec3(-1.0, 0.0, 0.5), Vec3(0.25, 0.05, 0.5), Vec3(1.5, 0.0, 0.5)});
  ASSERT_TRUE(split) << split.message();
  EXPECT_EQ(components(*split), 2);
  expect_valid(*split, s);
  EXPECT_EQ(r.edits().size(), 1u);
  // Both parts keep their section; the gap is in the middle of the zone.
  EXPECT_LT(mesh_topology(*split).signed_volume, mesh_topology(*joined).signed_volume);
}

TEST(ReconTopologyEdit, SplitShrinksTheContinuationInTheNeighbourZone) {
  // The plane x = 0.25 carries a section far above (z = 3) and cuts both circles: their prisms
  // in the body zone z in [0, 1] come in two halves whose walls meet in x = 0.25, where that
  // zone face has no section. Both halves must shrink together or the stitched surface opens.
  SectionSet s = two_circles(0.5);
  testing::add_circle(s, 0, 0.25, 0.0, 3.0, 0.3);
  ProgressiveReconstructor r(no_improve());
  auto before = r.update(s);
  ASSERT_TRUE(before) << before.message();
  const int parts = components(*before);
  auto split = r.split({Vec3(-1.0, 0.0, 0.5), Vec3(1.5, 0.0, 0.5)});
  ASSERT_TRUE(split) << split.message();
  expect_valid(*split, s);
  EXPECT_EQ(components(*split), parts + 1);
}

TEST(ReconTopologyEdit, JoinConnectsTwoSeparateParts) {
  const SectionSet s = two_circles(2.0);
  ProgressiveReconstructor r(no_improve());
  auto apart = r.update(s);
  ASSERT_TRUE(apart) << apart.message();
  ASSERT_EQ(components(*apart), 2);
  auto joined = r.join({Vec3(0.0, 0.0, 0.2), Vec3(1.0, 0.0, 0.5), Vec3(2.0, 0.0, 0.8)});
  ASSERT_TRUE(joined) << joined.message();
  EXPECT_EQ(components(*joined), 1);
  EXPECT_EQ(mesh_topology(*joined).genus, 0);
  expect_valid(*joined, s);

  // Undo gives back the mesh before the join, bit for bit.
  auto undone = r.undo_edit();
  ASSERT_TRUE(undone) << undone.message();
  EXPECT_TRUE(undone->vertices == apart->vertices);
  EXPECT_TRUE(undone->faces == apart->faces);
  EXPECT_TRUE(r.edits().empty());
  EXPECT_FALSE(r.undo_edit());
}

// Two parts in different zones: circles on z = 0 and z = 1 at x = 0 and at x = 3, and planes
// x = c carrying a small section off to the side and above (y = 3, z = 2.5; a part of its own),
// which cut the slab between the parts into zones whose shared faces hold no section there (one
// cut: neighbouring zones; two: an empty zone between them).
// Parts standing on two planes z = 0 and z = 1: a circle on each at every x of `xs`.
SectionSet stacked_parts(std::initializer_list<double> xs) {
  SectionSet s;
  for (double z : {0.0, 1.0}) {
    Plane pl;
    pl.normal = Vec3::UnitZ();
    pl.offset = z;
    s.planes.push_back(pl);
    for (double x : xs)
      s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1,
                                      testing::ellipse(2, z, x, 0.0, 0.5, 0.5, 40)});
  }
  return s;
}

TEST(ReconTopologyEdit, JoinCarriesTheFrustumAcrossZones) {
  for (const auto& cuts : {std::vector<double>{1.5}, std::vector<double>{1.0, 2.0}}) {
    SectionSet s = stacked_parts({0.0, 3.0});
    for (double c : cuts) testing::add_circle(s, 0, c, 3.0, 2.5, 0.3);
    ProgressiveReconstructor r(no_improve());
    auto apart = r.update(s);
    ASSERT_TRUE(apart) << apart.message();
    const int before = components(*apart);
    ASSERT_EQ(before, 3);  // the two parts and the side sections (two of them are one part)
    ReconstructReport rep;
    auto joined = r.join({Vec3(0.0, 0.0, 0.5), Vec3(3.0, 0.0, 0.5)}, &rep);
    ASSERT_TRUE(joined) << joined.message();
    EXPECT_EQ(components(*joined), before - 1) << cuts.size() << " cut(s)";
    expect_valid(*joined, s);
    // The tube between the parts passes through the zones between them: the surface crosses the
    // plane x = 1.25 between the parts, at their height (and did not before).
    auto crossings = [](const TriMesh& m) {
      int count = 0;
      for (const auto& f : m.faces) {
        double lo = 1e300, hi = -1e300;
        bool near = true;
        for (int i : f) {
          const Vec3& v = m.vertices[static_cast<std::size_t>(i)];
          lo = std::min(lo, v.x());
          hi = std::max(hi, v.x());
          near = near && std::abs(v.y()) < 1.0 && v.z() >= 0.0 && v.z() <= 1.0;
        }
        count += near && lo < 1.25 && hi > 1.25;
      }
      return count;
    };
    EXPECT_EQ(crossings(*apart), 0);
    EXPECT_GT(crossings(*joined), 0);
    // Only the zones of the chain are recomputed (the first part's, those crossed, the second's).
    EXPECT_LE(rep.zones_recomputed, static_cast<int>(cuts.size()) + 2);
    // Reversed stroke: the second part is carried to the first.
    ProgressiveReconstructor other(no_improve());
    ASSERT_TRUE(other.update(s));
    auto reversed = other.join({Vec3(3.0, 0.0, 0.5), Vec3(0.0, 0.0, 0.5)});
    ASSERT_TRUE(reversed) << reversed.message();
    EXPECT_EQ(components(*reversed), before - 1);
    expect_valid(*reversed, s);
    // Undo gives back the parts, bit for bit.
    auto undone = r.undo_edit();
    ASSERT_TRUE(undone) << undone.message();
    EXPECT_TRUE(undone->vertices == apart->vertices);
    EXPECT_TRUE(undone->faces == apart->faces);
  }
}

TEST(ReconTopologyEdit, JoinAcrossAFaceHoldingASectionIsRefusedAndChangesNothing) {
  // The plane x = 1.5 between the parts holds a section in their slab (off to the side, y = 3):
  // the frustum cannot be carried through that face.
  SectionSet s = stacked_parts({0.0, 3.0});
  testing::add_circle(s, 0, 1.5, 3.0, 0.5, 0.3);
  ProgressiveReconstructor r(no_improve());
  auto apart = r.update(s);
  ASSERT_TRUE(apart) << apart.message();
  ASSERT_EQ(components(*apart), 3);
  const auto e = r.join({Vec3(0.0, 0.0, 0.5), Vec3(3.0, 0.0, 0.5)});
  ASSERT_FALSE(e);
  EXPECT_NE(e.message().find("holds a section"), std::string::npos) << e.message();
  EXPECT_TRUE(r.edits().empty());
  EXPECT_TRUE(r.mesh().vertices == apart->vertices);
}

TEST(ReconTopologyEdit, JoinInEitherStrokeDirectionConnects) {
  // Reversed: the prism moved is the one the stroke starts on.
  const SectionSet s = two_circles(2.0);
  ProgressiveReconstructor r(no_improve());
  ASSERT_TRUE(r.update(s));
  auto reversed = r.join({Vec3(2.0, 0.0, 0.8), Vec3(0.0, 0.0, 0.2)});
  ASSERT_TRUE(reversed) << reversed.message();
  EXPECT_EQ(mesh_topology(*reversed).components, 1);
  EXPECT_TRUE(check_guarantees(*reversed).valid());
}

TEST(ReconTopologyEdit, EditIsKeptWhenASectionIsAddedElsewhere) {
  SectionSet s = two_circles(2.0);
  ProgressiveReconstructor r(no_improve());
  ASSERT_TRUE(r.update(s));
  ASSERT_TRUE(r.join({Vec3(0.0, 0.0, 0.2), Vec3(2.0, 0.0, 0.8)}));
  // A separate blob on the plane x = 3.5, off to the side (y = 3): the new plane cuts the joined
  // parts' zone in two, but not through the parts, whose edit must still apply.
  testing::add_circle(s, 0, 3.5, 3.0, 0.5, 0.3);
  ReconstructReport rep;
  auto more = r.update(s, &rep);
  ASSERT_TRUE(more) << more.message();
  EXPECT_EQ(components(*more), 2);  // the joined part and the new blob
  for (const auto& w : rep.warnings) EXPECT_EQ(w.find("no longer applies"), std::string::npos) << w;
  EXPECT_EQ(r.edits().size(), 1u);
}

TEST(ReconTopologyEdit, RefusalsNameTheReasonAndChangeNothing) {
  const SectionSet s = two_circles(2.0);
  ProgressiveReconstructor r(no_improve());
  auto before = r.update(s);
  ASSERT_TRUE(before);
  const auto same_part = r.join({Vec3(0.0, 0.0, 0.2), Vec3(0.1, 0.0, 0.3)});
  ASSERT_FALSE(same_part);
  EXPECT_NE(same_part.message().find("same part"), std::string::npos) << same_part.message();
  const auto single = r.split({Vec3(-1.0, 0.0, 0.5), Vec3(1.0, 0.0, 0.5)});
  ASSERT_FALSE(single);
  EXPECT_NE(single.message().find("single frustum"), std::string::npos) << single.message();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto bad = r.join({Vec3(nan, 0.0, 0.0), Vec3(2.0, 0.0, 0.8)});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("NaN"), std::string::npos) << bad.message();
  EXPECT_FALSE(r.split({Vec3(0.0, 0.0, 0.5)}));
  EXPECT_TRUE(r.edits().empty());
  EXPECT_TRUE(r.mesh().vertices == before->vertices);
}

// Planes in two directions 45 degrees apart (no frame makes them axis planes): chapter 6, where
// topology edits are not available.
TEST(ReconTopologyEdit, ObliqueSectionsRefuseEdits) {
  SectionSet s;
  auto add = [&](const Vec3& normal, const Vec3& centre) {
    Plane tilted;
    tilted.normal = normal.normalized();
    tilted.offset = tilted.normal.dot(centre);
    Vec3 u, v;
    tilted.basis(u, v);
    std::vector<Vec3> circle;
    for (int i = 0; i < 40; ++i) {
      const double a = 2 * M_PI * i / 40;
      circle.push_back(centre + 0.5 * (std::cos(a) * u + std::sin(a) * v));
    }
    s.planes.push_back(tilted);
    s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1, circle});
  };
  add(Vec3(1.0, 0.0, 1.0), Vec3::Zero());
  add(Vec3(1.0, 0.0, 0.0), Vec3(3.0, 0.0, 0.0));
  ProgressiveReconstructor r(no_improve());
  ASSERT_TRUE(r.update(s));
  const auto e = r.split({Vec3(-1.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0)});
  ASSERT_FALSE(e);
  EXPECT_NE(e.message().find("three orthogonal directions only"), std::string::npos) << e.message();
}

// A tilted stack runs on the grid in its own frame (aligned_frame.h), so it takes edits; the
// strokes are in world coordinates. The same split as on the axis-aligned pair, turned.
TEST(ReconTopologyEdit, TiltedStackTakesEditsInWorldCoordinates) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.8, Vec3(1.0, 2.0, -1.0).normalized()).toRotationMatrix();
  SectionSet s = two_circles(0.5);
  for (auto& p : s.planes) p.normal = turn * p.normal;
  for (auto& c : s.curves)
    for (auto& p : c.points) p = turn * p;
  ProgressiveReconstructor r(no_improve());
  ReconstructReport rep;
  auto joined = r.update(s, &rep);
  ASSERT_TRUE(joined) << joined.message();
  EXPECT_TRUE(rep.rotated_frame);
  ASSERT_EQ(components(*joined), 1);
  std::vector<Vec3> stroke = {Vec3(-1.0, 0.0, 0.5), Vec3(0.25, 0.05, 0.5), Vec3(1.5, 0.0, 0.5)};
  for (auto& p : stroke) p = turn * p;
  auto split = r.split(stroke, &rep);
  ASSERT_TRUE(split) << split.message();
  EXPECT_EQ(components(*split), 2);
  expect_valid(*split, s);
  // Undo gives back the joined solid, bit for bit.
  auto undone = r.undo_edit();
  ASSERT_TRUE(undone) << undone.message();
  EXPECT_EQ(undone->vertices, joined->vertices);
}

TEST(ReconTopologyEdit, SplitDoesNotDependOnStrokeDirection) {
  const SectionSet s = two_circles(0.5);
  ProgressiveReconstructor a(no_improve()), b(no_improve());
  ASSERT_TRUE(a.update(s));
  ASSERT_TRUE(b.update(s));
  auto fa = a.split({Vec3(-1.0, 0.0, 0.5), Vec3(1.5, 0.0, 0.5)});
  auto fb = b.split({Vec3(1.5, 0.0, 0.5), Vec3(-1.0, 0.0, 0.5)});
  ASSERT_TRUE(fa && fb);
  EXPECT_TRUE(fa->vertices == fb->vertices);
  EXPECT_TRUE(fa->faces == fb->faces);
}

}  // namespace
}  // namespace ps

namespace ps {
namespace {

TEST(TopologyEditFile, RoundTripsAndNamesWhatIsWrong) {
  const std::vector<TopologyEdit> edits = {{TopologyEditKind::kJoin, {Vec3(0.1, 0.2, 0.3), Vec3(1.0 / 3.0, 2, 3)}},
                                           {TopologyEditKind::kSplit, {Vec3(-1, 0, 0.5), Vec3(1.5, 0, 0.5)}}};
  auto back = parse_topology_edits(format_topology_edits(edits));
  ASSERT_TRUE(back) << back.message();
  ASSERT_EQ(back->size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ((*back)[i].kind, edits[i].kind);
    EXPECT_TRUE((*back)[i].stroke == edits[i].stroke);
  }
  const std::pair<const char*, const char*> bad[] = {
      {"", "not JSON"},
      {"[]", "array \"edits\""},
      {R"({"edits": [{"kind": "fold", "stroke": []}]})", "edits[0].kind"},
      {R"({"edits": [{"kind": "join"}]})", "edits[0]: expected an array \"stroke\""},
      {R"({"edits": [{"kind": "join", "stroke": [[0, 0]]}]})", "edits[0].stroke[0]"},
      {R"({"edits": [{"kind": "split", "stroke": [[0, 0, 0]]}]})", "at least 2 points"},
      {R"({"edits": [{"kind": "split", "stroke": [[0, 0, 0], [1e999, 0, 0]]}]})", "number overflow"},
  };
  for (const auto& [text, expected] : bad) {
    auto r = parse_topology_edits(text);
    ASSERT_FALSE(r) << text;
    EXPECT_NE(r.message().find(expected), std::string::npos) << text << " -> " << r.message();
  }
}

}  // namespace
}  // namespace ps
