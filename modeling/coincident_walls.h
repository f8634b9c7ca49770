#pragma once
// Internal to the zone unions of the arbitrary-plane reconstruction (mesh_boolean.cpp,
// nef_union.cpp); pulls in CGAL's kernel through exact_snap.h.
//
// Two frusta of a zone can meet face to face along a wall they share: both rise from the same
// zone edge to the same two top points (stress seed 2: the pulled top points of two frusta whose
// sections meet on that edge land on the same place). In exact arithmetic a union glues them
// only if the two walls are the same surface. They are not when the top points, computed
// by different formulas, differ by a rounding step, or when each frustum splits the (slightly
// non-planar) quad along the other diagonal: then a void a few 1e-17 thick stays between them,
// bounded by both walls, and the boundary is not a 2-manifold (corefinement refuses the pair).
// So before the union, points of
// different frusta within `tol` of each other are made one exact point (the one of the
// lower-numbered frustum), and a wall edge whose quad another frustum splits along the other
// diagonal is flipped to match. A frustum that is no longer usable after that (a collinear or
// self-intersecting face) is left as it was. Hand-written: no CGAL function aligns the
// triangulations of two meshes along a shared patch.
//
// Only vertices without plane tags move (a tagged vertex is exact on its planes, and zone-face
// caps must keep matching the neighbouring zone's), and only wall edges flip (an edge or new
// diagonal with an untagged end). meshes[i] is solids[i] snapped (exact_snap.h), vertex for
// vertex. Returns the number of points moved and edges flipped (0: meshes unchanged).
// `kept` (optional) receives, per mesh, 1 when the mesh was changed and kept: it was then
// checked here to be usable and free of self-intersections (exact tests).
#include <vector>

#include "modeling/exact_snap.h"

namespace ps::exact {

int align_coincident_walls(std::vector<SurfaceMesh>& meshes, const std::vector<SnappedSolid>& solids, double tol,
                           std::vector<char>* kept = nullptr);

}  // namespace ps::exact
