#pragma once
// Geometric queries on triangle meshes, through CGAL (exact predicates, AABB trees):
// self-intersection, point-to-surface distance, Hausdorff distance, and the full set of
// guarantees a reconstruction or sculpting result must satisfy.
#include <string>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/mesh_topology.h"

namespace ps {

// True when two non-adjacent triangles intersect, or two adjacent ones overlap beyond their
// shared edge or vertex (CGAL::Polygon_mesh_processing::does_self_intersect, exact predicates).
// Requires a valid index structure; works on any triangle soup.
bool does_self_intersect(const TriMesh& mesh);

// Largest distance from any of `points` to the surface. 0 for no points. A point equal to a
// vertex of some face is at distance 0 exactly (found by lookup: reconstructions keep every curve
// point as a vertex); only the others go through an AABB tree of the faces.
double max_distance_to_surface(const TriMesh& mesh, const std::vector<Vec3>& points);

// Symmetric Hausdorff distance approximated by sampling both surfaces
// (CGAL::Polygon_mesh_processing::approximate_Hausdorff_distance, `samples_per_area_unit`
// chosen so each mesh gets about `samples` points). Returns max(d(a,b), d(b,a)).
double hausdorff_distance(const TriMesh& a, const TriMesh& b, int samples = 20000);

// Every guarantee checked at once (tests assert these; the reconstruct report prints them).
struct MeshGuarantees {
  MeshTopology topology;
  bool self_intersecting = true;
  bool valid() const {
    return topology.closed && topology.manifold() && topology.consistently_oriented &&
           topology.signed_volume > 0.0 && !self_intersecting;
  }
  std::string problem() const {
    if (!topology.problem.empty()) return topology.problem;
    if (self_intersecting) return "the surface intersects itself";
    return {};
  }
};
MeshGuarantees check_guarantees(const TriMesh& mesh);

}  // namespace ps
