#pragma once
// Cotangent weights and mixed Voronoi areas (Meyer et al. 2003, the thesis's [107]) with
// clamping for degenerate triangles. Used by the deformation graphs (edge_graph.h).
//
// Conventions:
//   clamped_cot(a, b, c): cotangent of the angle at corner a of triangle (a, b, c).
//   Near-degenerate angles (|cot| > kMaxCotangent, i.e. below ~0.06 degrees or above
//   ~179.94 degrees) and zero-area triangles give +-kMaxCotangent; `clamped` reports it.
//   mixed_areas(a, b, c): the share of triangle (a, b, c)'s area that belongs to each corner's
//   mixed Voronoi cell: Voronoi areas for non-obtuse triangles, area/2 at an obtuse corner and
//   area/4 at the two others. The three shares sum to the triangle's area.
#include <array>

#include "modeling/mesh.h"

namespace ps {

inline constexpr double kMaxCotangent = 1e3;

double clamped_cot(const Vec3& a, const Vec3& b, const Vec3& c, bool* clamped = nullptr);

std::array<double, 3> mixed_areas(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace ps
