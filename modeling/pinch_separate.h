#pragma once
// Separation of a closed surface that touches itself along edges or at vertices (pinches).
//
// Where material lies in two diagonally opposite zones around a grid line and not in the other
// two, the stitched surface of the reconstruction is two solid wedges meeting along that line:
// edges with four faces, and vertices whose faces form two fans. Such a surface bounds a valid
// solid but is not a 2-manifold, and the reconstruction used to refuse it (1.1% of the valid
// stress inputs, bench/results/stress.md).
//
// separate_pinches makes it one:
//   1. Around an edge (a, b) with more than two faces, the faces are ordered by the angle of
//      their third vertex about the edge's axis d = b - a (a < b by index). With outward
//      orientation, a face running b -> a has solid on its side of increasing angle and a face
//      running a -> b on its side of decreasing angle, so walking in increasing angle each
//      b -> a face opens a wedge of solid and the next face, which must run a -> b, closes it.
//      The faces of one wedge are glued along the edge; different wedges are not.
//   2. Around each vertex the faces are grouped into fans through the glued edges; a vertex with
//      several fans gets one copy per fan (the fan holding the vertex's first corner, in face
//      order, keeps the original index; the copies are appended in corner order, so the result
//      depends only on the input mesh).
//   3. Every copy of a split vertex moves by `gap` against its fan's area-weighted normal, into
//      its own solid, so the sheets no longer touch.
// `gap` must be far below the local edge lengths; the caller checks the result for
// self-intersections around the moved vertices (listed in `moved`).
//
// PinchMode::kJoin pairs the faces the other way: across the empty wedges, each a -> b face with
// the next face in increasing angle. The solids then stay joined along the line by a sliver
// `gap` wide, and the empty wedges become separate. Where a vertex's faces form a single fan
// however they are paired in kSeparate (the fan passes through the pinched edge twice), kJoin
// can split it: the caller tries kSeparate first, then kJoin.
//
// PinchDirection::kInsideFan changes step 3: each copy moves along fan_cone_direction (below)
// of its fan's face normals, the direction furthest inside all of its faces, where one exists,
// else along the fan normal. The fan normal, an area-weighted mean, can point out of a thin
// wedge or a bladed fan, and then the moved faces cross the other sheet however small the gap:
// mixed stress seed 158 (a pinched edge whose empty wedges are 0.9 and 5 degrees wide, between
// nearly coplanar faces of neighbouring zones), seed 938 (vertex pinches whose fans are blades of
// three to five faces, two nearly opposite), and 14 face pairs of Vetebrae's 88 pinches. The
// reconstruction tries the fan normal first (what it resolved keeps its result bit for bit) and
// kInsideFan when both modes leave a crossing.
//
// Hand-written: CGAL 5.5's PMP::duplicate_non_manifold_vertices splits vertices only, on a
// halfedge graph, which cannot hold an edge with four faces in the first place.
//
// Returns the number of vertices split (0: the surface has no pinch, mesh unchanged), or -1 when
// the surface has a boundary edge, an edge whose faces do not alternate in direction, a repeated
// angle, or a fan without a normal (mesh unchanged).
#include <vector>

#include "modeling/mesh.h"

namespace ps {

enum class PinchMode { kSeparate, kJoin };
enum class PinchDirection { kFanNormal, kInsideFan };

int separate_pinches(TriMesh& mesh, double gap, std::vector<int>* moved = nullptr,
                     PinchMode mode = PinchMode::kSeparate,
                     PinchDirection direction = PinchDirection::kFanNormal);

// The unit direction d that maximises min_i u_i . d over the unit vectors u (the fan's face
// normals, signed towards the side the copy moves to), or zero when that minimum is not
// positive. Moving the copy along d moves every face of its fan to that side, so none sweeps
// through the other fans at the vertex. The fan normal (an area-weighted mean) misses it where
// the fan is a thin blade (stress seed 938 of the mixed oblique set: fans of three to five
// faces, two of them nearly opposite). The maximum of a minimum of linear functions on the
// sphere has at most three active constraints with equal values, so it is among: one u_i; the
// bisector of two; the direction equally far from three, (u_j - u_i) x (u_k - u_i) with either
// sign. Fans have a few faces (the candidates are cubic in their number; over 24 faces the fan
// is not searched).
Vec3 fan_cone_direction(const std::vector<Vec3>& u);

}  // namespace ps
