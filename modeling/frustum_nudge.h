#pragma once
// Overlap nudges between frusta whose walls coincide to rounding (thesis 6.3.1, Case 2).
//
// Two frusta on faces F and G of a zone that share bottom points on the F-G edge must overlap
// beyond them for their union to be a solid. The top placement of frustum_builder can put both
// tops next to the shared points at the same place, up to an ulp (each pulled inside the zone
// by the same margins): the two walls then coincide to rounding, and CGAL refuses the union as
// non-manifold (stress seed 9, zone 18: a whole zone edge shared, tops 1e-17 apart).
// frustum_connectors.h fills an open wedge; here there is no wedge to fill.
//
// A nudge moves each such top point (untagged: not kept on a face) a small fraction of its
// distance towards the other frustum's bottom plane, so each wall leans into the other frustum
// and the two overlap in a thin wedge along the shared points. Bottoms are not touched, so the
// surface on the zone faces, which the stitching relies on, is unchanged; a top point moves
// towards a face plane it lies inside of, by a fraction of its distance, so it stays on the
// zone's side of that plane.
//
// Used, like connectors, only on a zone whose union was refused, and only for pairs whose own
// union is refused and becomes valid with the nudge (fractions 0.02, then 0.05).
#include <vector>

#include "modeling/pair_union_memo.h"
#include "modeling/zone_union.h"

namespace ps {

// The frusta of one zone, with the top points of refused pairs nudged as above (same order).
// Shared bottom points: the same set of plane tags (both bottom planes among them) and
// coordinates within 1e-9 of the frusta's diagonal (tagged points are made exact on their
// planes before the union, so equal tags are one point). Frustum layout: bottoms are the
// first half of the vertices, vertex i + n/2 is the top of bottom vertex i (frustum_builder).
// `nudged` (optional) receives the number of pairs changed. `memo` (optional) answers the
// unions of pairs as they are from earlier requests (pair_union_memo.h); it must be built on
// the same `planes`.
std::vector<SnappedSolid> with_overlap_nudges(const std::vector<SnappedSolid>& frusta, const std::vector<Plane>& planes,
                                              int* nudged = nullptr, PairUnionMemo* memo = nullptr);

}  // namespace ps
