#pragma once
// The per-zone union (thesis Eq. 4.2) of a zone that its primitives provably fill: the zone's
// box, without the exact corefinement. Orthogonal zones only (zone_partition.h).
//
// Inside a model, every face of a zone is often covered by one section piece that is the whole
// face rectangle (109 of the 369 body zones of the 20-section ellipsoid in bench/recon_bench).
// The six prisms of such a zone fill it, and CGAL's union returns the box made of the six bottom
// caps, at about 4 ms per zone on the CI machine; this returns the same box in microseconds.
//
// Why the prisms fill the zone. Write a point of the zone in coordinates normalised to [0, 1]
// per axis, and let d be its smallest distance to a face, say to the face of axis k, so d <= 1/2.
// The prism on that face reaches depth t >= 1/2 (checked; Eq. 4.1 gives 0.95), and its top is
// its bottom moved inward by at most t along each side axis (checked; the 4.3 pull is a few
// percent). Its section at depth d <= t therefore contains the face rectangle shrunk by at most
// d per side (walls are linear between bottom and top vertices, diagonals included), and the
// point, at distance >= d from every side, lies in it. Everything checked is read off the
// primitives themselves, so prisms changed by a topology edit (topology_edit.h) either pass the
// same checks or go to the exact union.
#include <optional>

#include "modeling/cylinder_builder.h"
#include "modeling/mesh.h"
#include "modeling/zone_partition.h"

namespace ps {

// The zone's box as 8 vertices and 12 outward triangles (each face triangulated as its prism's
// bottom cap, so a neighbour zone's cap over the same piece matches it), when the primitives
// are exactly six prisms, one per zone face, each with a whole-rectangle bottom and a top that
// keeps the zone filled (see above). std::nullopt otherwise: the caller takes the exact union.
std::optional<TriMesh> filled_zone_union(const Zone& zone, const ZonePrimitives& primitives);

}  // namespace ps
