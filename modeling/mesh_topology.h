#pragma once
// Combinatorial facts about a triangle mesh: closedness, edge- and vertex-manifoldness,
// consistent orientation, components, Euler characteristic and genus, signed volume.
// Plain C++ (no CGAL) so it compiles fast and runs everywhere, including in fuzz targets.
#include <string>

#include "modeling/mesh.h"

namespace ps {

struct MeshTopology {
  bool closed = false;            // every edge has exactly two incident faces
  bool edge_manifold = false;     // no edge has more than two incident faces
  bool vertex_manifold = false;   // the faces around every vertex form one fan
  bool consistently_oriented = false;  // each directed edge appears at most once
  int boundary_edges = 0;
  int nonmanifold_edges = 0;
  int nonmanifold_vertices = 0;
  int degenerate_faces = 0;       // repeated vertex index or zero area (relative 1e-14)
  int isolated_vertices = 0;
  int components = 0;             // face-connected components
  int euler_characteristic = 0;   // V - E + F over referenced vertices
  int genus = -1;                 // for a closed, orientable, manifold mesh: sum over components
  double signed_volume = 0.0;     // > 0 for outward orientation
  double area = 0.0;
  bool manifold() const { return edge_manifold && vertex_manifold; }
  // The first problem, in words, or empty.
  std::string problem;
};

MeshTopology mesh_topology(const TriMesh& mesh);

// Face-connected component id per face; returns the number of components.
int face_components(const TriMesh& mesh, std::vector<int>& component_of_face);

// Signed volume (> 0 for outward orientation), from the tetrahedra joining each face to
// `origin`. The result does not depend on the origin in exact arithmetic; in doubles, an origin
// near the mesh (one of its vertices, say) keeps the sum from cancelling far from zero.
double signed_volume(const TriMesh& mesh, const Vec3& origin = Vec3::Zero());

// Indices of the faces with at least one vertex v where mark[v] != 0, in face order (the
// query faces of intersecting_face_pairs after some vertices moved or merged).
std::vector<int> faces_touching(const TriMesh& mesh, const std::vector<char>& mark);

}  // namespace ps
