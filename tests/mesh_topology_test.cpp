#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"

using namespace ps;

namespace {
TriMesh tetrahedron() {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}
std::string cgal_mesh(const char* name) { return std::string(PLANESKETCH_CGAL_DATA) + "/" + name; }
}  // namespace

TEST(MeshTopology, TetrahedronIsClosedManifoldOutwardGenusZero) {
  const auto t = mesh_topology(tetrahedron());
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.manifold());
  EXPECT_TRUE(t.consistently_oriented);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, 0);
  EXPECT_NEAR(t.signed_volume, 1.0 / 6.0, 1e-15);
  EXPECT_TRUE(t.problem.empty()) << t.problem;
}

TEST(MeshTopology, FlippedFaceIsInconsistent) {
  auto m = tetrahedron();
  std::swap(m.faces[0][1], m.faces[0][2]);
  const auto t = mesh_topology(m);
  EXPECT_FALSE(t.consistently_oriented);
  EXPECT_NE(t.problem.find("orientation"), std::string::npos);
}

TEST(MeshTopology, RemovedFaceLeavesHoles) {
  auto m = tetrahedron();
  m.faces.pop_back();
  const auto t = mesh_topology(m);
  EXPECT_FALSE(t.closed);
  EXPECT_EQ(t.boundary_edges, 3);
}

TEST(MeshTopology, TwoTetrahedraSharingOneVertexAreNotVertexManifold) {
  auto m = tetrahedron();
  auto n = tetrahedron();
  for (auto& v : n.vertices) v = -v;
  const int off = 4;
  for (auto f : n.faces) {
    for (auto& i : f) i = i == 0 ? 0 : i + off - 1;
    m.faces.push_back(f);
  }
  for (std::size_t i = 1; i < n.vertices.size(); ++i) m.vertices.push_back(n.vertices[i]);
  const auto t = mesh_topology(m);
  EXPECT_TRUE(t.edge_manifold);
  EXPECT_FALSE(t.vertex_manifold);
}

TEST(MeshIo, CgalDataMeshesHaveTheirKnownGenus) {
  struct Case { const char* name; int genus; };
  for (const Case c : {Case{"sphere966.off", 0}, Case{"double-torus-example.off", 2}}) {
    const std::string path = cgal_mesh(c.name);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "CGAL data not extracted: " << path;
    auto r = read_mesh(path);
    ASSERT_TRUE(r) << r.message();
    const auto g = check_guarantees(*r);
    EXPECT_TRUE(g.valid()) << c.name << ": " << g.problem();
    EXPECT_EQ(g.topology.genus, c.genus) << c.name;
  }
}

TEST(MeshIo, RoundTripEveryFormat) {
  const auto m = tetrahedron();
  const auto dir = std::filesystem::temp_directory_path() / "planesketch_mesh_io_test";
  std::filesystem::create_directories(dir);
  for (const char* ext : {".obj", ".off", ".ply", ".stl"}) {
    const std::string path = (dir / (std::string("tet") + ext)).string();
    ASSERT_TRUE(write_mesh(path, m)) << path;
    auto r = read_mesh(path);
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->faces.size(), 4u) << ext;
    EXPECT_NEAR(signed_volume(*r), 1.0 / 6.0, 1e-12) << ext;
  }
}

TEST(MeshIo, BadInputGivesClearMessages) {
  const auto dir = std::filesystem::temp_directory_path() / "planesketch_mesh_io_bad";
  std::filesystem::create_directories(dir);
  EXPECT_NE(read_mesh((dir / "missing.off").string()).message().find("no such file"), std::string::npos);
  EXPECT_NE(read_mesh(dir.string()).message().find("directory"), std::string::npos);
  const std::string empty = (dir / "empty.off").string();
  { std::ofstream(empty).flush(); }
  EXPECT_NE(read_mesh(empty).message().find("empty"), std::string::npos);
  const std::string nan = (dir / "nan.off").string();
  { std::ofstream f(nan); f << "OFF\n3 1 0\n0 0 0\nnan 1 0\n0 1 0\n3 0 1 2\n"; }
  auto r = read_mesh(nan);
  EXPECT_FALSE(r);
  EXPECT_FALSE(r.message().empty());
  EXPECT_NE(read_mesh((dir / "x.txt").string()).message().find(""), std::string::npos);
  EXPECT_FALSE(write_mesh((dir / "x.xyz").string(), tetrahedron()));
}
