#pragma once
// Union of the primitives of one zone (thesis Eq. 4.2, the term in parentheses), through CGAL's
// corefinement (Polygon_mesh_processing::corefine_and_compute_union, exact predicates). This is
// the only translation unit including CGAL's corefinement. Zones are independent; the caller
// runs them in parallel.
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// Union of closed, outward-oriented solids, taken one by one in the given order (the result's
// combinatorics depend on that order, so callers pass a canonical order). One solid is returned
// unchanged; none gives an empty mesh.
Result<TriMesh> union_solids(const std::vector<TriMesh>& solids);

}  // namespace ps
