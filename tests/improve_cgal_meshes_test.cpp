// Mesh improvement on CGAL's data meshes (smooth, already well shaped, genus 0 to 2) with a
// loop of edges fixed where a horizontal plane cuts them: the result must keep the topology, the
// loop and the shape, and must not make the triangles worse.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "modeling/halfedge_mesh.h"
#include "modeling/mesh_improve.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "tests/improve_fixtures.h"

using namespace ps;

namespace {

struct Case {
  const char* file;
  int genus;
  // Coarse CAD-like meshes (eight.off: 634 faces, sharp rims) are rounded by the smoothing, as
  // the union's creases are: only topology, interpolation and triangle quality are checked.
  bool smooth_and_fine = true;
};

class CgalMesh : public ::testing::TestWithParam<Case> {};

TEST_P(CgalMesh, KeepsTopologyLoopAndShape) {
  const Case c = GetParam();
  const std::string path = std::string(PLANESKETCH_CGAL_DATA) + "/" + c.file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "CGAL data mesh absent: " << path;
  auto read = read_mesh(path);
  ASSERT_TRUE(read.is_ok()) << read.message();
  const TriMesh& in = *read;
  const MeshGuarantees g0 = check_guarantees(in);
  ASSERT_TRUE(g0.valid()) << c.file << ": " << g0.problem();
  ASSERT_EQ(g0.topology.genus, c.genus);

  std::vector<bool> fixed;
  std::vector<std::array<int, 2>> edges;
  const Box3 box = bounding_box(in.vertices);
  ps::testing::fix_level_loop(in, box.center().z(), fixed, edges);
  ASSERT_GE(edges.size(), 3u);

  ImproveReport rep;
  auto r = improve_mesh(in, fixed, edges, {}, &rep);
  ASSERT_TRUE(r.is_ok()) << r.message();
  const TriMesh& out = *r;

  const MeshGuarantees g1 = check_guarantees(out);
  EXPECT_TRUE(g1.valid()) << c.file << ": " << g1.problem();
  EXPECT_EQ(g1.topology.genus, c.genus);
  EXPECT_EQ(g1.topology.components, g0.topology.components);

  for (std::size_t v = 0; v < in.vertices.size(); ++v) {
    if (fixed[v]) {
      ASSERT_EQ(out.vertices[v], in.vertices[v]) << "vertex " << v;
    }
  }
  auto hm = HalfedgeMesh::build(out);
  ASSERT_TRUE(hm.is_ok()) << hm.message();
  for (const auto& e : edges) EXPECT_GE(hm->find_halfedge(e[0], e[1]), 0) << e[0] << "-" << e[1];

  const double diag = box.diagonal();
  const double moved = hausdorff_distance(in, out, 20000);
  const double v0 = signed_volume(in), v1 = signed_volume(out);
  const MeshQuality q0 = mesh_quality(in), q1 = mesh_quality(out);
  std::printf("%s: faces %d -> %d, Hausdorff %.4f diag, volume %+.2f%%, mean min angle %.1f -> %.1f, "
              "min angle %.1f -> %.1f, rms dihedral %.2f -> %.2f, %.1f ms\n",
              c.file, rep.faces_in, rep.faces_out, moved / diag, 100 * (v1 - v0) / v0, q0.mean_min_angle_deg,
              q1.mean_min_angle_deg, q0.min_angle_deg, q1.min_angle_deg, q0.rms_dihedral_deg, q1.rms_dihedral_deg,
              rep.ms);
  EXPECT_GT(q1.mean_min_angle_deg, q0.mean_min_angle_deg - 1.0);
  if (!c.smooth_and_fine) return;
  EXPECT_LT(moved, 0.01 * diag);
  EXPECT_LT(std::abs(v1 - v0), 0.02 * std::abs(v0));
  EXPECT_LT(q1.rms_dihedral_deg, q0.rms_dihedral_deg);
}

INSTANTIATE_TEST_SUITE_P(DataMeshes, CgalMesh,
                         ::testing::Values(Case{"sphere966.off", 0}, Case{"blobby.off", 0}, Case{"knot1.off", 1},
                                           Case{"eight.off", 2, false}),
                         [](const auto& param_info) {
                           std::string n = param_info.param.file;
                           return n.substr(0, n.find('.'));
                         });

// A sphere is a fixed point of the curvature-evening flow: improving a sampled sphere must keep
// every vertex close to the sphere.
TEST(CgalMeshSphere, StaysOnTheSphere) {
  const std::string path = std::string(PLANESKETCH_CGAL_DATA) + "/sphere966.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "CGAL data mesh absent: " << path;
  auto read = read_mesh(path);
  ASSERT_TRUE(read.is_ok()) << read.message();
  const TriMesh& in = *read;
  Vec3 center = Vec3::Zero();
  for (const auto& v : in.vertices) center += v;
  center /= static_cast<double>(in.vertices.size());
  double radius = 0;
  for (const auto& v : in.vertices) radius += (v - center).norm();
  radius /= static_cast<double>(in.vertices.size());
  auto deviation = [&](const TriMesh& m) {
    double worst = 0;
    for (const auto& v : m.vertices) worst = std::max(worst, std::abs((v - center).norm() - radius));
    return worst;
  };
  std::vector<bool> fixed;
  std::vector<std::array<int, 2>> edges;
  ps::testing::fix_level_loop(in, center.z(), fixed, edges);
  auto r = improve_mesh(in, fixed, edges);
  ASSERT_TRUE(r.is_ok()) << r.message();
  std::printf("sphere966: radial deviation %.5f -> %.5f (radius %.4f)\n", deviation(in), deviation(*r), radius);
  EXPECT_LT(deviation(*r), std::max(1.5 * deviation(in), 0.01 * radius));
}

}  // namespace
