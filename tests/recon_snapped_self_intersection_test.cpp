// The self-intersection test of snapped frusta (modeling/snapped_self_intersection.h) against
// CGAL's Polygon_mesh_processing::does_self_intersect, which it replaces in the zone unions:
// the same verdict on every frustum of a real contour set (SideBishop, oblique planes) under all
// three frustum margins, and of the dumped zone of stress seed 9, and
// on the same frusta broken on purpose (a top corner pushed through the bottom cap, a bottom
// corner pushed across its own cap), so both verdicts occur.
#include "modeling/snapped_self_intersection.h"

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "modeling/contour_io.h"
#include "modeling/frustum_builder.h"
#include "modeling/polyhedral_partition.h"
#include "modeling/section_validate.h"
#include "modeling/zone_partition.h"
#include "tests/zone_fixture.h"

namespace ps {
namespace {

struct Tally {
  int frusta = 0, intersecting = 0, disagreements = 0;
};

void compare(const SnappedSolid& s, const std::vector<Plane>& planes, Tally& t, const std::string& what) {
  exact::SurfaceMesh sm = exact::snapped_surface_mesh(s, planes);
  if (!exact::unusable_operand(sm).empty()) return;  // refused before either test runs
  for (auto v : sm.vertices()) CGAL::exact(sm.point(v));  // as union_snapped_solids does
  const bool cgal = CGAL::Polygon_mesh_processing::does_self_intersect(sm);
  const bool ours = exact::snapped_self_intersects(sm, s.tags, planes);
  ++t.frusta;
  t.intersecting += cgal ? 1 : 0;
  if (cgal != ours) {
    ++t.disagreements;
    ADD_FAILURE() << what << ": CGAL says " << cgal << ", ours " << ours;
  }
}

// Every frustum as built, then with its last top corner moved onto the bottom cap's far side
// (through the cap) and with its first bottom corner moved to the middle of its cap.
void compare_all(const std::vector<ZoneFrusta>& zones, const std::vector<Plane>& planes, Tally& t,
                 const std::string& name) {
  for (std::size_t z = 0; z < zones.size(); ++z)
    for (std::size_t f = 0; f < zones[z].solids.size(); ++f) {
      const SnappedSolid& s = zones[z].solids[f];
      const std::string what = name + " zone " + std::to_string(z) + " frustum " + std::to_string(f);
      compare(s, planes, t, what);
      const std::size_t n = s.mesh.vertices.size();
      if (n < 8 || n % 2 != 0) continue;
      const std::size_t half = n / 2;
      Vec3 bottom_centre = Vec3::Zero(), top_centre = Vec3::Zero();
      for (std::size_t v = 0; v < half; ++v) bottom_centre += s.mesh.vertices[v] / static_cast<double>(half);
      for (std::size_t v = half; v < n; ++v) top_centre += s.mesh.vertices[v] / static_cast<double>(half);
      SnappedSolid through = s;
      through.mesh.vertices[n - 1] = bottom_centre + 0.5 * (bottom_centre - top_centre);
      through.tags[n - 1] = {-1, -1, -1};
      compare(through, planes, t, what + " (top corner through the bottom)");
      SnappedSolid folded = s;
      folded.mesh.vertices[0] = bottom_centre + 0.9 * (bottom_centre - s.mesh.vertices[half / 2]);
      compare(folded, planes, t, what + " (bottom corner across its cap)");
    }
}

TEST(SnappedSelfIntersection, SameVerdictAsCgalOnRealFrusta) {
  const std::string root = std::string(PLANESKETCH_SHARED_DIR) + "/data/csl/";
  Tally t;
  int sets = 0;
  for (const char* file : {"without_ref/SideBishop.csl"}) {
    const std::string path = root + file;
    if (!std::filesystem::exists(path)) continue;
    std::vector<std::string> warnings;
    auto sections = read_sections(path, &warnings);
    ASSERT_TRUE(sections) << sections.message();
    auto valid = validate_sections(*sections);
    ASSERT_TRUE(valid) << valid.message();
    const Box3 box = default_reconstruction_box(valid->sections.all_points());
    auto part = partition_polyhedral(*valid, box);
    ASSERT_TRUE(part) << part.message();
    FrustumOptions wide, narrow;
    wide.face_margin = 0.045;
    wide.height_margin = 0.12;
    narrow.face_margin = 0.009;
    narrow.height_margin = 0.03;
    for (const FrustumOptions& o : {FrustumOptions{}, wide, narrow}) {
      auto frusta = build_frusta(*part, o);
      ASSERT_TRUE(frusta) << frusta.message();
      compare_all(*frusta, part->planes, t, file);
    }
    ++sets;
  }
  // The dumped zone of stress seed 9 (always present).
  const auto seed9 = testing::read_seed9_frusta_offset();
  compare_all({ZoneFrusta{seed9}}, testing::read_seed9_planes(), t, "seed 9");
  std::printf("%d contour sets, %d frusta compared, %d intersecting\n", sets, t.frusta, t.intersecting);
  EXPECT_EQ(t.disagreements, 0);
  EXPECT_GT(t.intersecting, 0);
  EXPECT_LT(t.intersecting, t.frusta);
}

}  // namespace
}  // namespace ps
