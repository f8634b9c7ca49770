#include "modeling/cotan_weights.h"

#include <cmath>

namespace ps {

double clamped_cot(const Vec3& a, const Vec3& b, const Vec3& c, bool* clamped) {
  const Vec3 u = b - a, v = c - a;
  const double dot = u.dot(v);
  const double cross = u.cross(v).norm();
  // cot = cos/sin = dot/|cross|; clamp when |cross| is too small for a finite, useful value.
  if (!(cross * kMaxCotangent > std::abs(dot))) {
    if (clamped) *clamped = true;
    return dot >= 0.0 ? kMaxCotangent : -kMaxCotangent;
  }
  if (clamped) *clamped = false;
  return dot / cross;
}

std::array<double, 3> mixed_areas(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  const double area = 0.5 * (b - a).cross(c - a).norm();
  std::array<double, 3> out{0.0, 0.0, 0.0};
  if (!(area > 0.0)) return out;
  // Obtuse corner? (dot of the two edges leaving it < 0)
  for (int k = 0; k < 3; ++k) {
    const Vec3& o = p[k];
    const Vec3& q = p[(k + 1) % 3];
    const Vec3& r = p[(k + 2) % 3];
    if ((q - o).dot(r - o) < 0.0) {
      out[static_cast<std::size_t>(k)] = 0.5 * area;
      out[static_cast<std::size_t>((k + 1) % 3)] = 0.25 * area;
      out[static_cast<std::size_t>((k + 2) % 3)] = 0.25 * area;
      return out;
    }
  }
  // Non-obtuse: Voronoi area at corner o = (|oq|^2 cot(r) + |or|^2 cot(q)) / 8.
  for (int k = 0; k < 3; ++k) {
    const Vec3& o = p[k];
    const Vec3& q = p[(k + 1) % 3];
    const Vec3& r = p[(k + 2) % 3];
    const double cot_q = clamped_cot(q, r, o);
    const double cot_r = clamped_cot(r, o, q);
    out[static_cast<std::size_t>(k)] = ((q - o).squaredNorm() * cot_r + (r - o).squaredNorm() * cot_q) / 8.0;
  }
  return out;
}

}  // namespace ps
