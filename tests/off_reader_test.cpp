// modeling/off_reader.h: the OFF variants it reads, the files it refuses (each with a message
// naming what is wrong), and agreement with write_mesh/read_mesh.
#include "modeling/off_reader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "modeling/mesh_io.h"

namespace ps {
namespace {

PolygonSoup parsed(const std::string& text) {
  auto r = parse_off(text);
  EXPECT_TRUE(r.is_ok()) << r.message();
  return r.is_ok() ? *r : PolygonSoup{};
}

// The refusal's message, which must contain `expected`.
void expect_refused(const std::string& text, const std::string& expected) {
  auto r = parse_off(text);
  ASSERT_FALSE(r.is_ok()) << "accepted:\n" << text;
  EXPECT_NE(r.message().find(expected), std::string::npos) << "message: " << r.message();
}

const char* kTetra =
    "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(OffReader, PlainTetrahedron) {
  const PolygonSoup s = parsed(kTetra);
  ASSERT_EQ(s.points.size(), 4u);
  ASSERT_EQ(s.polygons.size(), 4u);
  EXPECT_EQ(s.points[3][2], 1.0);
  EXPECT_EQ(s.polygons[1], (std::vector<std::size_t>{0, 1, 3}));
}

TEST(OffReader, VariantsReadTheSameGeometry) {
  const PolygonSoup plain = parsed(kTetra);
  const std::string variants[] = {
      // counts on the keyword's line, comments, CRLF line ends, blank lines, '+' signs
      "OFF 4 4 6 # tetra\r\n\r\n0 0 0\r\n+1 0 0\r\n0 1.0 0\r\n# a comment\r\n0 0 1e0\r\n3 0 2 1\r\n3 0 1 3\r\n"
      "3 0 3 2\r\n3 1 2 3\r\n",
      // colours per vertex and per face
      "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 255\n"
      "3 0 2 1 1 0 0\n3 0 1 3 0.5 0.5 0.5 1\n3 0 3 2\n3 1 2 3 7\n",
      // normals
      "NOFF\n4 4 6\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1 0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
      // homogeneous coordinates, divided by w
      "4OFF\n4 4 6\n0 0 0 2\n2 0 0 2\n0 3 0 3\n0 0 -1 -1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
      // texture coordinates and colours together, indices written as integral decimals
      "STCOFF\n4 4\n0 0 0 1 1 1 1 0.1 0.2\n1 0 0 1 1 1 1 0 0\n0 1 0 1 1 1 1 0 0\n0 0 1 1 1 1 1 0 0\n"
      "3 0 2 1\n3.0 0 1 3\n3 0 3.0 2\n3 1 2 3\n",
  };
  for (const auto& text : variants) {
    SCOPED_TRACE(text.substr(0, 12));
    const PolygonSoup s = parsed(text);
    ASSERT_EQ(s.points.size(), plain.points.size());
    EXPECT_EQ(s.points, plain.points);
    EXPECT_EQ(s.polygons, plain.polygons);
  }
}

TEST(OffReader, QuadsAndPolygonsKeepTheirCorners) {
  const PolygonSoup s = parsed("OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0\n4 0 1 2 3\n3 3 2 4\n");
  ASSERT_EQ(s.polygons.size(), 2u);
  EXPECT_EQ(s.polygons[0].size(), 4u);
}

TEST(OffReader, BinaryPlainOff) {
  std::string b = "OFF BINARY\n";
  auto i32 = [&](std::int32_t v) {
    const auto u = static_cast<std::uint32_t>(v);
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<char>((u >> s) & 0xffu));
  };
  auto f32 = [&](float f) {
    std::uint32_t u = 0;
    std::memcpy(&u, &f, 4);
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<char>((u >> s) & 0xffu));
  };
  i32(4), i32(4), i32(6);
  const float pts[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& p : pts) f32(p[0]), f32(p[1]), f32(p[2]);
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : faces) {
    i32(3), i32(f[0]), i32(f[1]), i32(f[2]);
    i32(0);  // no colour
  }
  const PolygonSoup plain = parsed(kTetra);
  const PolygonSoup s = parsed(b);
  EXPECT_EQ(s.points, plain.points);
  EXPECT_EQ(s.polygons, plain.polygons);

  // A negative index in binary, and a count the data cannot hold.
  std::string bad = b;
  bad[11 + 12 + 4 * 12 + 4 + 3] = static_cast<char>(0xff);  // low byte of face 0's first index
  for (int k = 0; k < 3; ++k) bad[11 + 12 + 4 * 12 + 4 + static_cast<std::size_t>(k)] = static_cast<char>(0xff);
  expect_refused(bad, "references vertex -1");
  std::string huge = b;
  huge[11] = 0x7f;  // vertex count 0x7f000004
  expect_refused(huge, "more than its");
}

TEST(OffReader, RefusesWithAReason) {
  // The input the mesh_import fuzz target found in CI (2026-12-06): CGAL's scanner converted -1 to
  // std::size_t, undefined behaviour.
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 -1 0 1\n", "vertex index '-1' is negative");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "vertex index '3' is larger than 2");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "'1.5' is not an integer");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1e300\n", "larger than 2");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", "corner count '-3' is negative");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "has 2 corners");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "declares 4 corners but lists 3");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 x 2\n", "'x' is not a number");
  expect_refused("OFF\n-3 1 0\n", "vertex count '-3' is negative");
  expect_refused("OFF\n3 99999999 0\n0 0 0\n", "face count '99999999' is larger than");
  expect_refused("OFF\n3 1 0\n0 0 0\n1 0 0\n", "ends after 2 of 3 vertices");
  expect_refused("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ends after 1 of 2 faces");
  expect_refused("OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: vertex 0 needs 3 coordinates");
  expect_refused("OFF\n3 1 0\n0 0 zero\n", "found 'zero'");
  expect_refused("4OFF\n3 1 0\n0 0 0 0\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "has w = 0");
  expect_refused("OFF\n3\n", "expected the vertex and face counts");
  expect_refused("OFF\n", "ends before the vertex and face counts");
  expect_refused("PLY\n3 1 0\n", "expected the OFF keyword");
  expect_refused("XOFF\n3 1 0\n", "unknown OFF keyword");
  expect_refused("nOFF\n3\n3 1 0\n", "nOFF");
  expect_refused("COFF BINARY\n", "binary COFF is not supported");
  expect_refused("# only a comment\n\n", "no OFF header");
}

TEST(OffReader, WriteThenReadKeepsTheMesh) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("off-reader-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  TriMesh m;
  m.vertices = {Vec3(0.1, -2.5, 3), Vec3(1e-7, 0, 0), Vec3(0, 12345.678, 0), Vec3(0, 0, 1.0 / 3.0)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string path = (dir / "t.off").string();
  ASSERT_TRUE(write_mesh(path, m).is_ok());
  auto back = read_mesh(path);
  ASSERT_TRUE(back.is_ok()) << back.message();
  EXPECT_EQ(back->faces, m.faces);
  ASSERT_EQ(back->vertices.size(), m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) EXPECT_EQ(back->vertices[i], m.vertices[i]);  // 17 digits: exact

  // The file name leads every refusal.
  { std::ofstream(dir / "neg.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 -1 0 1\n"; }
  auto bad = read_mesh((dir / "neg.off").string());
  ASSERT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.message().rfind((dir / "neg.off").string() + ": cannot parse mesh (line 6: face 0: vertex index", 0), 0u)
      << bad.message();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ps
