#pragma once
// Local self-intersection test for a triangle mesh whose faces changed: which of a given set of
// faces intersect some other face of the mesh improperly (more than a shared edge or vertex).
// Used by mesh improvement after every refinement and smoothing step, so that only the moved
// part of the mesh is tested (the rest is known to be free of intersections).
//
// Exact predicates (CGAL Epick) on the double coordinates; candidate pairs from
// CGAL::box_intersection_d. Two faces sharing an edge intersect when they are coplanar and
// folded onto each other; two sharing a vertex when an opposite edge meets the other triangle
// (the rules of CGAL::Polygon_mesh_processing::does_self_intersect).
#include <array>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// How candidate pairs are found. kAuto: a uniform grid scanned in parallel when the mesh is large
// and its faces alike in size (mesh improvement's refined meshes), CGAL's sequential box sweep
// otherwise. kSweep: always CGAL's sweep (tests compare the two). The pairs are the same.
enum class BroadPhase { kAuto, kSweep };

// Pairs {q, g} with q in query_faces (indices into faces) and g any face, q != g, that
// intersect improperly; each unordered pair once, as {smaller, larger} index, sorted. faces may
// hold any triangle soup; faces are compared by vertex index, so coincident duplicate vertices
// count as distinct.
std::vector<std::array<int, 2>> intersecting_face_pairs(const std::vector<Vec3>& points,
                                                        const std::vector<Face>& faces,
                                                        const std::vector<int>& query_faces,
                                                        BroadPhase broad_phase = BroadPhase::kAuto);

// Every improperly intersecting pair of faces of the mesh (all faces as queries).
std::vector<std::array<int, 2>> self_intersecting_pairs(const TriMesh& mesh);

}  // namespace ps
