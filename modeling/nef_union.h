#pragma once
// Last resort of a zone union (thesis 6.3, the union of a zone's frusta): all the snapped
// solids united at once through CGAL's Nef polyhedra (exact, closed under Boolean operations on
// any polyhedral set, manifold or not).
//
// Why: corefinement (union_snapped_solids) unites two closed 2-manifolds into a 2-manifold and
// refuses when the result of that pair would not be one, e.g. two frusta touching along an
// edge. In a zone of five frusta, such a contact of one pair can be covered by a third frustum,
// so the whole union is a 2-manifold while every order of pairwise unions meets a non-manifold
// intermediate (the caller tries rotations and the reverse). A Nef polyhedron has no such
// intermediate restriction. It costs about two orders of magnitude more than corefinement, so
// it runs only for zones whose unions all failed, one zone at a time (a process-wide lock).
//
// Frusta meeting face to face on a wall they share only up to rounding (top corners an ulp
// apart, the quad split along different diagonals) would leave a crack a few 1e-17 wide
// between them; before the union, points of different frusta within 1e-14 of the zone's size
// are made one exact point and such walls one triangulation, so the two glue (a frustum that
// this would make unusable is left as it was).
//
// The result is the regularised union's boundary, triangulated, rounded from the exact values
// like union_snapped_solids (so a point shared with a neighbouring zone rounds the same way).
// When that boundary is not a 2-manifold (the union really is not one: frusta touching along an
// edge or at a point without overlapping), it is refused with a message, or, with
// allow_non_manifold, returned as triangles sharing the contact's vertices (*manifold set to
// false) for the stitch's pinch resolution. Refused, with a message, when an operand is unusable
// after snapping.
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"
#include "modeling/zone_union.h"

namespace ps {

Result<TriMesh> union_snapped_solids_at_once(const std::vector<SnappedSolid>& solids, const std::vector<Plane>& planes,
                                             bool allow_non_manifold = false, bool* manifold = nullptr);

}  // namespace ps
