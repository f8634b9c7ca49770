#pragma once
// Ear-clipping triangulation of one simple polygon (no holes), given in 3D and triangulated in
// its best-fit (Newell) plane. Used to split n-gons read from mesh files. Written by hand because
// CGAL 5.5 has no soup-level polygon triangulation and this needs no kernel types.
//
// Returns triangles as index triples into `corners`, oriented like the polygon.
// Never fails: degenerate input falls back to a fan.
#include <array>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

std::vector<std::array<int, 3>> triangulate_polygon_3d(const std::vector<Vec3>& corners);

// Same, for a polygon already in 2D; counter-clockwise or clockwise.
std::vector<std::array<int, 3>> triangulate_polygon_2d(const std::vector<Vec2>& corners);

// Newell's normal of a closed polygon: twice its vector area (unnormalised; zero for a
// degenerate polygon).
Vec3 newell_normal(const std::vector<Vec3>& corners);

// Twice the signed area (positive for counter-clockwise).
double signed_area_2d(const std::vector<Vec2>& poly);

// Even-odd (crossing number) test: is `p` inside the closed polygon `poly`? Meant for points off
// the boundary; a point on it may go either way.
bool point_in_polygon_2d(const Vec2& p, const std::vector<Vec2>& poly);

}  // namespace ps
