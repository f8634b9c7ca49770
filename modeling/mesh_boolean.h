#pragma once
// Exact Boolean operations on closed solids, for sculpting (extrusion, tunnelling, cutting).
// CGAL corefinement on the exact-constructions kernel; the result is rounded to doubles once.
//
// Operands: closed, 2-manifold, consistently and outward-oriented triangle meshes (positive
// signed volume) without self-intersections. Each is checked first; a violation is refused with
// a message naming the operand ("the model", "the tool solid"). The result is closed and
// outward-oriented; it may be empty (a difference that removes everything) or have several
// components. Every input vertex that ends on the result keeps its exact coordinates.
#include "modeling/mesh.h"
#include "modeling/solid_check.h"  // check_solid: the operand check
#include "modeling/status.h"

namespace ps {

enum class BooleanOp { kUnion, kDifference, kIntersection };

// a op b (kDifference: a minus b). `checked_a`: the caller has already passed `a` through
// check_solid (repeated operations on one model check it once).
Result<TriMesh> mesh_boolean(const TriMesh& a, const TriMesh& b, BooleanOp op, bool checked_a = false);

}  // namespace ps
