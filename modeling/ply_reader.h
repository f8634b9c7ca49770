#pragma once
// Reader for Stanford PLY meshes: ascii, binary_little_endian and binary_big_endian.
//
// Written by hand instead of calling CGAL 5.5's PLY reader, which fuzzing showed crashing or
// exhausting memory on malformed headers and bodies: it dereferences a null dynamic_cast when a
// coordinate is not float or double ("property uchar z"; UBSan, 2026-12-06), segfaults when a
// property precedes every element, and sizes a buffer from each face's list count before reading
// it (a corrupt count makes it allocate up to 32 GB). Here every count is checked against the
// bytes or tokens left before anything is allocated for it.
//
// Read: the "vertex" (or "vertices") element's x, y and z, of any numeric type; the "face" (or
// "faces") element's "vertex_indices" (or "vertex_index") list, of any integer type. Every other
// element and property is parsed and skipped. Refused with a message naming what is wrong: a
// missing "ply" magic or format line, an unknown format or type, a malformed element or property
// line, a property before any element, counts the file cannot hold, a vertex element without x,
// y or z, faces without an index list, an index that is negative, not an integer, or out of
// range, a face with fewer than three corners, and a body that ends early. Non-finite
// coordinates are passed through (read_mesh names them).
#include <string>

#include "modeling/off_reader.h"  // PolygonSoup
#include "modeling/status.h"

namespace ps {

// Parses the whole content of a .ply file. Errors name what is wrong, without the file name.
Result<PolygonSoup> parse_ply(const std::string& content);

}  // namespace ps
