#pragma once
// Reader for Object File Format (.off) meshes, ASCII and binary.
//
// Written by hand instead of calling CGAL 5.5's File_scanner_OFF because that scanner reads every
// number of a face line as a double and converts it with static_cast<std::size_t>: a negative or
// huge index or corner count ("3 -1 0 1") is undefined behaviour there (UBSan: "-1 is outside
// the range of representable values of type 'unsigned long'", found by the mesh_import fuzz
// target in CI, 2026-12-06), and it sizes its arrays from the header's counts before reading.
// Here every count and index is an integer checked against its range before use.
//
// Accepted (what CGAL's reader and Geomview's documentation accept):
//   [ST][C][N][4]OFF keyword (texture coordinates, colours, normals, homogeneous coordinates),
//   optionally followed by BINARY (plain OFF only); the counts "nv nf [ne]" on the keyword's line
//   or the next; one vertex per line, x y z first (x y z w with 4OFF: divided by w), anything after
//   them (normal, colour, texture coordinates) ignored; one face per line, a corner count n, n
//   vertex indices (0-based), then an optional colour, ignored. '#' starts a comment.
//   Binary: big-endian int32 counts, float32 vertices, per face int32 n, n int32 indices, int32
//   colour count and that many float32 values.
// Refused with a message naming the line (or byte offset) and what is wrong: a missing keyword,
// counts that are not integers or exceed the file's size, a vertex line with fewer than three
// numbers, a corner count or index that is not an integer, negative, or out of range, a face with
// fewer than three corners, a file that ends early, w = 0 with 4OFF, and nOFF (dimension other
// than 3). Non-finite coordinates are passed through: read_mesh names them.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "modeling/status.h"

namespace ps {

struct PolygonSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> polygons;  // 0-based indices into points, all in range
};

// Parses the whole content of an .off file. Errors name what is wrong, without the file name.
Result<PolygonSoup> parse_off(const std::string& content);

}  // namespace ps
