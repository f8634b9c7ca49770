#pragma once
// Smoothing by a scratch-out stroke (thesis 3.2.2): the region of the surface under the stroke is
// smoothed by a few steps of constrained smoothing (mesh_smooth.h, Eq. 4.3 with the mean-curvature
// flow), every vertex outside the region fixed, so the change stays local.
//
// Region: the vertices that face the camera and whose window projection lies within `radius_px`
// of the stroke polyline (radius_px <= 0: a fifth of the stroke's larger extent, at least 6 px).
// Visibility is approximated by facing: a front-facing vertex hidden behind another part of the
// model can be selected.
// After smoothing the surface must still be free of self-intersections; otherwise fewer steps are
// tried, and when even one step intersects the request is refused. Refused too: an empty or
// non-finite stroke, a stroke over no vertex, a mesh that is not a manifold triangle mesh.
#include <vector>

#include "modeling/camera.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct ScratchSmoothOptions {
  int steps = 8;             // smoothing steps (halved on a self-intersection)
  double radius_px = 0.0;    // see above
  double normal_step = 0.5;  // lambda of the mean-curvature flow
  double tangential_step = 0.5;
};

struct ScratchSmoothReport {
  int region_vertices = 0;
  int steps = 0;  // steps actually applied
};

Result<TriMesh> smooth_by_scratch(const TriMesh& model, const std::vector<Vec2>& stroke_px, const Camera& camera,
                                  const ScratchSmoothOptions& options = {}, ScratchSmoothReport* report = nullptr);

}  // namespace ps
