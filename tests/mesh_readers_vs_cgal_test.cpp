// The hand-written OFF and PLY readers (modeling/off_reader.h, modeling/ply_reader.h) against
// CGAL's readers on every .off and .ply mesh of CGAL's data set (libcgal-demo): the same points,
// bit for bit, and the same polygons. CGAL's readers are kept here only as the reference.
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "modeling/mesh_io.h"

namespace ps {
namespace {

namespace fs = std::filesystem;

TEST(MeshReadersVsCgal, EveryOffAndPlyMeshOfTheDataSetReadsAlike) {
  const fs::path root = fs::path(PLANESKETCH_CGAL_DATA);
  if (!fs::exists(root)) GTEST_SKIP() << "no CGAL data at " << root;
  int files = 0;
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".off" || ext == ".ply") paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  for (const auto& path : paths) {
    SCOPED_TRACE(path.filename().string());
    std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
    std::vector<std::vector<std::size_t>> polygons;
    const bool cgal_ok = CGAL::IO::read_polygon_soup(path.string(), points, polygons, CGAL::parameters::verbose(false));
    auto ours = read_polygon_soup_file(path.string());
    ASSERT_EQ(ours.is_ok(), cgal_ok) << (ours.is_ok() ? "CGAL refused it" : ours.message());
    if (!cgal_ok) continue;
    ++files;
    ASSERT_EQ(ours->points.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto& p = ours->points[i];
      ASSERT_TRUE(p[0] == points[i].x() && p[1] == points[i].y() && p[2] == points[i].z()) << "vertex " << i;
    }
    ASSERT_EQ(ours->polygons, polygons);
  }
  EXPECT_GE(files, 100);
}

}  // namespace
}  // namespace ps
