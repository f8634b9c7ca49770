#pragma once
// A compact halfedge (corner-table) mesh for local remeshing of closed, oriented, manifold
// triangle meshes: centroid splits, edge flips, one-ring walks, per-edge constraint flags.
//
// Hand-written rather than CGAL::Surface_mesh because mesh improvement runs after every pen
// stroke: flat arrays indexed by face keep splits and flips allocation-free, and this header
// costs nothing to compile.
//
// Shapes and conventions:
//   faces:    #F triangles (counter-clockwise seen from outside), as in TriMesh.
//   halfedge h = 3 f + k runs from faces[f][k] to faces[f][(k + 1) % 3]; next(h) stays in f.
//   twin:     #3F, the opposite halfedge (always valid: the mesh is closed).
//   out:      #V, one outgoing halfedge per vertex.
//   constrained: #3F flags, equal on a halfedge and its twin (curve edges: never flipped).
// Vertex indices never change: splits append vertices, flips only rewire faces.
#include <cstdint>
#include <string>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

class HalfedgeMesh {
 public:
  // Builds the structure; refuses a mesh that is not closed, edge- and vertex-manifold and
  // consistently oriented, or that has an out-of-range index, naming the first problem.
  static Result<HalfedgeMesh> build(const TriMesh& mesh);

  TriMesh to_trimesh() const;

  int num_vertices() const { return static_cast<int>(positions.size()); }
  int num_faces() const { return static_cast<int>(faces.size()); }
  int num_halfedges() const { return 3 * num_faces(); }

  static int face_of(int h) { return h / 3; }
  static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
  int twin(int h) const { return twins[static_cast<std::size_t>(h)]; }
  int source(int h) const { return faces[static_cast<std::size_t>(h / 3)][static_cast<std::size_t>(h % 3)]; }
  int target(int h) const { return source(next(h)); }
  const Vec3& position(int v) const { return positions[static_cast<std::size_t>(v)]; }
  bool is_constrained(int h) const { return constrained[static_cast<std::size_t>(h)] != 0; }

  // Halfedge from a to b, or -1.
  int find_halfedge(int a, int b) const;
  // Calls f(h) for every outgoing halfedge of v (counter-clockwise seen from outside).
  template <class F>
  void for_each_outgoing(int v, F&& f) const {
    const int start = out[static_cast<std::size_t>(v)];
    int h = start;
    do {
      f(h);
      h = twin(prev(h));
    } while (h != start);
  }
  int valence(int v) const;

  // Marks the edge a-b constrained; false when it is not an edge.
  bool constrain_edge(int a, int b);

  // Splits face f at point p (a new vertex, returned) into three faces: f keeps the first,
  // two faces are appended. Constraint flags of the three outer edges are kept.
  int split_face(int f, const Vec3& p);

  // True when flipping the edge of h keeps the mesh manifold: the edge is not constrained and
  // the opposite vertices are distinct and not yet joined by an edge.
  bool can_flip(int h) const;
  // Replaces edge (a, b) of faces (a, b, c), (b, a, d) by (c, d). Caller checks can_flip.
  // Afterwards h runs from d to c (h's face is (c, a, d)), twin(h) from c to d.
  void flip(int h);

  // Area-weighted (unnormalised, twice the area) normal of face f.
  Vec3 face_normal(int f) const;

  std::vector<Vec3> positions;
  std::vector<Face> faces;
  std::vector<int> twins;
  std::vector<int> out;
  std::vector<std::uint8_t> constrained;
};

}  // namespace ps
