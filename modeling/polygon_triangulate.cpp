#include "modeling/polygon_triangulate.h"

#include <cmath>
#include <list>

namespace ps {

double signed_area_2d(const std::vector<Vec2>& poly) {
  double a = 0.0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a;
}

bool point_in_polygon_2d(const Vec2& p, const std::vector<Vec2>& poly) {
  bool in = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) in = !in;
    }
  }
  return in;
}

namespace {

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool point_in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = cross2(a, b, p), d2 = cross2(b, c, p), d3 = cross2(c, a, p);
  return d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0;
}

std::vector<std::array<int, 3>> fan(std::size_t n) {
  std::vector<std::array<int, 3>> out;
  for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({0, static_cast<int>(i), static_cast<int>(i + 1)});
  return out;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon_2d(const std::vector<Vec2>& corners) {
  const std::size_t n = corners.size();
  if (n < 3) return {};
  if (n == 3) return {{0, 1, 2}};
  const bool ccw = signed_area_2d(corners) > 0.0;
  // Work on a counter-clockwise copy; map triangles back to the input's orientation.
  std::vector<Vec2> p = corners;
  if (!ccw)
    for (auto& q : p) q.y() = -q.y();
  std::list<int> ring;
  for (std::size_t i = 0; i < n; ++i) ring.push_back(static_cast<int>(i));
  std::vector<std::array<int, 3>> out;
  std::size_t guard = 0;
  auto it = ring.begin();
  while (ring.size() > 3 && guard < n * n) {
    ++guard;
    auto prev = it == ring.begin() ? std::prev(ring.end()) : std::prev(it);
    auto next = std::next(it) == ring.end() ? ring.begin() : std::next(it);
    const Vec2 &a = p[static_cast<std::size_t>(*prev)], &b = p[static_cast<std::size_t>(*it)],
               &c = p[static_cast<std::size_t>(*next)];
    bool ear = cross2(a, b, c) > 0.0;
    if (ear) {
      for (int k : ring) {
        if (k == *prev || k == *it || k == *next) continue;
        if (point_in_triangle(p[static_cast<std::size_t>(k)], a, b, c)) {
          ear = false;
          break;
        }
      }
    }
    if (ear) {
      out.push_back({*prev, *it, *next});
      it = ring.erase(it);
      if (it == ring.end()) it = ring.begin();
      guard = 0;
    } else {
      it = next;
    }
  }
  if (ring.size() == 3) {
    auto a = ring.begin();
    out.push_back({*a, *std::next(a), *std::next(a, 2)});
  } else {
    return fan(n);  // degenerate (self-overlapping) input
  }
  return out;
}

Vec3 newell_normal(const std::vector<Vec3>& corners) {
  const std::size_t n = corners.size();
  Vec3 normal = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = corners[i];
    const Vec3& b = corners[(i + 1) % n];
    normal += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                   (a.x() - b.x()) * (a.y() + b.y()));
  }
  return normal;
}

std::vector<std::array<int, 3>> triangulate_polygon_3d(const std::vector<Vec3>& corners) {
  const std::size_t n = corners.size();
  if (n < 3) return {};
  Vec3 normal = newell_normal(corners);
  if (!(normal.norm() > 0.0)) return fan(n);
  normal.normalize();
  const Vec3 helper = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = normal.cross(helper).normalized();
  const Vec3 v = normal.cross(u);
  std::vector<Vec2> p;
  p.reserve(n);
  for (const auto& c : corners) p.emplace_back(c.dot(u), c.dot(v));
  // With u x v = normal, the polygon is counter-clockwise in (u, v), so triangles keep its
  // orientation.
  return triangulate_polygon_2d(p);
}

}  // namespace ps
