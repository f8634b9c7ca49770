#pragma once
// The bodies of the fuzz targets, shared by tests/fuzz/*_fuzz.cpp (libFuzzer, clang builds with
// PLANESKETCH_FUZZ=ON) and tests/formats_fuzz_corpus_test.cpp (every build, over the seed corpus
// and deterministic mutations of it). Each check returns an empty string when the input was
// handled correctly, or what went wrong: a reader accepted something that breaks the
// SectionSet invariants, or a written set does not read back the same.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "modeling/contour_io.h"
#include "modeling/mesh_io.h"

namespace ps::fuzz {

// Invariants every successfully read set satisfies (cross_section.h).
inline std::string check_set(const SectionSet& s) {
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    const auto& p = s.planes[i];
    if (!std::isfinite(p.offset) || !p.normal.allFinite() || std::abs(p.normal.norm() - 1.0) > 1e-12)
      return "plane " + std::to_string(i) + " is not a finite unit-normal plane";
  }
  for (std::size_t c = 0; c < s.curves.size(); ++c) {
    const auto& cv = s.curves[c];
    if (cv.plane < 0 || static_cast<std::size_t>(cv.plane) >= s.planes.size()) return "curve plane out of range";
    if (cv.points.size() < 3) return "curve " + std::to_string(c) + " has fewer than 3 points";
    for (const auto& q : cv.points)
      if (!q.allFinite()) return "curve " + std::to_string(c) + " has a non-finite point";
  }
  return {};
}

inline std::vector<const CrossSection*> by_plane(const SectionSet& s) {
  std::vector<const CrossSection*> out;
  for (const auto& c : s.curves) out.push_back(&c);
  std::stable_sort(out.begin(), out.end(), [](const CrossSection* a, const CrossSection* b) { return a->plane < b->plane; });
  return out;
}

// Reads, checks the invariants, writes in all three formats and reads each back: the counts
// must survive and every point must come back within a relative 1e-9 of the diagonal.
inline std::string check_parse(const std::uint8_t* data, std::size_t size, ContourFormat format) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> warnings;
  auto r = parse_sections(text, format, "fuzz-input", &warnings);
  if (!r) {
    if (r.message().empty()) return "error without a message";
    return {};
  }
  if (auto p = check_set(*r); !p.empty()) return p;
  const double diag = bounding_box(r->all_points()).diagonal();
  for (ContourFormat out : {ContourFormat::Json, ContourFormat::Csl, ContourFormat::Ctr2Suf}) {
    const std::string written = out == ContourFormat::Json  ? format_contour_json(*r)
                                : out == ContourFormat::Csl ? format_csl(*r)
                                                            : format_ctr2suf(*r);
    auto back = parse_sections(written, out, "round-trip", nullptr);
    const std::string fmt = contour_format_extension(out);
    if (!back) return "written " + fmt + " does not read back: " + back.message();
    if (back->curves.size() != r->curves.size()) return "round trip through " + fmt + " changed the curve count";
    // CSL and .contour group curves by plane: compare in plane order (stable).
    const auto ra = by_plane(*r), rb = by_plane(*back);
    for (std::size_t c = 0; c < r->curves.size(); ++c) {
      const auto& a = ra[c]->points;
      const auto& b = rb[c]->points;
      if (a.size() != b.size())
        return "round trip through " + fmt + " changed the point count of curve " + std::to_string(c) + " from " +
               std::to_string(a.size()) + " to " + std::to_string(b.size());
      for (std::size_t k = 0; k < a.size(); ++k)
        if ((a[k] - b[k]).norm() > 1e-9 * diag) return "round trip through " + fmt + " moved a point";
    }
  }
  return {};
}

inline std::string check_contour_json(const std::uint8_t* d, std::size_t n) { return check_parse(d, n, ContourFormat::Json); }
inline std::string check_csl(const std::uint8_t* d, std::size_t n) { return check_parse(d, n, ContourFormat::Csl); }
inline std::string check_ctr2suf(const std::uint8_t* d, std::size_t n) { return check_parse(d, n, ContourFormat::Ctr2Suf); }

// Mesh import: the bytes as a file with each extension, through ps::read_mesh.
inline std::string check_mesh_import(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = fs::temp_directory_path() / ("planesketch-fuzz-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directories(dir, ec);
  for (const char* ext : {".obj", ".off", ".ply", ".stl"}) {
    const fs::path file = dir / (std::string("input") + ext);
    {
      std::ofstream out(file, std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    auto r = read_mesh(file.string());
    if (!r) {
      if (r.message().empty()) return std::string("error without a message for ") + ext;
      continue;
    }
    if (r->faces.empty()) return std::string("a mesh without faces was accepted from ") + ext;
    for (const auto& v : r->vertices)
      if (!v.allFinite()) return std::string("a non-finite vertex was accepted from ") + ext;
    for (const auto& f : r->faces)
      for (int i : f)
        if (i < 0 || static_cast<std::size_t>(i) >= r->vertices.size())
          return std::string("a face index out of range was accepted from ") + ext;
  }
  return {};
}

}  // namespace ps::fuzz
