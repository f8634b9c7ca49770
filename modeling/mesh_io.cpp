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

#include "modeling/off_reader.h"
#include "modeling/ply_reader.h"
#include "modeling/polygon_triangulate.h"

namespace ps {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_mesh_extension(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".obj" || e == ".off" || e == ".ply" || e == ".stl";
}

Result<PolygonSoup> read_polygon_soup_file(const std::string& path) {
  using R = Result<PolygonSoup>;
  const std::string ext = lower_extension(path);
  if (ext == ".off" || ext == ".ply") {
    std::ifstream in(path, std::ios::binary);
    if (!in) return R::error(path + ": cannot be opened for reading");
    std::ostringstream content;
    content << in.rdbuf();
    auto soup = ext == ".off" ? parse_off(content.str()) : parse_ply(content.str());
    if (!soup) return R::error(path + ": cannot parse mesh (" + soup.message() + ")");
    return soup;
  }

  using InPoint = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<InPoint> points;
  PolygonSoup soup;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, soup.polygons, CGAL::parameters::verbose(false));
  } catch (const std::exception& e) {
    return R::error(path + ": cannot parse mesh (" + e.what() + ")");
  }
  if (!ok) return R::error(path + ": cannot parse mesh (malformed " + ext + " file)");
  soup.points.reserve(points.size());
  for (const auto& p : points) soup.points.push_back({p.x(), p.y(), p.z()});
  for (std::size_t f = 0; f < soup.polygons.size(); ++f)
    for (std::size_t v : soup.polygons[f])
      if (v >= points.size())
        return R::error(path + ": face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                        " out of range");
  return soup;
}

Result<TriMesh> read_mesh(const std::string& path, const MeshReadOptions& options) {
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

  auto soup = read_polygon_soup_file(path);
  if (!soup) return Result<TriMesh>::error(soup.message());
  const auto& points = soup->points;
  const auto& polygons = soup->polygons;
  if (polygons.empty()) return Result<TriMesh>::error(path + ": mesh has no faces");

  TriMesh mesh;
  mesh.vertices.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return Result<TriMesh>::error(path + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  mesh.faces.reserve(polygons.size());
  for (std::size_t fi = 0; fi < polygons.size(); ++fi) {
    const auto& poly = polygons[fi];
    if (poly.size() < 3)
      return Result<TriMesh>::error(path + ": face " + std::to_string(fi) + " has fewer than 3 vertices");
    // Every index is in range: read_polygon_soup_file checks it for every format.
    if (poly.size() == 3) {
      mesh.faces.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[1]), static_cast<int>(poly[2])});
      continue;
    }
    if (options.triangles_only)
      return Result<TriMesh>::error(path + ": face " + std::to_string(fi) + " has " + std::to_string(poly.size()) +
                                    " corners; a triangle mesh is needed here");
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
