// CGAL translation unit: mesh IO through CGAL::IO polygon soups.
#include "modeling/mesh_io.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "modeling/polygon_triangulate.h"

namespace ps {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// CGAL 5.5's PLY_reader::init dereferences the last element when a "property" line comes
// before any "element" line (segfault found by fuzzing): refuse such headers before CGAL reads.
bool ply_property_before_element(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool element_seen = false;
  for (int n = 0; n < 100000 && std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") break;
    if (keyword == "element") element_seen = true;
    if (keyword == "property" && !element_seen && n >= 2) return true;
  }
  return false;
}

// CGAL 5.5's OFF and PLY readers size their arrays from counts in the file (OFF header and
// per-face corner counts, PLY element counts) before reading the data, so a corrupt count makes
// them allocate and zero gigabytes (found by fuzzing). No count can exceed the file's size in
// bytes: refuse such files before CGAL reads them. Returns the reason, or empty.
std::string implausible_counts(const std::string& path, const std::string& ext) {
  std::error_code ec;
  const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
  if (ec) return {};
  std::ifstream in(path, std::ios::binary);
  std::string line;
  // A count as CGAL's readers take it (`stream >> n`): the integer a token starts with, its
  // trailing characters ignored ("4294967296M" is a face of 4294967296 corners to them; found
  // by fuzzing, 2026-12-06). A value too large for long long counts as implausible.
  auto count_ok = [&](const std::string& tok, long long& v) {
    std::size_t i = tok[0] == '+' || tok[0] == '-' ? 1 : 0;
    if (i >= tok.size() || !std::isdigit(static_cast<unsigned char>(tok[i]))) return false;
    try {
      v = std::stoll(tok);
    } catch (const std::out_of_range&) {
      v = std::numeric_limits<long long>::max();
    }
    return true;
  };
  if (ext == ".ply") {
    for (int n = 0; n < 100000 && std::getline(in, line); ++n) {
      std::istringstream words(line);
      std::string keyword, name, count;
      words >> keyword;
      if (keyword == "end_header") break;
      long long v = 0;
      if (keyword == "element" && (words >> name >> count) && count_ok(count, v) && (v < 0 || v > size))
        return "element " + name + " declares " + count + " items, more than the file's " + std::to_string(size) + " bytes can hold";
    }
    return {};
  }
  if (ext != ".off") return {};
  // ASCII OFF, line by line: header, vertex lines, then face lines starting with a corner count.
  std::vector<std::string> tokens;
  auto next_line = [&]() {
    while (std::getline(in, line)) {
      if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
      std::istringstream words(line);
      tokens.clear();
      for (std::string t; words >> t;) tokens.push_back(t);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  if (!next_line()) return {};
  const std::string& kw = tokens[0];
  if (kw.size() < 3 || kw.compare(kw.size() - 3, 3, "OFF") != 0) return {};
  if (tokens.size() > 1 && tokens[1] == "BINARY") return {};
  std::vector<std::string> counts(tokens.begin() + 1, tokens.end());
  if (counts.empty()) {
    if (!next_line()) return {};
    counts = tokens;
  }
  long long nv = 0, nf = 0;
  if (counts.size() < 2 || !count_ok(counts[0], nv) || !count_ok(counts[1], nf)) return {};
  if (nv < 0 || nf < 0 || nv > size || nf > size)
    return "header declares " + counts[0] + " vertices and " + counts[1] + " faces, more than the file's " +
           std::to_string(size) + " bytes can hold";
  for (long long i = 0; i < nv; ++i)
    if (!next_line()) return {};
  for (long long f = 0; f < nf && next_line(); ++f) {
    long long corners = 0;
    if (count_ok(tokens[0], corners) && (corners < 0 || corners > size))
      return "face " + std::to_string(f) + " declares " + tokens[0] + " corners, more than the file's " +
             std::to_string(size) + " bytes can hold";
  }
  return {};
}

}  // namespace

bool is_mesh_extension(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".obj" || e == ".off" || e == ".ply" || e == ".stl";
}

Result<TriMesh> read_mesh(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return Result<TriMesh>::error(path + ": no such file");
  if (fs::is_directory(path, ec)) return Result<TriMesh>::error(path + ": is a directory, not a mesh file");
  if (!is_mesh_extension(path))
    return Result<TriMesh>::error(path + ": unknown mesh extension (expected .obj, .off, .ply or .stl)");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return Result<TriMesh>::error(path + ": cannot be opened for reading");
    if (probe.peek() == std::ifstream::traits_type::eof())
      return Result<TriMesh>::error(path + ": file is empty");
  }

  if (lower_extension(path) == ".ply" && ply_property_before_element(path))
    return Result<TriMesh>::error(path + ": cannot parse mesh (malformed .ply header: a property before any element)");

  if (const std::string why = implausible_counts(path, lower_extension(path)); !why.empty())
    return Result<TriMesh>::error(path + ": cannot parse mesh (" + why + ")");

  using InPoint = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<InPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch (const std::exception& e) {
    return Result<TriMesh>::error(path + ": cannot parse mesh (" + e.what() + ")");
  }
  if (!ok) return Result<TriMesh>::error(path + ": cannot parse mesh (malformed " + lower_extension(path) + " file)");
  if (polygons.empty()) return Result<TriMesh>::error(path + ": mesh has no faces");

  TriMesh mesh;
  mesh.vertices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      return Result<TriMesh>::error(path + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  mesh.faces.reserve(polygons.size());
  for (std::size_t fi = 0; fi < polygons.size(); ++fi) {
    const auto& poly = polygons[fi];
    if (poly.size() < 3)
      return Result<TriMesh>::error(path + ": face " + std::to_string(fi) + " has fewer than 3 vertices");
    for (std::size_t v : poly)
      if (v >= points.size())
        return Result<TriMesh>::error(path + ": face " + std::to_string(fi) + " references vertex " +
                                      std::to_string(v) + " out of range");
    if (poly.size() == 3) {
      mesh.faces.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[1]), static_cast<int>(poly[2])});
      continue;
    }
    std::vector<Vec3> corners;
    for (std::size_t v : poly) corners.push_back(mesh.vertices[v]);
    for (const auto& t : triangulate_polygon_3d(corners))
      mesh.faces.push_back({static_cast<int>(poly[static_cast<std::size_t>(t[0])]),
                            static_cast<int>(poly[static_cast<std::size_t>(t[1])]),
                            static_cast<int>(poly[static_cast<std::size_t>(t[2])])});
  }
  return mesh;
}

Status write_mesh(const std::string& path, const TriMesh& mesh) {
  namespace fs = std::filesystem;
  if (!is_mesh_extension(path))
    return Status::error(path + ": unknown mesh extension (expected .obj, .off, .ply or .stl)");
  std::error_code ec;
  if (fs::is_directory(path, ec)) return Status::error(path + ": is a directory");
  using OutPoint = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<OutPoint> points;
  points.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces)
    polygons.push_back({static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]),
                        static_cast<std::size_t>(f[2])});

  // Write beside the target with the same extension (CGAL picks the format from it), then
  // rename into place: no partial output on failure.
  const fs::path target(path);
  const fs::path tmp = target.parent_path() /
                       (".tmp-" + target.stem().string() + "-" + std::to_string(::getpid()) + target.extension().string());
  bool ok = false;
  try {
    ok = CGAL::IO::write_polygon_soup(tmp.string(), points, polygons,
                                      CGAL::parameters::stream_precision(17).use_binary_mode(false));
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot write mesh (" + e.what() + ")");
  }
  if (!ok) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot write mesh (is the folder writable?)");
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return Status::error(path + ": cannot move the written mesh into place: " + ec.message());
  }
  return Status::ok();
}

}  // namespace ps
