#pragma once
// Mesh improvement after reconstruction (thesis 4.5.1): alternate Liepa-style refinement
// (centroid splits driven by length attributes propagated ring by ring from the curve vertices,
// alpha = sqrt(2), plus edge relaxation) and smoothing (Eq. 4.3: p' = p + tau N + eps T with
// tau = A^2/150, eps = 0.5 and the tangential term), for `iterations` rounds.
//
// Fixed vertices (those on input curves) never move; fixed edges (curve edges) are never flipped
// or split. Every step is checked for self-intersections and stepped back if it introduced any.
#include <array>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct ImproveOptions {
  int iterations = 10;
  double alpha = 1.4142135623730951;  // sqrt(2), as in Liepa
  double tangential_step = 0.5;       // epsilon of Eq. 4.3
  bool check_self_intersections = true;
};

struct ImproveReport {
  int splits = 0, flips = 0, smoothing_rollbacks = 0;
  double ms = 0;
};

// fixed_vertex: #V flags (true: on an input curve). fixed_edges: vertex pairs, either order.
// The input must be closed and manifold; the output is too, with the same topology.
Result<TriMesh> improve_mesh(const TriMesh& mesh, const std::vector<bool>& fixed_vertex,
                             const std::vector<std::array<int, 2>>& fixed_edges,
                             const ImproveOptions& options = {}, ImproveReport* report = nullptr);

}  // namespace ps
