#pragma once
// Regularised Boolean operations on simple closed 2D loops, exact (CGAL's Polygon_set_2 on the
// exact-constructions kernel), for the curve repair (curve_repair.h): overlapping curves of one
// plane become the boundary of their union.
//
// Shapes: a loop lists its points in order, the last joined to the first, in either
// orientation, and must be simple apart from consecutive repeated points (dropped here); a
// loop left with fewer than 3 points or no area is skipped. The result is a list of polygons with holes, each [outer, hole, hole...],
// outer loops counter-clockwise and holes clockwise, rounded to doubles (points of the input come
// back bit for bit; crossing points are rounded). Outer loops and holes may touch at vertices
// (CGAL keeps such pinches in one polygon); the caller separates them.
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// region = ((({} op_0 L_0) op_1 L_1) ...), op_i = union when add[i], else difference.
std::vector<std::vector<std::vector<Vec2>>> boolean_of_loops(const std::vector<std::vector<Vec2>>& loops,
                                                             const std::vector<bool>& add);

// One part of a region: the union of `add` minus the union of `remove`.
struct RegionPart {
  std::vector<std::vector<Vec2>> add, remove;
};

// region = union of the parts, then minus each loop of `subtract`. Used for CSL components: a
// part is a component (its loops) and its holes.
std::vector<std::vector<std::vector<Vec2>>> union_of_parts(const std::vector<RegionPart>& parts,
                                                           const std::vector<std::vector<Vec2>>& subtract);

}  // namespace ps
