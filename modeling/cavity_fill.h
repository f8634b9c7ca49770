#pragma once
// Empty pockets enclosed between primitives, filled (thesis 4.2 and 6.3: the model is the union
// of the zones' primitives; where the primitives of a zone leave a closed gap between them, the
// union's boundary includes that gap's boundary, a shell oriented inward).
//
// Such a shell is a separate face component of negative signed volume. If none of its vertices
// lies on an input curve, no section asked for it: it is an artefact of how the primitives meet
// (seen on the CSL armadillo, 0.0004% of the volume, and in oblique stress cases whose zone
// union was taken at once), invisible from outside but a separate "part" in the component count
// and a void for anyone printing or meshing the solid. A cavity that the sections do ask for
// (inside a ring of nested curves) has the hole curves on it and is kept.
//
// Shape conventions: `on_curve` is indexed by vertex (shorter means "not on a curve"); the mesh
// is closed and outward oriented (the caller checked), so each component is a closed shell.
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// Removes the inward shells without a curve vertex and the vertices only they used (then
// canonical order, modeling/zone_stitch.h canonicalize). Returns the number of shells removed
// (0: mesh unchanged) and their total volume (positive) in `volume`.
int fill_curveless_cavities(TriMesh& mesh, const std::vector<bool>& on_curve, double& volume);

}  // namespace ps
