#pragma once
// Internal to the two CGAL translation units of the zone union (mesh_boolean.cpp, which defines
// these, and nef_union.cpp): the exact surface mesh of a snapped solid and the rounding of an
// exact mesh back to doubles, so that both unions snap and round identically (a point shared by
// two zones must round the same way in both). Not for other files: it pulls in CGAL's kernel.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <vector>

#include "modeling/mesh.h"
#include "modeling/zone_union.h"

namespace ps::exact {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;

// The solid with every tagged vertex on the exact intersection of its planes.
SurfaceMesh snapped_surface_mesh(const SnappedSolid& s, const std::vector<Plane>& planes);

// Empty, invalid, open, or with a face whose corners are exactly collinear (after snapping):
// what corefinement must not be given. Names the problem, or returns an empty string.
std::string unusable_operand(const SurfaceMesh& sm);

// The double nearest the exact point (from the exact value, not from however far the lazy
// number was evaluated).
Vec3 rounded_point(const K::Point_3& p);

// Doubles rounded from the exact values (garbage collected first); triangles only.
TriMesh rounded(SurfaceMesh& sm);

}  // namespace ps::exact
