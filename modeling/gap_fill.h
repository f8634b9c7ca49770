#pragma once
// Filling of planar gaps left in a surface that should be closed.
//
// The stitching of zone solids (zone_stitch.h) can leave a hole where a zone face's cap material
// was not matched: seen on CGAL's bunny00 sliced by two planes per axis, a 6e-4 x 0.2 rectangle
// of a section plane with nothing on either side. Such a gap is a loop of boundary edges lying
// in one plane, and the only closed completion that keeps the surface where it is, is that
// plane's region inside the loop.
//
// fill_planar_gaps closes every boundary loop whose vertices all lie within `plane_tol` of the
// loop's best-fit (Newell) plane: the loop is triangulated by ear clipping in that plane
// (polygon_triangulate.h), its triangles oriented against the faces along it, so the
// orientation stays consistent. The caller checks the result (topology, and intersections of
// the added faces with the rest: `added` lists their indices).
//
// Returns the number of loops filled (0: no boundary, mesh unchanged), or -1 when a boundary
// vertex starts two boundary edges (the loops are ambiguous), or a loop is not planar or has
// fewer than three vertices (mesh unchanged).
#include <vector>

#include "modeling/mesh.h"

namespace ps {

int fill_planar_gaps(TriMesh& mesh, double plane_tol, std::vector<int>* added = nullptr);

}  // namespace ps
