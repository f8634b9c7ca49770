// modeling/ply_reader.h: the three encodings, the properties and elements it reads or skips, and
// the files it refuses (each with a message naming what is wrong).
#include "modeling/ply_reader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace ps {
namespace {

PolygonSoup parsed(const std::string& text) {
  auto r = parse_ply(text);
  EXPECT_TRUE(r.is_ok()) << r.message();
  return r.is_ok() ? *r : PolygonSoup{};
}

void expect_refused(const std::string& text, const std::string& expected) {
  auto r = parse_ply(text);
  ASSERT_FALSE(r.is_ok()) << "accepted:\n" << text;
  EXPECT_NE(r.message().find(expected), std::string::npos) << "message: " << r.message();
}

const std::vector<std::array<double, 3>> kPoints = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::vector<std::size_t>> kFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

const std::string kHeader =
    "ply\nformat ascii 1.0\ncomment a tetrahedron\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kBody = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(PlyReader, AsciiTetrahedron) {
  const PolygonSoup s = parsed(kHeader + kBody);
  EXPECT_EQ(s.points, kPoints);
  EXPECT_EQ(s.polygons, kFaces);
}

TEST(PlyReader, OtherPropertiesAndElementsAreSkipped) {
  // Normals, colours, coordinates of other types and in another order, an edge element before
  // the faces, a face colour list after the indices, CRLF line ends, vertex_index.
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nobj_info made by hand\r\nelement vertex 4\r\nproperty uchar red\r\n"
      "property double z\r\nproperty short x\r\nproperty float nx\r\nproperty list uchar float extra\r\n"
      "property int y\r\nelement edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
      "element face 4\r\nproperty list ushort uint vertex_index\r\nproperty list uchar uchar rgb\r\nend_header\r\n"
      "255 0 0 0.5 2 1.5 2.5 0\r\n9 0 1 0 0 0\r\n9 0 0 0 1 7 1\r\n9 1 0 0 0 0\r\n"
      "0 1\r\n"
      "3 0 2 1 3 1 2 3\r\n3 0 1 3 0\r\n3 0 3 2 0\r\n3 1 2 3 1 9\r\n";
  const PolygonSoup s = parsed(text);
  EXPECT_EQ(s.points, kPoints);
  EXPECT_EQ(s.polygons, kFaces);
}

std::string binary(bool big_endian) {
  std::string b =
      std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
      " 1.0\nelement vertex 4\nproperty float x\nproperty double y\nproperty int16 z\n"
      "element face 4\nproperty list uint8 int32 vertex_indices\nend_header\n";
  auto put = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const char*>(p);
    for (std::size_t k = 0; k < n; ++k) b.push_back(c[big_endian ? n - 1 - k : k]);  // this machine is little-endian
  };
  for (const auto& p : kPoints) {
    const float x = static_cast<float>(p[0]);
    const double y = p[1];
    const auto z = static_cast<std::int16_t>(p[2]);
    put(&x, 4), put(&y, 8), put(&z, 2);
  }
  for (const auto& f : kFaces) {
    const std::uint8_t n = 3;
    put(&n, 1);
    for (std::size_t v : f) {
      const auto i = static_cast<std::int32_t>(v);
      put(&i, 4);
    }
  }
  return b;
}

TEST(PlyReader, BinaryBothEndians) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    const PolygonSoup s = parsed(binary(big));
    EXPECT_EQ(s.points, kPoints);
    EXPECT_EQ(s.polygons, kFaces);
  }
}

TEST(PlyReader, RefusesWithAReason) {
  expect_refused("", "not a PLY file");
  expect_refused("off\n", "not a PLY file");
  expect_refused("ply\nelement vertex 0\nend_header\n", "no format line");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 0\n", "no end_header");
  expect_refused("ply\nformat utf8 1.0\nend_header\n", "unknown format 'utf8'");
  expect_refused("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "header line 3: a property before any element");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n", "unknown property type 'real'");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n", "not an integer type");
  expect_refused("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "not a non-negative integer");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n", "more than the file's");
  expect_refused("ply\nformat ascii 1.0\nelemnt vertex 1\nend_header\n", "unknown header keyword 'elemnt'");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                 "the vertex element has no z property");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty list uchar float z\n"
                 "end_header\n0 0 1 0\n",
                 "vertex property z is a list");
  expect_refused("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int corners\nend_header\n3 0 1 2\n",
                 "no vertex_indices list");
  const std::string head = kHeader;
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 -1 2 1\n", "item 0: vertex index -1");
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 4\n", "face 3 references vertex 4, out of range");
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2.5 1\n", "vertex index 2.5");
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n2 0 2\n", "item 0 has 2 corners");
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1", "the body ends or is malformed in element face item 1");
  expect_refused(head + "0 0 0\n1 0 0\n0 one 0\n", "'one' is not a number");
  expect_refused(head + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n4000000000 0 2 1\n", "declares 4000000000 values, more than");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n3 0 0 0\n",
                 "floating-point type");
  // Binary: truncated, and a list count the remaining bytes cannot hold.
  const std::string b = binary(false);
  expect_refused(b.substr(0, b.size() - 3), "face item 3: list vertex_indices declares 3 values, more than the rest");
  expect_refused(b.substr(0, b.size() - 13), "the body ends or is malformed in element face item 3");
  std::string huge = b;
  huge[huge.size() - 13] = static_cast<char>(0xff);  // face 3's corner count: 255
  expect_refused(huge, "face item 3: list vertex_indices declares 255 values, more than the rest");
}

}  // namespace
}  // namespace ps
