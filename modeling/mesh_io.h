#pragma once
// Mesh input and output: OBJ, OFF, PLY and STL, chosen by the file's extension
// (case-insensitive), written through CGAL's IO.
//
// OFF and PLY files are read by modeling/off_reader.h and modeling/ply_reader.h (CGAL 5.5's
// readers for them crash or allocate without bound on malformed files; the headers say how);
// OBJ and STL by CGAL.
//
// read_mesh refuses, with a message naming the file and what is wrong: a missing or unreadable
// file, a directory, an unknown extension, a file that cannot be parsed, no faces, a non-finite
// coordinate, a face index out of range. Polygons with more than three corners are split into
// triangles (ear clipping in the polygon's best-fit plane).
//
// write_mesh writes to a temporary file beside the target and renames it into place, so a
// failure never leaves a partial output file.
#include <string>

#include "modeling/mesh.h"
#include "modeling/off_reader.h"
#include "modeling/status.h"

namespace ps {

struct MeshReadOptions {
  // Refuse a polygon with more than three corners (naming it) instead of splitting it into
  // triangles: for commands whose input must be the user's own triangles (deform).
  bool triangles_only = false;
};
Result<TriMesh> read_mesh(const std::string& path, const MeshReadOptions& options = {});
// The file's vertices and polygons as stored (no triangulation, no finiteness check); every
// index in range. Errors name the file.
Result<PolygonSoup> read_polygon_soup_file(const std::string& path);
Status write_mesh(const std::string& path, const TriMesh& mesh);

// True when the extension is one write_mesh/read_mesh understands (.obj .off .ply .stl).
bool is_mesh_extension(const std::string& path);

}  // namespace ps
