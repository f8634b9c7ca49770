#pragma once
// Frusta of the arbitrary-orientation reconstruction (thesis 6.3.1 and 6.3.2): one frustum per
// section piece per adjacent non-empty zone, its bottom the piece on the zone face and its top
// inside the (convex) zone; end-zone pieces are extended by virtual sections through empty
// zones.
//
//   Body zone (6.3.1, Eq. 6.1): the top is the bottom translated by h_p = d_p - eps along the
//   face's inward normal, d_p the depth of the zone along that normal from the piece's centre
//   (eps = height_margin * d_p). Top points are then shrunk towards the top's centre, uniformly
//   by a ratio s (Case 1) and, for the points still outside, each one just far enough to lie
//   inside with a margin (Case 2: the points near a face carrying another section stay near it,
//   so the two frusta overlap beyond their common segment). s runs from 1 down to min_scale;
//   then the height is lowered (never a cone). See docs/reconstruction.md for how this differs
//   from the thesis's Laplacian top deformation (Eq. 6.2).
//   Points of the bottom on a face that carries no section at that point (the piece was clipped
//   by a plane holding no section there) keep their top on that face, so the wall lies in the
//   face and is merged with the neighbour zone's wall by the stitching.
//   End zone (6.3.2): the bottom is projected along the inward normal onto the other faces;
//   the face with the largest projected area is chosen; if it is an internal face, the
//   projection shrunk into that face is a virtual section (the frustum's top), continued from
//   the zone across it until a non-empty zone or the box is reached, where the last frustum is
//   built as in a body zone.
//
// Every frustum is a closed, outward-oriented triangle mesh without self-intersections, lying
// inside its zone; vertex tags name the planes a vertex lies on exactly (zone_union.h).
#include <string>
#include <vector>

#include "modeling/polyhedral_partition.h"
#include "modeling/status.h"
#include "modeling/zone_union.h"

namespace ps {

struct FrustumOptions {
  double height_margin = 0.05;  // eps of Eq. 6.1 as a fraction of d_p
  double face_margin = 0.02;    // top points keep this fraction of d_p from the zone's faces
  double min_scale = 0.3;       // smallest uniform shrink of a top (never a cone)
  int height_steps = 10;        // heights tried: (1 - eps) d_p * (steps - i) / steps
  bool extend_end_zones = true; // 6.3.2 virtual sections
};

struct FrustumReport {
  int frusta = 0;
  int virtual_sections = 0;   // virtual sections made by end-zone extensions
  int extensions_to_box = 0;  // end-zone pieces whose best face was on the box (not extended)
  int fallback_frusta = 0;    // body frusta built by the homothety fallback (no translated top fit)
};

struct ZoneFrusta {
  std::vector<SnappedSolid> solids;  // canonical order: zone's faces in order, pieces in order
};

// Per zone (indexed like partition.zones). Fails with a message naming the zone and face when
// no frustum fits (should not happen for a convex zone of positive volume).
Result<std::vector<ZoneFrusta>> build_frusta(const PolyPartition& partition, const FrustumOptions& options = {},
                                             FrustumReport* report = nullptr);

}  // namespace ps
