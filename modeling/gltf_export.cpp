// glTF 2.0 binary writer (see gltf_export.h for why it is hand-written).
#include "modeling/gltf_export.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <string_view>

#include "modeling/contour_io.h"

namespace ps {
namespace {

// glTF constants (glTF 2.0 specification, 3.6 and 5.x).
constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));  // little-endian
}

void put_f32(std::vector<std::uint8_t>& out, float f) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  put_u32(out, bits);
}

}  // namespace

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(f[2])];
    const Vec3 fn = (b - a).cross(c - a);  // length = twice the area: area weighting
    for (int i : f) n[static_cast<std::size_t>(i)] += fn;
  }
  for (auto& v : n) {
    const double len = v.norm();
    v = len > 0 && std::isfinite(len) ? Vec3(v / len) : Vec3(Vec3::UnitZ());
  }
  return n;
}

Result<std::vector<std::uint8_t>> encode_glb(const TriMesh& mesh) {
  using R = Result<std::vector<std::uint8_t>>;
  if (mesh.vertices.empty() || mesh.faces.empty()) return R::error("glTF export: the mesh is empty");
  const double fmax = static_cast<double>(std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
      return R::error("glTF export: vertex " + std::to_string(i) + " has a non-finite coordinate");
    if (v.cwiseAbs().maxCoeff() > fmax)
      return R::error("glTF export: vertex " + std::to_string(i) + " does not fit a 32-bit float");
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int i : mesh.faces[f])
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size())
        return R::error("glTF export: face " + std::to_string(f) + " references vertex " + std::to_string(i) +
                        " out of range");
  if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max() / 64)
    return R::error("glTF export: the mesh is too large for one glTF buffer");

  // === Binary buffer: positions, normals, indices (each section a multiple of 4 bytes).
  const std::size_t nv = mesh.vertices.size(), nf = mesh.faces.size();
  std::vector<std::uint8_t> bin;
  bin.reserve(nv * 24 + nf * 12);
  float mn[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  float mx[3] = {-mn[0], -mn[1], -mn[2]};
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(v[k]);
      mn[k] = std::min(mn[k], f);
      mx[k] = std::max(mx[k], f);
      put_f32(bin, f);
    }
  const std::size_t normals_offset = bin.size();
  for (const auto& n : vertex_normals(mesh))
    for (int k = 0; k < 3; ++k) put_f32(bin, static_cast<float>(n[k]));
  const std::size_t indices_offset = bin.size();
  for (const auto& f : mesh.faces)
    for (int i : f) put_u32(bin, static_cast<std::uint32_t>(i));

  // === JSON
  using nlohmann::json;
  json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "planesketch"}};
  j["scene"] = 0;
  j["scenes"] = json::array({{{"nodes", {0}}}});
  j["nodes"] = json::array({{{"mesh", 0}}});
  j["meshes"] = json::array(
      {{{"primitives", json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", kTriangles}}})}}});
  j["buffers"] = json::array({{{"byteLength", bin.size()}}});
  j["bufferViews"] = json::array({
      {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", normals_offset}, {"target", kArrayBuffer}},
      {{"buffer", 0}, {"byteOffset", normals_offset}, {"byteLength", indices_offset - normals_offset}, {"target", kArrayBuffer}},
      {{"buffer", 0}, {"byteOffset", indices_offset}, {"byteLength", bin.size() - indices_offset}, {"target", kElementArrayBuffer}},
  });
  j["accessors"] = json::array({
      {{"bufferView", 0}, {"componentType", kFloat}, {"count", nv}, {"type", "VEC3"},
       {"min", {mn[0], mn[1], mn[2]}}, {"max", {mx[0], mx[1], mx[2]}}},
      {{"bufferView", 1}, {"componentType", kFloat}, {"count", nv}, {"type", "VEC3"}},
      {{"bufferView", 2}, {"componentType", kUnsignedInt}, {"count", 3 * nf}, {"type", "SCALAR"}},
  });
  std::string text = j.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);

  // === Container: 12-byte header, JSON chunk, BIN chunk.
  std::vector<std::uint8_t> out;
  const std::size_t total = 12 + 8 + text.size() + 8 + bin.size();
  out.reserve(total);
  put_u32(out, kMagic);
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(total));
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  put_u32(out, kChunkJson);
  out.insert(out.end(), text.begin(), text.end());
  put_u32(out, static_cast<std::uint32_t>(bin.size()));
  put_u32(out, kChunkBin);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

Status write_glb(const std::string& path, const TriMesh& mesh) {
  auto bytes = encode_glb(mesh);
  if (!bytes) return Status::error(path + ": " + bytes.message());
  return write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
}

}  // namespace ps
