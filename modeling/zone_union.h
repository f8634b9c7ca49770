#pragma once
// Union of the primitives of one zone (thesis Eq. 4.2 and 6.3, the term in parentheses),
// through CGAL's corefinement (Polygon_mesh_processing::corefine_and_compute_union, exact
// predicates and constructions). This is the only translation unit including CGAL's
// corefinement. Zones are independent; the caller runs them in parallel.
#include <array>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// Union of closed, outward-oriented solids, taken one by one in the given order (the result's
// combinatorics depend on that order, so callers pass a canonical order). One solid is returned
// unchanged; none gives an empty mesh.
Result<TriMesh> union_solids(const std::vector<TriMesh>& solids);

// The same, where verified[i] says the caller has proved solid i free of self-intersections
// (cylinder_builder.h, PrimitiveInfo::verified): its 3D self-intersection test is skipped. The
// other operand checks (closed, oriented 2-manifold, positive volume) still run. A `verified`
// of another size than `solids` counts as all false.
Result<TriMesh> union_solids(const std::vector<TriMesh>& solids, const std::vector<bool>& verified);

// A solid whose vertices must lie exactly on given planes (chapter 6: section planes of any
// orientation cannot hold double points exactly). tags[v] lists up to three plane indices
// (-1 unused); the exact vertex is the point nearest to mesh.vertices[v] on the intersection
// of those planes, computed in exact arithmetic. Untagged vertices are used as they are.
struct SnappedSolid {
  TriMesh mesh;
  std::vector<std::array<int, 3>> tags;
};

// Union of snapped solids (same order rule as union_solids). The result is rounded from the
// exact values, also for a single solid, so a point shared by two zones rounds the same way in
// both.
Result<TriMesh> union_snapped_solids(const std::vector<SnappedSolid>& solids, const std::vector<Plane>& planes);

}  // namespace ps
