#pragma once
// Slicing an implicit solid by a plane: the closed curves where a scalar field crosses zero.
//
// Used to synthesize demo stroke logs whose cross sections are consistent by construction
// (stroke rule 4, thesis 3.3.2): every curve is a slice of the same solid, so curves on two
// planes cross the planes' common line at the same points.
//
// Method: marching squares on a uniform grid over a square window of the plane (saddle cells
// resolved by the field at the cell centre), then every contour vertex is moved onto the zero
// set by bisection along its grid edge, so vertices lie on the true slice to ~1e-15 relative.
// Hand-written (no library in the dependency set slices implicit functions on a plane); it is
// only used to make test and demo input.
#include <functional>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/status.h"

namespace ps {

// Negative inside the solid, positive outside, continuous across the zero set.
using ScalarField = std::function<double(const Vec3&)>;

struct SliceWindow {
  Vec3 center = Vec3::Zero();  // projected onto the plane before use
  double half_extent = 1.0;    // the window is a square of side 2 * half_extent
  int resolution = 500;        // grid cells per side
};

// Closed curves (last point not repeated) of {field == 0} on `plane`, ordered by enclosed area,
// largest first (so an outer curve comes before the holes it contains). Fails when the solid
// reaches the window's border.
Result<std::vector<std::vector<Vec3>>> slice_implicit(const ScalarField& field, const Plane& plane,
                                                      const SliceWindow& window);

}  // namespace ps
