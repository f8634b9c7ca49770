#pragma once
// Connectors between frusta that meet on a zone edge (thesis 6.3.1, Case 2, and the failure of
// its Fig. 6.5c).
//
// When the sections on two faces F and G of a zone meet on their common edge, the frusta built
// on them share bottom points there. Their union is a valid solid only if the two frusta
// overlap beyond that common part. The top placement of frustum_builder aims at this, but a
// frustum that had to stay low (a shallow zone behind its face) can leave its wall almost in
// its own face, so the two walls bound an empty wedge at the edge and the union is refused as
// non-manifold (seen on the armadillo CSL set: walls at 90 and 137 degrees in a 142-degree
// dihedral).
//
// A connector fills that wedge: for each run of bottom points two frusta share (a point, or a
// segment along the zone edge), the convex hull of those points and of the top points next to
// them in both frusta. It lies in the zone (a convex hull of points of a convex zone). Its
// only points on the zone's boundary are the shared points: top points kept on a face (tagged)
// are left out, so the union's boundary on the zone faces, which the stitching of zones relies
// on, is unchanged. Adding connectors never removes material, so the surface still passes
// through every section piece.
//
// The reconstruction adds connectors only to a zone whose union was refused, so zones that
// succeed without them keep their exact previous result.
#include <vector>

#include "modeling/pair_union_memo.h"
#include "modeling/zone_union.h"

namespace ps {

// The frusta of one zone with their connectors inserted: each connector right after the first
// frustum of its pair (pairs in order, then runs along the first frustum). Unions taken in any
// balanced or sequential order of this list then meet the connector before, or together with,
// the second frustum of its pair, which is what keeps the intermediate unions manifold.
// Shared points are bottom vertices with identical coordinates; bottoms are the first half of
// each frustum's vertices (frustum_builder's layout). Runs whose hull is flat are skipped.
// Only pairs whose own union (union_snapped_solids on `planes`) is refused get connectors, and
// only when the pair's union with them is valid. `added` (optional) receives the number of
// connectors. `memo` (optional) answers the pairs' own unions from earlier requests
// (pair_union_memo.h); it must be built on the same `planes`.
std::vector<SnappedSolid> with_frustum_connectors(const std::vector<SnappedSolid>& frusta, const std::vector<Plane>& planes,
                                                  int* added = nullptr, PairUnionMemo* memo = nullptr);

}  // namespace ps
