#pragma once
// Surface reconstruction from cross sections (thesis chapter 4 for orthogonal planes, chapter 6
// for planes of any orientation): partition a box twice the size of the points' box into convex
// zones by every plane that holds a section, build one primitive (cylinder / frustum) per section
// per zone, extend end-zone primitives, take their exact union (CGAL corefinement), then refine
// and smooth with the input curves held fixed.
//
// Output: a closed, 2-manifold, outward-oriented triangle mesh without self-intersections that
// contains every input curve point within 1e-6 of the bounding-box diagonal; or a Status naming
// the offending curve when the input breaks a stroke rule.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/mesh_improve.h"
#include "modeling/status.h"

namespace ps {

struct ReconstructOptions {
  bool improve = true;           // refinement + smoothing (4.5.1)
  // Rounds of refinement and smoothing. 4, not the thesis's 10: on the stress unions four end
  // smoother on both figures, on the CSL sets within 2 degrees of mean smallest angle with the
  // RMS dihedral mostly lower, in 30-80% of the time (docs/mesh-improvement.md, "Four rounds by
  // default"). The alpha ramp takes 8 of every 10 rounds.
  int improve_iterations = 4;
  int threads = 0;               // 0: all hardware threads; results are identical for any count
  // Planes in at most three orthogonal directions other than the axes (a tilted stack) go to the
  // grid of chapter 4 in their own frame (aligned_frame.h); false: chapter 6 in the world frame.
  bool rotate_to_planes = true;
  // The grid runs on canonical axes chosen from the box (axes by decreasing extent, each pointing
  // the way the box's centre lies from the origin) and the mesh is mapped back exactly, so any
  // permutation or mirror of the input's axes gives the same mesh, moved, bit for bit, with the
  // improvement too (docs/reconstruction.md). false: the grid in the input's own axes.
  bool canonical_axes = true;
  // Called with a stage name and a fraction in [0, 1]; used to show progress on long runs.
  // The union stage of planes of any orientation reports per zone from the worker threads,
  // one call at a time.
  std::function<void(const std::string& stage, double fraction)> progress;
};

struct StageTimings {
  double validate_ms = 0, partition_ms = 0, primitives_ms = 0, union_ms = 0, stitch_ms = 0,
         improve_ms = 0, total_ms = 0;
  // Within improve_ms (mesh_improve.h's ImproveReport): refinement, smoothing, and the
  // self-intersection checks after each round, summed over the rounds.
  double improve_refine_ms = 0, improve_smooth_ms = 0, improve_check_ms = 0;
};

struct ReconstructReport {
  int zones = 0, empty_zones = 0, end_zones = 0, body_zones = 0;
  int primitives = 0;
  int zones_recomputed = 0;  // zones whose union was computed (not taken from the cache)
  int zones_filled = 0;      // of those, zones filled by six whole-face prisms: their box (zone_box_union.h)
  int zones_stacked = 0;     // of those, straight prisms along one axis united in 2D (zone_stacked_union.h)
  // The planes took at most three orthogonal directions other than the axes, and the grid ran
  // in their frame (aligned_frame.h); the mesh is in world coordinates all the same.
  bool rotated_frame = false;
  int components = 0;
  bool improved = false;
  StageTimings timings;
  std::vector<std::string> warnings;  // e.g. "result has 2 components" (a hint, not a failure)
  // For the improvement step and the app, indexing the returned mesh: per-vertex "lies on an
  // input curve" and the mesh edges lying along input curves (vertex pairs, smaller first).
  std::vector<bool> curve_vertex;
  std::vector<std::array<int, 2>> curve_edges;
};

// === Improvement hook
// improve_mesh() lives in another part of the project; the integrator connects it here. Without
// a hook, improvement is skipped with the warning "mesh improvement unavailable".
using ImproveHook = Result<TriMesh> (*)(const TriMesh&, const std::vector<bool>&,
                                        const std::vector<std::array<int, 2>>&, const ImproveOptions&,
                                        ImproveReport*);
void set_improve_hook(ImproveHook hook);
ImproveHook improve_hook();

// One-shot reconstruction. The bounding box is default_reconstruction_box (zone_partition.h):
// twice the points' box about its centre. The result does not depend on the order of the curves
// or planes, nor on the thread count.
Result<TriMesh> reconstruct(const SectionSet& sections, const ReconstructOptions& options = {},
                            ReconstructReport* report = nullptr);

// Axis planes only: the grid of chapter 4 (cached per zone in progressive updates). Any other
// orientation: the convex zones and frusta of chapter 6 (docs/reconstruction.md).

}  // namespace ps
