#pragma once
// Cross sections, strokes and views shared by the session tests and benches: axis-aligned
// planes, circles on them, circles in the window, a perspective camera.
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"

namespace ps::testing {

// The plane x[axis] = offset.
inline Plane axis_plane(int axis, double offset) {
  Plane p;
  p.normal = Vec3::Unit(axis);
  p.offset = offset;
  return p;
}

// n points of the circle of radius r about the axis, on the plane x[axis] = offset.
inline std::vector<Vec3> circle(int axis, double offset, double r, int n = 40) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    Vec3 p;
    p[axis] = offset;
    p[(axis + 1) % 3] = r * std::cos(a);
    p[(axis + 2) % 3] = r * std::sin(a);
    pts.push_back(p);
  }
  return pts;
}

// n window points (pixels) of the circle of radius r about c, counter-clockwise on screen.
inline std::vector<Vec2> window_circle(const Vec2& c, double r, int n) {
  std::vector<Vec2> pts;
  for (int i = 0; i < n; ++i) pts.push_back(c + r * Vec2(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n)));
  return pts;
}

// A perspective camera at `eye` looking at `target` (fov 40 degrees, width x height pixels).
inline Camera look_at(const Vec3& eye, const Vec3& target, const Vec3& up, int width, int height) {
  Camera c;
  std::tie(c.eye, c.target, c.up) = std::tie(eye, target, up);
  std::tie(c.width, c.height) = std::pair(width, height);
  return c;
}

}  // namespace ps::testing
