#pragma once
// Internal to the zone unions (mesh_boolean.cpp); pulls in CGAL's kernel through exact_snap.h.
//
// Whether a snapped frustum (exact_snap.h) intersects itself, with the same verdict as CGAL's
// Polygon_mesh_processing::does_self_intersect, which union_snapped_solids ran on every
// operand: faces meet improperly when they share an edge and fold onto each other (coplanar,
// third corners on the same side), share a vertex and an opposite edge of one meets the other
// face, or share nothing and meet at all.
//
// Why not CGAL's function: a frustum's bottom cap lies exactly in its zone face, and its
// triangles are snapped exact points on that plane. Every pair of cap triangles CGAL tests is
// then exactly coplanar, so no interval filter decides it and each predicate falls back to
// rational arithmetic: on the SideBishop CSL set that test was 53% of the whole reconstruction
// (perf, one thread), more than the unions. Here a pair of faces whose six corners are all
// tagged with one plane, and verified to lie exactly on it, is decided in 2D, in the
// coordinate projection that is one-to-one on that plane: the same predicates (orientation of
// the third corners about the shared edge, segment against triangle, triangle against
// triangle) give the same answers there, and they are not degenerate, so intervals decide
// them. Every other pair goes through the same 3D predicates as CGAL's. Candidate pairs come
// from CGAL's box_self_intersection_d on the faces' interval boxes, as in CGAL.
//
// Preconditions (checked by the caller, as before CGAL's test): a valid, closed triangle mesh
// without a face whose corners are collinear. `tags[v]` are the plane tags of vertex v (as in
// SnappedSolid; missing entries count as untagged).
#include <array>
#include <vector>

#include "modeling/exact_snap.h"

namespace ps::exact {

bool snapped_self_intersects(const SurfaceMesh& sm, const std::vector<std::array<int, 3>>& tags,
                             const std::vector<Plane>& planes);

}  // namespace ps::exact
