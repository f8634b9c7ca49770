#pragma once
// Clearance limit for smoothing moves (mesh improvement, docs/mesh-improvement.md "Thin parts").
//
// Smoothing moves a vertex by a fraction of its umbrella vector, which knows nothing about the
// rest of the surface: where two sheets of a thin part (or the two sides of a narrow gap) are
// closer than an edge length, a round of smoothing pushes them through each other, and the exact
// self-intersection check can only undo every such move afterwards. (eight_20's reconstruction:
// 140k crossing face pairs per round, 11.5 s of checks, and no smoothing at all on its thin
// sheets.) Mesh improvement calls this on the moved corners of the faces its check finds
// crossing (ImproveOptions::ClearanceLimit), and shortens those moves instead of undoing them:
//
//   d_v = |p_v - r_v|   the move of vertex v over the round (r: positions before smoothing)
//   c_v = min over faces g not incident to v whose rest normal opposes v's rest normal
//         (n_g . n_v < 0: the other side of a slab, or the far side of a gap) of dist(r_v, g)
//   if d_v > kShare c_v:  p_v <- r_v + (kShare c_v / d_v) (p_v - r_v)
//
// with kShare = 0.4: two sheets a gap c apart, both moving towards each other, close at most 0.8 c
// of it. Faces of the same sheet (normals alike) never limit a move, so smoothing elsewhere is
// unchanged bit for bit. This is a heuristic that makes crossings rare, not a guarantee (the
// closest pair of two triangles can be two edges, and a move sideways along a crease is not
// covered): the exact check runs again on every face of a shortened move, and undoes what
// still crosses.
//
// Written here rather than with CGAL's AABB tree: the query is "nearest face among those facing
// the point, within a radius that differs per vertex", for about every vertex of a 200k-face mesh
// each round; a uniform grid over the faces' boxes, built once per call and queried in
// parallel, answers it in a few tens of milliseconds.
#include <cstdint>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

inline constexpr double kClearanceShare = 0.4;

// positions: #V after smoothing, changed in place; rest: #V before it; faces: the mesh (both
// position sets share it); only: #V flags, the vertices to consider (all when null). Returns the
// number of moves shortened. Deterministic: each vertex is decided from the rest positions and
// its own move only, so the result does not depend on threads or order.
int limit_moves_by_clearance(std::vector<Vec3>& positions, const std::vector<Vec3>& rest,
                             const std::vector<Face>& faces, const std::vector<std::uint8_t>* only = nullptr);

}  // namespace ps
