#pragma once
// A closed solid swept from a window-space polygon along the camera's viewing rays: the tool
// solid of the sculpting operations that act "through the screen" (cutting, tunnelling; thesis
// 3.2.2). Written by hand: it is a prism with planar caps whose side walls follow the rays, which
// no library builds from a camera.
//
// polygon_px: a simple closed polygon in window pixels (x right, y down; either orientation;
// the closing edge is implicit). Every corner is lifted along its ray to the depths near_depth and
// far_depth, measured along the viewing direction from the eye (perspective) or from the image
// plane (orthographic): the caps are planar, orthogonal to the viewing direction.
// Result: closed, 2-manifold, outward-oriented. Refused: fewer than 3 corners, a non-finite
// corner, zero area, a self-crossing polygon, 0 < near_depth < far_depth violated.
#include <vector>

#include "modeling/camera.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

Result<TriMesh> extrude_window_polygon(const std::vector<Vec2>& polygon_px, const Camera& camera,
                                       double near_depth, double far_depth);

// Depth range of `mesh` along the camera's viewing direction: [min, max] of (p - eye) . forward.
struct DepthRange {
  double min = 0.0, max = 0.0;
};
DepthRange depth_range(const TriMesh& mesh, const Camera& camera);

}  // namespace ps
