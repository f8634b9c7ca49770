#pragma once
// Primitives of the orthogonal reconstruction (thesis 4.3 and 4.4): one cylinder (prism) per
// section piece per adjacent non-empty zone, its bottom the piece on the zone face and its top the
// bottom translated into the zone.
//
//   Body zone (4.3, Eq. 4.1): height h_p = h_zn - eps with eps = height_margin * h_zn. The top's
//   points lying on a side face of the zone that holds a section there are pulled into the zone
//   by perturb * (the zone's extent across that face), so no wall of the prism lies in a face
//   carrying another section (this lets the union interpolate that section). The pull is halved
//   until every top cap triangle keeps its orientation.
//   End zone (4.4): the prism is stretched through the zone across the face opposite its section
//   and continued through the following zones along the same axis while they are empty; it stops
//   with Eq. 4.1 in the first non-empty zone, or in the zone whose far face is the bounding box.
//   Each zone gets its own segment of the stretched prism (full height where it passes through),
//   so zones stay independent. Walls of a piece clipped by a plane carrying no section there
//   stay in that plane; the stitching merges them with the neighbour zone.
//
// Holes: a piece with holes gives a prism with inner walls. Caps are constrained Delaunay
// triangulations of the piece (no Steiner points), computed once per piece, so the two zones
// sharing a piece get identical cap triangles.
//
// Every primitive is a closed, outward-oriented triangle mesh.
#include <vector>

#include "modeling/content_cache.h"
#include "modeling/mesh.h"
#include "modeling/zone_partition.h"

namespace ps {

struct CylinderOptions {
  double height_margin = 0.05;  // eps of Eq. 4.1 as a fraction of the zone height
  double perturb = 0.02;        // pull of top points off neighbour faces (fraction of zone size)
};

// Where a primitive comes from. Every primitive is a prism whose first `bottom_count` vertices
// are its bottom (on zone face `face`, 0..5 = -x,+x,-y,+y,-z,+z) and the next `bottom_count`
// its top, vertex for vertex. Body-zone prisms of Eq. 4.1 are the ones topology edits change
// (topology_edit.h); extension segments (4.4) are not.
struct PrimitiveInfo {
  int piece = -1;
  int face = 0;
  bool body = false;  // a body zone's own prism (Eq. 4.1), not an extension segment
  int bottom_count = 0;
  // The builder proved the prism free of self-intersections: a pulled prism passed the 3D test,
  // or a straight prism stands over a piece whose loops were checked simple and pairwise
  // disjoint in exact 2D arithmetic (rounded clipping can leave a piece that is not). The zone
  // union then skips its own 3D test of that operand. Edits that move vertices clear it.
  bool verified = false;
};

struct ZonePrimitives {
  std::vector<TriMesh> solids;  // in a fixed order (zone's own faces, then incoming extensions)
  std::vector<PrimitiveInfo> info;  // parallel to solids
};

// Cap triangulation of a piece: indices into the concatenation of piece.loops, counter-clockwise
// in the plane's 2D frame.
std::vector<std::array<int, 3>> triangulate_piece(const SectionPiece& piece);

// What the progressive reconstructor keeps of one run's primitives: cap triangulations by
// piece loops, and whether a pulled prism intersects itself, by prism.
struct PrismKey {
  TriMesh prism;
  bool operator==(const PrismKey& o) const { return prism.vertices == o.prism.vertices && prism.faces == o.prism.faces; }
};
struct CylinderCache {
  ContentCache<std::vector<std::vector<Vec2>>, std::vector<std::array<int, 3>>> caps;
  ContentCache<PrismKey, bool> self_intersecting;
};

// Primitives per zone (indexed like Partition::zones). Results found in `previous` are reused;
// everything computed or reused goes to `next` (either may be null).
// The 3D point of an axis plane x_k = coord with in-plane coordinates q (u = axis (k+1)%3,
// v = axis (k+2)%3, so e_u x e_v = e_k): the frame of SectionPiece loops.
Vec3 axis_frame_point(int k, double coord, const Vec2& q);

// Whether a straight prism over `piece` is free of self-intersections, decided in exact 2D
// arithmetic: every loop has at least three points and no zero-length edge, and no loop crosses
// or touches itself or another loop. Pieces with more than 16 loops are not tested pairwise and
// return false (unproven). build_cylinders sets PrimitiveInfo::verified from it.
bool piece_is_simple(const SectionPiece& piece);

std::vector<ZonePrimitives> build_cylinders(const Partition& partition, const CylinderOptions& options = {},
                                            const CylinderCache* previous = nullptr, CylinderCache* next = nullptr);

}  // namespace ps
