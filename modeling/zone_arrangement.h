#pragma once
// Zones of the arbitrary-orientation case (thesis 6.2): the reconstruction box split by every
// section plane in turn into convex polyhedra. Each zone is kept as its bounding half-spaces and
// its boundary polygons; the split uses exact predicates and exact intersection points (Epeck),
// so neighbouring zones agree exactly on their shared faces and the volumes add up to the box.
//
// This is the first step of chapter 6 (frusta on these zones are not built yet); for axis
// planes it gives the same cells as partition_zones().
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/zone_partition.h"

namespace ps {

struct ConvexZone {
  std::vector<HalfSpace> half_spaces;      // normal . p <= offset for every point of the zone
  std::vector<std::vector<Vec3>> faces;    // boundary polygons, counter-clockwise seen from outside
  std::vector<int> face_plane;             // per face: index into the planes, or -1 (box face)
  // Per face: its outward unit normal, exact in sign (the split's side, not the polygon's
  // rounded vertices, which can all coincide on a face a few ulps wide).
  std::vector<Vec3> face_outward;
};

// Splits `box` by each plane in order; planes missing the current zones leave them whole. Zones
// with zero volume are never produced. The result is independent of the plane order as a set of
// cells, not as a list.
std::vector<ConvexZone> partition_box_by_planes(const Box3& box, const std::vector<Plane>& planes);

// Volume of a convex zone (divergence theorem over its faces).
double zone_volume(const ConvexZone& zone);

}  // namespace ps
