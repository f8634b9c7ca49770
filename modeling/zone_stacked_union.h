#pragma once
// The per-zone union (thesis Eq. 4.2) of a zone whose primitives are straight prisms along one
// axis, built from a 2D arrangement instead of CGAL's 3D corefinement. Orthogonal zones only.
//
// Parallel sections (CT and MRI contours, most of OReX's CSL sets, any sketch on one stack of
// planes) give slab zones whose only primitives stand on the two faces of one axis k: prisms
// P_A x [c0, a] rising from the low face and P_B x [b, c1] hanging from the high face, with
// c0 < b < a < c1 (Eq. 4.1: each reaches (1 - eps) of the zone). Their union is
//   P_A x [c0, b]  +  (P_A u P_B) x [b, a]  +  P_B x [a, c1],
// so it only needs where the boundaries of P_A and P_B cross. Corefinement spent 22-84 ms on
// such a zone of CSL hand_ok (two 1 400-vertex prisms, Epeck); this takes about a millisecond.
//
// Construction. The loops of P_A and P_B are split at their crossings (exact orientation tests
// decide which edges cross; the crossing points are rounded to doubles, as corefinement's
// output is). Each split edge of one region is inside or outside the other (an exact
// point-in-region test for the loop's first point, toggled at every crossing). Faces:
//   - the low prisms' bottom caps at c0 and the high prisms' at c1, unchanged (so the zone's
//     caps match its neighbours' over the same pieces, zone_stitch.h);
//   - walls of P_A over [c0, b] and of P_B over [a, c1], their edge at b (at a) split at the
//     crossings;
//   - walls of the split edges of either region that lie outside the other, over [b, a];
//   - at b, facing -e_k, P_B \ P_A; at a, facing +e_k, P_A \ P_B: constrained Delaunay
//     triangulations (CGAL, exact predicates) of their split boundary edges.
// Walls of a region edge p -> q (region on the left, e_u x e_v = e_k) are (p@z0, q@z0, q@z1,
// p@z1), outward.
//
// What is accepted (else std::nullopt and the caller takes the exact union): every primitive a
// straight prism over its partition piece (bottom and top vertices the piece's loops lifted, in
// order), all along one axis; per face, pieces from one plane and one face rectangle whose
// loops are pairwise disjoint (exact); boundaries of P_A and P_B meeting only in proper
// crossings, at distinct points well inside both edges (no shared vertex, no vertex on an edge,
// no overlap); the result a closed, oriented 2-manifold without self-intersections (checked:
// the rounded crossing points are the only inexact step). With prisms on one face only, or with
// b > a, the prisms are disjoint and the union is their concatenation.
#include <optional>

#include "modeling/cylinder_builder.h"
#include "modeling/mesh.h"
#include "modeling/zone_partition.h"

namespace ps {

std::optional<TriMesh> stacked_zone_union(const Partition& partition, const Zone& zone,
                                          const ZonePrimitives& primitives);

}  // namespace ps
