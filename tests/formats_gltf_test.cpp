// glTF export: parse the .glb back with a minimal reader of our own and check the container,
// alignment, accessors (with min/max) and the data against the mesh.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "modeling/gltf_export.h"
#include "modeling/mesh_io.h"

using namespace ps;
using nlohmann::json;

namespace {

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
float f32(const std::vector<std::uint8_t>& b, std::size_t at) {
  const std::uint32_t bits = u32(b, at);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

struct Glb {
  json doc;
  std::vector<std::uint8_t> bin;
};

// Minimal GLB reader: header, JSON chunk, BIN chunk (glTF 2.0, section 4.4).
Glb parse_glb(const std::vector<std::uint8_t>& b) {
  Glb g;
  EXPECT_GE(b.size(), 28u);
  EXPECT_EQ(u32(b, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(u32(b, 4), 2u);
  EXPECT_EQ(u32(b, 8), b.size());
  const std::uint32_t jlen = u32(b, 12);
  EXPECT_EQ(u32(b, 16), 0x4E4F534Au);
  EXPECT_EQ(jlen % 4, 0u);
  g.doc = json::parse(b.begin() + 20, b.begin() + 20 + jlen);
  const std::size_t at = 20 + jlen;
  const std::uint32_t blen = u32(b, at);
  EXPECT_EQ(u32(b, at + 4), 0x004E4942u);
  EXPECT_EQ(blen % 4, 0u);
  EXPECT_EQ(at + 8 + blen, b.size());
  g.bin.assign(b.begin() + static_cast<std::ptrdiff_t>(at + 8), b.end());
  return g;
}

void check_against(const TriMesh& mesh, const std::vector<std::uint8_t>& bytes) {
  const Glb g = parse_glb(bytes);
  const json& d = g.doc;
  EXPECT_EQ(d["asset"]["version"], "2.0");
  ASSERT_EQ(d["meshes"].size(), 1u);
  ASSERT_EQ(d["nodes"].size(), 1u);
  EXPECT_EQ(d["nodes"][0]["mesh"], 0);
  const json& prim = d["meshes"][0]["primitives"][0];
  EXPECT_EQ(prim["mode"], 4);
  EXPECT_GE(d["buffers"][0]["byteLength"].get<std::size_t>(), 0u);
  EXPECT_LE(d["buffers"][0]["byteLength"].get<std::size_t>(), g.bin.size());
  auto view_of = [&](int accessor) -> std::pair<std::size_t, std::size_t> {
    const json& a = d["accessors"][static_cast<std::size_t>(accessor)];
    const json& v = d["bufferViews"][a["bufferView"].get<std::size_t>()];
    const std::size_t off = v.value("byteOffset", 0u) + a.value("byteOffset", 0u);
    EXPECT_EQ(off % 4, 0u);
    EXPECT_LE(v["byteOffset"].get<std::size_t>() + v["byteLength"].get<std::size_t>(), g.bin.size());
    return {off, a["count"].get<std::size_t>()};
  };
  const int pos = prim["attributes"]["POSITION"], nrm = prim["attributes"]["NORMAL"], idx = prim["indices"];
  const json& pa = d["accessors"][static_cast<std::size_t>(pos)];
  EXPECT_EQ(pa["componentType"], 5126);
  EXPECT_EQ(pa["type"], "VEC3");
  auto [poff, pcount] = view_of(pos);
  ASSERT_EQ(pcount, mesh.vertices.size());
  for (int k = 0; k < 3; ++k) {
    float lo = HUGE_VALF, hi = -HUGE_VALF;
    for (std::size_t i = 0; i < pcount; ++i) {
      const float x = f32(g.bin, poff + 12 * i + 4 * static_cast<std::size_t>(k));
      EXPECT_EQ(x, static_cast<float>(mesh.vertices[i][k]));
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    EXPECT_EQ(pa["min"][static_cast<std::size_t>(k)].get<float>(), lo);
    EXPECT_EQ(pa["max"][static_cast<std::size_t>(k)].get<float>(), hi);
  }
  auto [noff, ncount] = view_of(nrm);
  ASSERT_EQ(ncount, mesh.vertices.size());
  for (std::size_t i = 0; i < ncount; ++i) {
    const Vec3 n(f32(g.bin, noff + 12 * i), f32(g.bin, noff + 12 * i + 4), f32(g.bin, noff + 12 * i + 8));
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
  }
  const json& ia = d["accessors"][static_cast<std::size_t>(idx)];
  EXPECT_EQ(ia["componentType"], 5125);
  EXPECT_EQ(ia["type"], "SCALAR");
  auto [ioff, icount] = view_of(idx);
  ASSERT_EQ(icount, 3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(u32(g.bin, ioff + 4 * (3 * f + k)), static_cast<std::uint32_t>(mesh.faces[f][k]));
}

TriMesh tetrahedron() {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

}  // namespace

TEST(FormatsGltf, TetrahedronGlbReadsBack) {
  auto bytes = encode_glb(tetrahedron());
  ASSERT_TRUE(bytes) << bytes.message();
  check_against(tetrahedron(), *bytes);
}

TEST(FormatsGltf, NormalsPointOutwardOnAClosedMesh) {
  const TriMesh m = tetrahedron();
  const auto n = vertex_normals(m);
  const Vec3 c = (m.vertices[0] + m.vertices[1] + m.vertices[2] + m.vertices[3]) / 4;
  for (std::size_t i = 0; i < n.size(); ++i) EXPECT_GT(n[i].dot(m.vertices[i] - c), 0.0);
}

TEST(FormatsGltf, RealMeshWrittenToAFileReadsBack) {
  auto mesh = read_mesh(std::string(PLANESKETCH_CGAL_DATA) + "/sphere966.off");
  if (!mesh) GTEST_SKIP() << mesh.message();
  const auto path = std::filesystem::temp_directory_path() / "planesketch-formats-gltf-test.glb";
  ASSERT_TRUE(write_glb(path.string(), *mesh));
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  check_against(*mesh, bytes);
  std::filesystem::remove(path);
}

TEST(FormatsGltf, BadMeshesAreRefused) {
  EXPECT_FALSE(encode_glb(TriMesh{}));
  TriMesh m = tetrahedron();
  m.faces[0][1] = 9;
  EXPECT_NE(encode_glb(m).message().find("out of range"), std::string::npos);
  m = tetrahedron();
  m.vertices[2].x() = std::nan("");
  EXPECT_NE(encode_glb(m).message().find("non-finite"), std::string::npos);
  m = tetrahedron();
  m.vertices[2].x() = 1e300;
  EXPECT_NE(encode_glb(m).message().find("32-bit float"), std::string::npos);
}
