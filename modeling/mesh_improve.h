#pragma once
// Mesh improvement after reconstruction (thesis 4.5.1): alternate Liepa-style refinement
// (centroid splits driven by length attributes propagated ring by ring from the curve vertices,
// alpha = sqrt(2), plus edge relaxation) and smoothing (Eq. 4.3: p' = p + tau N + eps T with
// tau = A^2/150, eps = 0.5 and the tangential term), for `iterations` rounds.
//
// Fixed vertices (those on input curves) never move; fixed edges (curve edges) are never flipped
// or split. Every step is checked for self-intersections and stepped back if it introduced any.
//
// Reading of the thesis (details and measurements in docs/mesh-improvement.md):
//   - sigma at a curve vertex is the mean length of its incident *curve* edges (all incident
//     edges when it has none), so triangles near a curve match the curve's sampling;
//   - tau N of Eq. 4.3 is a curvature-driven normal move with a stable explicit step (see
//     modeling/mesh_smooth.h), T the tangential part of the umbrella vector;
//   - refinement steps are checked (locally, exact predicates) for self-intersections and redone
//     without the offending flips; smoothing moves that cause one are undone per vertex.
//
// Vertex indices: output vertex i < mesh.num_vertices() is input vertex i (fixed ones at
// bit-identical positions); vertices created by splits are appended after them. So the caller's
// curve-vertex indices and fixed-edge pairs stay valid for the output.
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
  // Smoothing: explicit steps of Eq. 4.3 per round, and the normal move's step (lambda, see
  // modeling/mesh_smooth.h); curvature_evening selects the fourth-order normal flow (a sphere
  // stays a sphere) instead of mean-curvature flow (shrinks towards a minimal surface).
  int smoothing_steps = 6;
  double normal_step = 0.4;
  bool curvature_evening = true;
  // Smoothing: a move towards a facing sheet (thin parts, narrow gaps) nearer than 2.5 times
  // the move is shortened to 0.4 of that distance before the check (smoothing_clearance.h).
  // kAuto: from the first round whose check finds more than 1 in 12 moved faces crossing
  // another face (that round's moves are then limited and checked again); kAlways: every round;
  // kOff: never. The limit costs 20-70 ms a round on 50-130k faces, and on models that are thin
  // only in places it left a worse mesh than undoing the few crossing moves.
  enum class ClearanceLimit { kOff, kAuto, kAlways };
  ClearanceLimit clearance_limit = ClearanceLimit::kAuto;
  // Smoothing: the curvature-evening move is limited to the size of the mean-curvature move
  // (SmoothOptions::limit_evening). kAuto: from the first round whose smoothing steps undid
  // fold moves for more than 1 in 20 vertex-steps, that round smoothed again with the limit, and
  // in every later round (rates measured per vertex and step: 0 on
  // clean staircases, 0.02-0.12 on hand_ok, about 0.1 on Skull-20, 0.2-0.4 on oblique stress
  // unions); kAlways: every round; kOff: never. On the rough inputs the limit gives smoother,
  // smaller meshes, 3x faster (docs/mesh-improvement.md, "Limiting the evening flow on rough
  // meshes"); on clean ones it would double the profile error, so it waits for the sign.
  enum class EveningLimit { kOff, kAuto, kAlways };
  EveningLimit evening_limit = EveningLimit::kAuto;
  // Refinement: alpha grows linearly to its value over the first ramp_rounds rounds (0: no ramp).
  int ramp_rounds = 8;
  // Refinement: no splits beyond this many faces (a guard against a tiny curve spacing).
  int max_faces = 400000;
  // Refinement: length attributes are floored at this fraction of the diagonal of the curve
  // vertices' bounding box (0: Liepa's attributes unchanged). Densely sampled curves (1000
  // points on a circle) would otherwise make the whole surface as dense as the curves: 400k
  // faces and a minute of work for two circles. Triangles next to such curves become fans
  // from the curve's short edges. See docs/mesh-improvement.md for the measurements.
  double min_length_fraction = 1.0 / 120.0;
  // Edges whose faces meet at a sharper angle are not flipped (a flip there changes the shape).
  double max_flip_normal_angle_deg = 45.0;
  // Give up after this round (0-based; -1: never) when the mesh is then worse than the input on
  // both smoothness figures, the test improve_mesh applies to the final result: the input comes
  // back (report->kept_input, report->gave_up_after_round). Measured per round on the CSL sets,
  // hand_ok and the oblique stress unions: every result that ends better than its input has its
  // mean smallest angle above the input's by round 1, while one that ends worse (stress seed 738)
  // was worse on both from round 1 and spent 14 of its 15 s in the rounds after. Round 0 is too
  // early: hand_ok is worse on both after it and ends much better.
  int give_up_after_round = 1;
};

// Triangle and smoothness figures (for tests, benchmarks and reports).
struct MeshQuality {
  double min_angle_deg = 0;       // smallest triangle angle
  double mean_min_angle_deg = 0;  // mean over faces of each face's smallest angle
  double max_aspect = 0;          // largest circumradius / (2 inradius); 1 for equilateral
  double mean_aspect = 0;
  double max_dihedral_deg = 0;    // largest angle between the normals of adjacent faces
  double rms_dihedral_deg = 0;    // root mean square of that angle, weighted by edge length
  // Shares of the edges with two faces (by count, not length) whose faces meet at more than 60
  // and 90 degrees. The RMS dihedral is dominated by long edges: a union of frusta has long flat
  // walls and scores low on it although a quarter of its edges are creases over 60 degrees.
  double sharp_edge_share = 0;
  double folded_edge_share = 0;
};

struct ImproveReport {
  int splits = 0, flips = 0;
  int smoothing_rollbacks = 0;   // vertex moves undone (a face turned over, or an intersection)
  int clearance_limits = 0;      // smoothing moves shortened by the clearance limit
  int evening_limited_from = -1;  // first round smoothed with the evening limit (-1: none)
  int crossing_rollbacks = 0;    // of smoothing_rollbacks: moves undone because faces crossed
  double ms = 0;                 // wall time of the whole call
  int refinement_rollbacks = 0;  // refinements undone after an intersection (redone with flips
                                 // locked near it; after a second one the round stays unrefined)
  int faces_in = 0, faces_out = 0;
  double refine_ms = 0, smooth_ms = 0, check_ms = 0;  // wall time per stage, summed over rounds
  // The input came back unchanged because the improved mesh was worse on both smoothness
  // figures: a smaller mean smallest angle and a larger RMS dihedral (see improve_mesh).
  bool kept_input = false;
  int gave_up_after_round = -1;  // the round after which that was decided early (-1: at the end)
  MeshQuality quality_in, quality_out;  // of the input and of the improved mesh (before that choice)
};

// fixed_vertex: #V flags (true: on an input curve). fixed_edges: vertex pairs, either order.
// The input must be closed and manifold; the output is too, with the same topology.
// Endpoints of fixed edges are treated as fixed even when not flagged.
// When the improved mesh has both a smaller mean smallest angle and a larger RMS dihedral than
// the input, the input is returned instead, unchanged (report->kept_input): seen on unions made
// of needles where flips cannot follow the splits (docs/mesh-improvement.md, "When the
// improvement makes it worse").
Result<TriMesh> improve_mesh(const TriMesh& mesh, const std::vector<bool>& fixed_vertex,
                             const std::vector<std::array<int, 2>>& fixed_edges,
                             const ImproveOptions& options = {}, ImproveReport* report = nullptr);

// Requires valid indices; edges with other than two faces are skipped in the dihedral figures.
MeshQuality mesh_quality(const TriMesh& mesh);

}  // namespace ps
