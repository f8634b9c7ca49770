#pragma once
// Flat slivers folded by rounding, removed and the seam zipped (the stitched surface of the
// arbitrary-plane reconstruction, thesis 6.3.3).
//
// An exact zone union can hold faces thinner than a double can place: a cap whose apex lies on
// the opposite edge (stress seed 73: apex 3.5e-17 off a 0.2-long edge), or a strip of such caps
// between a crease edge and the chain of vertices the other side of the crease put on it (seed
// 74: three faces of area 1e-19 to 1e-21). Rounding the exact points to doubles can turn such a
// face over, and its neighbours then cross each other over it, although the exact surface was
// sound. No CGAL function of 5.5 does this repair (its experimental
// remove_almost_degenerate_faces collapses needles, which moves curve vertices, and flips caps
// one at a time, which cannot resolve a strip of collinear points), so it is written here.
//
// Shape conventions: `crossing` holds pairs of face indices from intersecting_face_pairs; tol is
// a length (the stitch's weld tolerance).
#include <array>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// Flat faces near the crossings (a face whose height over its longest edge is at most tol, with
// a vertex on a crossing face, and the flat faces sharing an edge with those) are removed; the
// hole each strip leaves has two sides that are one segment to within tol, and it is zipped by
// splitting the faces of one side at the vertices of the other (split_t_junctions). Where the
// two sides still meet at separate vertices within tol of each other (rounding put the ends of
// a strip a step apart: stress seed 38), vertices on the open seam are merged, each into the
// smallest index of its group; no other vertex moves, so curve points stay within tol of where
// they were. Returns the number of faces removed, 0
// when there was none (mesh unchanged). The caller checks the result (closed, manifold, no
// crossing) and keeps the original when the check fails.
int remove_folded_slivers(TriMesh& mesh, const std::vector<std::array<int, 2>>& crossing, double tol);

// Height of face f over its longest edge (0 for a repeated vertex or zero-length edges).
double face_height(const TriMesh& mesh, const Face& f);

}  // namespace ps
