#pragma once
// Distance from a point to a triangle, by the Voronoi regions of its corners, edges and face (the
// classic closest-point case analysis, Ericson, Real-Time Collision Detection 5.1.5). Hand-written
// and header-only: CGAL's squared_distance(Point_3, Triangle_3) would bring CGAL's kernel headers
// into the light translation units that need it (topology editing, the smoothing clearance).
// A degenerate triangle (corners on a line) gives the distance to its nearest corner or edge.
#include <algorithm>
#include <cmath>

#include "modeling/mesh.h"

namespace ps {

inline double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  const double sum = va + vb + vc;
  if (!(std::abs(sum) > 0)) return std::min({ap.squaredNorm(), bp.squaredNorm(), cp.squaredNorm()});
  const double s = 1.0 / sum;
  return (p - (a + vb * s * ab + vc * s * ac)).squaredNorm();
}

inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::sqrt(point_triangle_distance2(p, a, b, c));
}

}  // namespace ps
