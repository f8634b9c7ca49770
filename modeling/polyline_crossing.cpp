#include "modeling/polyline_crossing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace ps {

namespace {

// === Exact arithmetic helpers (error-free transformations)
// two_sum: s + e == a + b exactly, |e| <= ulp(s)/2.
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}
// two_diff: d + e == a - b exactly.
inline void two_diff(double a, double b, double& d, double& e) { two_sum(a, -b, d, e); }
// two_product: p + e == a * b exactly (fma computes the rounding error exactly).
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

// Sign of an exact sum of doubles. The terms are accumulated into a nonoverlapping expansion
// (components in increasing magnitude, zeros dropped); its sign is that of its largest
// component.
int exact_sign_of_sum(const double* terms, int count) {
  std::array<double, 40> e{};
  int len = 0;
  for (int t = 0; t < count; ++t) {
    double q = terms[t];
    int out = 0;
    for (int i = 0; i < len; ++i) {
      double s, err;
      two_sum(q, e[static_cast<std::size_t>(i)], s, err);
      q = s;
      if (err != 0.0) e[static_cast<std::size_t>(out++)] = err;
    }
    if (q != 0.0) e[static_cast<std::size_t>(out++)] = q;
    len = out;
  }
  if (len == 0) return 0;
  return e[static_cast<std::size_t>(len - 1)] > 0.0 ? 1 : -1;
}

int orient2d_exact(const Vec2& a, const Vec2& b, const Vec2& c) {
  double d1h, d1l, d2h, d2l, d3h, d3l, d4h, d4l;
  two_diff(b.x(), a.x(), d1h, d1l);
  two_diff(c.y(), a.y(), d2h, d2l);
  two_diff(b.y(), a.y(), d3h, d3l);
  two_diff(c.x(), a.x(), d4h, d4l);
  // (d1h + d1l)(d2h + d2l) - (d3h + d3l)(d4h + d4l), every product split exactly.
  std::array<double, 16> t{};
  two_product(d1h, d2h, t[0], t[1]);
  two_product(d1h, d2l, t[2], t[3]);
  two_product(d1l, d2h, t[4], t[5]);
  two_product(d1l, d2l, t[6], t[7]);
  two_product(-d3h, d4h, t[8], t[9]);
  two_product(-d3h, d4l, t[10], t[11]);
  two_product(-d3l, d4h, t[12], t[13]);
  two_product(-d3l, d4l, t[14], t[15]);
  return exact_sign_of_sum(t.data(), 16);
}

// === Segment bookkeeping
struct Seg {
  Vec2 a, b;
  int poly = 0;  // which polyline (0 or 1)
  int k = 0;     // segment index within its polyline (after duplicate removal)
};

struct Hit {
  bool found = false;
  int key_segment = std::numeric_limits<int>::max();
  double key_t = std::numeric_limits<double>::infinity();
  Vec2 point = Vec2::Zero();
};

std::vector<Vec2> drop_consecutive_duplicates(const std::vector<Vec2>& pts, bool closed) {
  std::vector<Vec2> out;
  out.reserve(pts.size());
  for (const auto& p : pts)
    if (out.empty() || p != out.back()) out.push_back(p);
  if (closed)
    while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

double param_on(const Seg& s, const Vec2& p) {
  const Vec2 r = s.b - s.a;
  const double rr = r.squaredNorm();
  return rr > 0.0 ? std::clamp((p - s.a).dot(r) / rr, 0.0, 1.0) : 0.0;
}

// A point shared by two intersecting segments (rounded construction).
Vec2 intersection_point(const Seg& s, const Seg& u) {
  const Vec2 r = s.b - s.a, q = u.b - u.a;
  const double denom = r.x() * q.y() - r.y() * q.x();
  if (denom != 0.0 && orient2d(s.a, s.b, u.a) * orient2d(s.a, s.b, u.b) != 0) {
    const Vec2 w = u.a - s.a;
    const double t = std::clamp((w.x() * q.y() - w.y() * q.x()) / denom, 0.0, 1.0);
    return s.a + t * r;
  }
  if (denom != 0.0) {
    // One endpoint of u lies on s (or the other way round).
    if (orient2d(s.a, s.b, u.a) == 0 && segments_intersect(s.a, s.b, u.a, u.a)) return u.a;
    if (orient2d(s.a, s.b, u.b) == 0 && segments_intersect(s.a, s.b, u.b, u.b)) return u.b;
    if (segments_intersect(u.a, u.b, s.a, s.a)) return s.a;
    return s.b;
  }
  // Collinear overlap: the overlap point nearest the start of u.
  Vec2 best = u.a;
  double best_t = std::numeric_limits<double>::infinity();
  for (const Vec2& c : {s.a, s.b, u.a, u.b}) {
    if (segments_intersect(s.a, s.b, c, c) && segments_intersect(u.a, u.b, c, c)) {
      const double t = param_on(u, c);
      if (t < best_t) best_t = t, best = c;
    }
  }
  return best;
}

// Collinear points a, c on the same side of v (a != v, c != v): consecutive segments a-v, v-c
// fold back onto each other.
bool folds_back(const Vec2& a, const Vec2& v, const Vec2& c) {
  if (orient2d(a, v, c) != 0) return false;
  if (a.x() != v.x()) return (a.x() > v.x()) == (c.x() > v.x());
  return (a.y() > v.y()) == (c.y() > v.y());
}

// Uniform-grid broad phase over the segments; `visit(i, j)` gets every pair whose bounding
// boxes share a cell, exactly once.
template <class Visit>
void for_each_candidate_pair(const std::vector<Seg>& segs, Visit&& visit) {
  const std::size_t n = segs.size();
  if (n < 2) return;
  Vec2 lo = segs[0].a, hi = segs[0].a;
  double total = 0.0;
  for (const auto& s : segs) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    total += (s.b - s.a).norm();
  }
  const Vec2 ext = hi - lo;
  const double extent = std::max(ext.x(), ext.y());
  if (!(extent > 0.0)) {  // all points coincide: every pair is a candidate
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) visit(i, j);
    return;
  }
  // Cell size: the mean segment length, but no more than ~4n cells in all.
  const double dn = static_cast<double>(n);
  double h = std::max(total / dn, extent / 2048.0);
  h = std::max(h, std::sqrt(std::max(ext.x(), h) * std::max(ext.y(), h) / (4.0 * dn)));
  const int nx = std::max(1, static_cast<int>(std::ceil(ext.x() / h)) + 1);
  const int ny = std::max(1, static_cast<int>(std::ceil(ext.y() / h)) + 1);
  auto cell_of = [&](double v, double origin, int count) {
    const int c = static_cast<int>(std::floor((v - origin) / h));
    return std::clamp(c, 0, count - 1);
  };
  struct Range {
    int x0, x1, y0, y1;
  };
  std::vector<Range> ranges(n);
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = segs[i];
    Range r{cell_of(std::min(s.a.x(), s.b.x()), lo.x(), nx), cell_of(std::max(s.a.x(), s.b.x()), lo.x(), nx),
            cell_of(std::min(s.a.y(), s.b.y()), lo.y(), ny), cell_of(std::max(s.a.y(), s.b.y()), lo.y(), ny)};
    ranges[i] = r;
    for (int y = r.y0; y <= r.y1; ++y)
      for (int x = r.x0; x <= r.x1; ++x)
        cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)]
            .push_back(static_cast<int>(i));
  }
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      const auto& c = cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(x)];
      for (std::size_t p = 0; p < c.size(); ++p) {
        for (std::size_t q = p + 1; q < c.size(); ++q) {
          const auto i = static_cast<std::size_t>(c[p]), j = static_cast<std::size_t>(c[q]);
          // Visit the pair only in the first cell both boxes share.
          if (std::max(ranges[i].x0, ranges[j].x0) != x || std::max(ranges[i].y0, ranges[j].y0) != y) continue;
          visit(std::min(i, j), std::max(i, j));
        }
      }
    }
  }
}

std::vector<Seg> make_segments(const std::vector<Vec2>& pts, bool closed, int poly) {
  std::vector<Seg> segs;
  const std::size_t n = pts.size();
  if (n < 2) return segs;
  const std::size_t count = closed ? n : n - 1;
  for (std::size_t k = 0; k < count; ++k)
    segs.push_back(Seg{pts[k], pts[(k + 1) % n], poly, static_cast<int>(k)});
  return segs;
}

std::optional<Vec2> self_crossing(const std::vector<Vec2>& input, bool closed) {
  const std::vector<Vec2> pts = drop_consecutive_duplicates(input, closed);
  const std::vector<Seg> segs = make_segments(pts, closed, 0);
  const int m = static_cast<int>(segs.size());
  if (m < 2) return std::nullopt;
  Hit best;
  auto consider = [&](const Seg& later, const Vec2& p) {
    const double t = param_on(later, p);
    if (later.k < best.key_segment || (later.k == best.key_segment && t < best.key_t)) {
      best.found = true;
      best.key_segment = later.k;
      best.key_t = t;
      best.point = p;
    }
  };
  for_each_candidate_pair(segs, [&](std::size_t i, std::size_t j) {
    const Seg& s = segs[i];
    const Seg& u = segs[j];  // j > i: u is drawn later
    const bool next = u.k == s.k + 1;
    const bool wrap = closed && s.k == 0 && u.k == m - 1;
    if (next && wrap) {
      // Two segments joined at both ends (a closed polyline of two points): a fold.
      consider(u, u.a);
      return;
    }
    if (next) {
      if (folds_back(s.a, s.b, u.b)) consider(u, u.a);
      return;
    }
    if (wrap) {
      if (folds_back(u.a, u.b, s.b)) consider(u, u.b);
      return;
    }
    if (segments_intersect(s.a, s.b, u.a, u.b)) consider(u, intersection_point(s, u));
  });
  if (!best.found) return std::nullopt;
  return best.point;
}

}  // namespace

// === Public predicates
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y());
  const double right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  // Forward error bound of the floating-point evaluation, (3 + 16 eps) eps (|left| + |right|).
  const double bound = 3.3306690738754716e-16 * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d_exact(a, b, c);
}

bool segments_intersect(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  const int o1 = orient2d(p0, p1, q0), o2 = orient2d(p0, p1, q1);
  const int o3 = orient2d(q0, q1, p0), o4 = orient2d(q0, q1, p1);
  if (o1 * o2 > 0 || o3 * o4 > 0) return false;
  if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return true;
  // All four points collinear: the segments meet when their boxes overlap (exact comparisons).
  return std::max(std::min(p0.x(), p1.x()), std::min(q0.x(), q1.x())) <=
             std::min(std::max(p0.x(), p1.x()), std::max(q0.x(), q1.x())) &&
         std::max(std::min(p0.y(), p1.y()), std::min(q0.y(), q1.y())) <=
             std::min(std::max(p0.y(), p1.y()), std::max(q0.y(), q1.y()));
}

std::optional<Vec2> first_self_crossing(const std::vector<Vec2>& closed_polyline) {
  return self_crossing(closed_polyline, true);
}

std::optional<Vec2> first_self_crossing_open(const std::vector<Vec2>& open_polyline) {
  return self_crossing(open_polyline, false);
}

std::optional<Vec2> first_crossing_between(const std::vector<Vec2>& closed_a,
                                           const std::vector<Vec2>& closed_b) {
  const auto pa = drop_consecutive_duplicates(closed_a, true);
  const auto pb = drop_consecutive_duplicates(closed_b, true);
  if (pa.empty() || pb.empty()) return std::nullopt;
  std::vector<Seg> segs = make_segments(pa, true, 0);
  const auto sb = make_segments(pb, true, 1);
  // A single point counts as a zero-length segment so that a point on the other curve is found.
  if (segs.empty()) segs.push_back(Seg{pa[0], pa[0], 0, 0});
  if (sb.empty())
    segs.push_back(Seg{pb[0], pb[0], 1, 0});
  else
    segs.insert(segs.end(), sb.begin(), sb.end());
  Hit best;
  for_each_candidate_pair(segs, [&](std::size_t i, std::size_t j) {
    const Seg& s = segs[i];
    const Seg& u = segs[j];
    if (s.poly == u.poly) return;
    const Seg& on_a = s.poly == 0 ? s : u;
    const Seg& on_b = s.poly == 0 ? u : s;
    if (!segments_intersect(on_a.a, on_a.b, on_b.a, on_b.b)) return;
    const Vec2 p = intersection_point(on_b, on_a);
    const double t = param_on(on_a, p);
    if (on_a.k < best.key_segment || (on_a.k == best.key_segment && t < best.key_t)) {
      best.found = true;
      best.key_segment = on_a.k;
      best.key_t = t;
      best.point = p;
    }
  });
  if (!best.found) return std::nullopt;
  return best.point;
}

}  // namespace ps
