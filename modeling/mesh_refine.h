#pragma once
// Liepa-style refinement (Liepa 2003, thesis 4.5.1): centroid splits driven by per-vertex length
// attributes spread from the curve vertices, and Delaunay-like edge relaxation.
//
// Length attribute sigma (#V): at a curve (fixed) vertex, the mean length of its incident curve
// (constrained) edges, or of all its incident edges when it has no curve edge; then ring by
// ring inward, each vertex gets the mean sigma of its neighbours in earlier rings. Vertices of a
// component without curve vertices get that component's mean edge length.
//
// A face (i, j, k) with centroid c and sigma_c = (sigma_i + sigma_j + sigma_k) / 3 is split at c
// when alpha |v_m - c| > sigma_c and alpha |v_m - c| > sigma_m for m = i, j, k. An edge is
// relaxed (flipped) when the two angles opposite to it sum to more than pi, it is not a curve
// edge, the flip keeps the mesh manifold, and the flip does not fold the surface (see
// RefineOptions::max_flip_normal_angle_deg).
#include <cstdint>
#include <vector>

#include "modeling/halfedge_mesh.h"

namespace ps {

struct RefineOptions {
  double alpha = 1.4142135623730951;  // sqrt(2), Liepa's density control
  int max_passes = 40;                // split + relax passes (each pass splits every eligible face)
  int max_faces = 400000;             // no split beyond this many faces
  // Floor on every length attribute (0: none). Curves sampled far more densely than the shape
  // needs would otherwise make the whole surface that dense (see ImproveOptions).
  double min_length = 0.0;
  // Only edges whose two faces' normals differ by at most this angle are flipped: a flip across
  // a sharper crease would cut or fill the crease (a shape change, not a retriangulation).
  double max_flip_normal_angle_deg = 45.0;
  // A face is not split while one of its corners has reached its valence limit: max_valence
  // edges, or twice its starting valence when that is more (a fan centre of a triangulated cap
  // starts with many). Starting valences: (*base_valence)[v] for v < base_valence->size(), or
  // the mesh's own at the call when base_valence is null (mesh improvement passes its input's,
  // so the limit does not grow from round to round); vertices made by splits start at 0. Splits
  // add an edge at each corner and relaxation normally takes them away again; where it cannot
  // (flips refused at a crease or a pinch, or locked after a self-intersection), repeated splits
  // only made needles. 0: no limit. Measured: docs/mesh-improvement.md.
  int max_valence = 32;
  const std::vector<int>* base_valence = nullptr;
  // Look at every face in every pass instead of only the faces rewritten since the last look
  // (and those the valence limit refused). The splits are the same either way; tests compare.
  bool rescan_every_face = false;
};

struct RefineStats {
  int splits = 0, flips = 0, passes = 0;
  int valence_refusals = 0;  // split tests refused by the valence limit (a face counts once per pass)
  int sliver_refusals = 0;   // split tests refused because the face is a sliver (same count)
};

// Sigma per vertex (#V); fixed is #V flags (nonzero: curve vertex).
std::vector<double> length_attributes(const HalfedgeMesh& mesh, const std::vector<std::uint8_t>& fixed);

// Regions where no edge may be flipped (used to redo a refinement whose flips made a
// self-intersection): an edge is locked when the box of its quad meets one of the boxes.
struct FlipLock {
  bool all = false;
  std::vector<Box3> regions;
  bool locks(const Box3& quad) const;
};

// Refines in place. fixed grows with the vertex count (new vertices are free). With `changed`,
// it comes back with one flag per face of the result: 1 where the face came from a flip or a
// split (a centroid split keeps its face's plane only up to rounding, which on needles was
// enough to cross a neighbour), 0 where the face is a face of the input, untouched. Slivers
// (twice the area below 1e-10 times the longest edge squared) are never split.
RefineStats refine_mesh(HalfedgeMesh& mesh, std::vector<std::uint8_t>& fixed,
                        const FlipLock& lock = {}, const RefineOptions& options = {},
                        std::vector<std::uint8_t>* changed = nullptr);

// Relaxes every edge until no flip applies (or a cap of 8 flips per edge is reached); returns
// the number of flips. Exposed for tests.
int relax_all_edges(HalfedgeMesh& mesh, const FlipLock& lock = {}, const RefineOptions& options = {});

}  // namespace ps
