#pragma once
// What the sketching tool shows on the selected plane before the user draws (thesis 3.2.1,
// 3.3.2): the points where sections on other planes cross it (stroke rule 4: a new section on
// the plane must pass through them) and the preview model's own cross section there (the
// calculated section, "rendered semi-transparently to provide the user reference").
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct CrossingHint {
  Vec3 point = Vec3::Zero();
  // A curve on the plane already passes through the point (within 1e-6 of the bounding-box
  // diagonal): rule 4 is met there. Open points are where a new curve must pass.
  bool met = false;
};

// required_crossings (modeling/curve_sewing.h) of `sections` with `plane`, each marked met or
// open against the curves lying on `plane` itself (a plane of the set coinciding with it, up
// to orientation, within 1e-9 relative). Pass the sewn curves: after sewing the crossings of
// both sides agree, so a met point is met exactly.
std::vector<CrossingHint> crossing_hints(const SectionSet& sections, const Plane& plane);

// Index of the plane of `set` that coincides with `plane` (same unit normal up to sign and the
// matching offset, within `rel_tol` relative to the offsets), or -1.
int find_plane(const SectionSet& set, const Plane& plane, double rel_tol = 1e-12);

// The model's cross section by `plane`: its closed curves, through the points where the plane
// cuts mesh edges, thinned to at least 1/120 of the bounding-box diagonal apart (loops left
// with fewer than 3 points are dropped); none when the plane misses the model.
// A vertex on the plane counts as above it, so a cut through vertices still chains into
// closed curves. Written for the interactive loop, not with modeling/mesh_slicer.h (CGAL's
// slicer with resampling and exact checks: about 20 times slower on a 60k-face model): one
// pass over the faces and a hash map of the cut edges. Refused, naming the reason, for an
// empty model, a degenerate plane, or a model that is open or non-manifold where the plane
// cuts it. Loop order and orientation carry no meaning.
Result<std::vector<std::vector<Vec3>>> model_section(const TriMesh& model, const Plane& plane);

}  // namespace ps
