#pragma once
// The operand check of the exact Booleans (mesh_boolean.h) and of the chapter 6 frusta: a solid
// is finite, closed, a consistently oriented 2-manifold with positive signed volume, and does not
// intersect itself.
//
// Checked solids are remembered: a mesh identical bit for bit (same vertices, same faces, same
// order) to one of the last few large solids that passed is not checked again. Sculpting applies
// operation after operation to one model, and the self-intersection test of a 20k-face model is
// about a third of an operation's time (bench/results/sculpt.md). The memo compares whole
// meshes, not just hashes, so a remembered answer is exactly what checking again would give.
// Thread-safe.
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// `which` names the solid in the message ("the model", "the tool solid", ...).
Status check_solid(const TriMesh& m, const char* which);

// Records a solid the caller knows to be finite and free of self-intersections (a Boolean
// result verified to that standard), once its topology agrees (closed, oriented 2-manifold,
// positive volume: checked here), so that the next operation on it skips check_solid. Small
// meshes are not recorded.
void remember_checked_solid(const TriMesh& m);

// Empties the memo (benchmarks measure the first operation on a new model with it).
void forget_checked_solids();

}  // namespace ps
