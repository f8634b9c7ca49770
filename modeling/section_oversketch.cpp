#include "modeling/section_oversketch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "modeling/polyline_crossing.h"

namespace ps {
namespace {

// The open polyline from `from` forward along `closed` to `to` (both hit points included) and
// the indices of the curve points it passes.
struct Arc {
  std::vector<Vec2> points;
  std::vector<std::size_t> vertices;
  double length = 0.0;
};

Arc forward_arc(const std::vector<Vec2>& closed, const ClosedCurveHit& from, const ClosedCurveHit& to) {
  const std::size_t n = closed.size();
  std::size_t count = (to.segment + n - from.segment) % n;
  if (count == 0 && to.t < from.t) count = n;  // same segment, behind: once around
  Arc a;
  a.points.push_back(from.point);
  for (std::size_t k = 1; k <= count; ++k) {
    const std::size_t v = (from.segment + k) % n;
    a.vertices.push_back(v);
    a.points.push_back(closed[v]);
  }
  a.points.push_back(to.point);
  for (std::size_t i = 1; i < a.points.size(); ++i) a.length += (a.points[i] - a.points[i - 1]).norm();
  return a;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double distance_to_open(const std::vector<Vec2>& poly, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < poly.size(); ++i) best = std::min(best, distance_to_segment(p, poly[i], poly[i + 1]));
  return best;
}

// Mean distance from the stroke's interior points (its midpoint for a two-point stroke) to `arc`.
double mean_distance(const std::vector<Vec2>& stroke, const std::vector<Vec2>& arc) {
  if (stroke.size() == 2) return distance_to_open(arc, 0.5 * (stroke[0] + stroke[1]));
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < stroke.size(); ++i) sum += distance_to_open(arc, stroke[i]);
  return sum / static_cast<double>(stroke.size() - 2);
}

// The point at arc-length fraction `s` in [0, 1] along an open polyline of length `length`.
Vec2 at_fraction(const std::vector<Vec2>& poly, double length, double s) {
  double left = s * length;
  for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
    const double l = (poly[i + 1] - poly[i]).norm();
    if (left <= l && l > 0.0) return poly[i] + (left / l) * (poly[i + 1] - poly[i]);
    left -= l;
  }
  return poly.back();
}

double polyline_length_2d(const std::vector<Vec2>& poly) {
  double l = 0.0;
  for (std::size_t i = 1; i < poly.size(); ++i) l += (poly[i] - poly[i - 1]).norm();
  return l;
}

Status check_points(const std::vector<Vec2>& pts, std::size_t min, const char* what) {
  if (pts.size() < min)
    return Status::error(std::string(what) + " has " + std::to_string(pts.size()) + " point(s); it needs at least " +
                         std::to_string(min));
  for (const Vec2& p : pts)
    if (!p.allFinite()) return Status::error(std::string(what) + " has a non-finite point");
  return Status::ok();
}

}  // namespace

ClosedCurveHit nearest_on_closed(const std::vector<Vec2>& closed, const Vec2& p) {
  ClosedCurveHit best;
  best.distance = std::numeric_limits<double>::infinity();
  const std::size_t n = closed.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = closed[i], b = closed[(i + 1) % n];
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const Vec2 q = a + t * ab;
    const double d = (q - p).norm();
    if (d < best.distance) best = ClosedCurveHit{i, t, q, d};
  }
  return best;
}

Result<Splice> splice_open_stroke(const std::vector<Vec2>& closed, const std::vector<Vec2>& open, double snap,
                                  const SpliceBlend& blend) {
  using R = Result<Splice>;
  if (auto st = check_points(closed, 3, "the section"); !st) return st;
  if (auto st = check_points(open, 2, "the stroke"); !st) return st;
  if (!(snap > 0.0) || !std::isfinite(snap)) return R::error("the snapping distance must be positive and finite");
  if (!(blend.stroke_weight >= 0.0 && blend.stroke_weight <= 1.0)) return R::error("the stroke's weight must lie in [0, 1]");
  const ClosedCurveHit h0 = nearest_on_closed(closed, open.front());
  const ClosedCurveHit h1 = nearest_on_closed(closed, open.back());
  if (h0.distance > snap || h1.distance > snap)
    return R::error(std::string(h0.distance > snap ? "the stroke's start" : "the stroke's end") +
                    " is too far from the section to join it (" + std::to_string(h0.distance > snap ? h0.distance : h1.distance) +
                    ", at most " + std::to_string(snap) + ")");
  if ((h0.point - h1.point).norm() < snap)
    return R::error("both ends of the stroke meet the section at the same place: draw across the part to replace");
  // The two parts of the curve between the ends: `a` runs from the start's point forward to the
  // end's, `b` from the end's forward to the start's.
  const Arc a = forward_arc(closed, h0, h1);
  const Arc b = forward_arc(closed, h1, h0);
  const double da = mean_distance(open, a.points), db = mean_distance(open, b.points);
  const bool replace_a = da < db || (da == db && a.length <= b.length);
  const Arc& kept = replace_a ? b : a;
  Splice out;
  out.kept_points = kept.vertices.size();
  out.kept_length = kept.length;
  out.replaced_length = replace_a ? a.length : b.length;
  // === The new part, from the start's end to the end's: the stroke blended with the replaced
  // part run in the same direction, matched by arc length.
  std::vector<Vec2> old = replace_a ? a.points : std::vector<Vec2>(b.points.rbegin(), b.points.rend());
  const double old_length = replace_a ? a.length : b.length, stroke_length = polyline_length_2d(open);
  const double w = blend.stroke_weight;
  std::vector<Vec2> fresh;
  double travelled = 0.0;
  for (std::size_t i = 0; i < open.size(); ++i) {
    if (i > 0) travelled += (open[i] - open[i - 1]).norm();
    const double s01 = stroke_length > 0.0 ? travelled / stroke_length : 0.0;
    fresh.push_back(w * open[i] + (1.0 - w) * at_fraction(old, old_length, s01));
  }
  // With the stroke weighted fully the ends are moved onto the curve; otherwise they keep their
  // blend and the step to the curve fades over the kept points next to them.
  if (blend.fade.empty()) {
    fresh.front() = h0.point;
    fresh.back() = h1.point;
  }
  const Vec2 step_start = fresh.front() - h0.point, step_end = fresh.back() - h1.point;
  // === The kept points, in order from the start's side (`a` kept) or the end's (`b` kept).
  std::vector<Vec2> pts;
  for (std::size_t v : kept.vertices) pts.push_back(closed[v]);
  const Vec2 step_first = replace_a ? step_end : step_start, step_last = replace_a ? step_start : step_end;
  for (std::size_t k = 0; k < blend.fade.size() && k < pts.size(); ++k) {
    pts[k] += blend.fade[k] * step_first;
    pts[pts.size() - 1 - k] += blend.fade[k] * step_last;
  }
  out.kept_points = pts.size() > 2 * blend.fade.size() ? pts.size() - 2 * blend.fade.size() : 0;
  // The kept points end at the start's side (b kept: the new part runs forward) or the end's (a kept: backward).
  if (replace_a) {
    pts.insert(pts.end(), fresh.begin(), fresh.end());
  } else {
    pts.insert(pts.end(), fresh.rbegin(), fresh.rend());
  }
  // A curve vertex right at an end (hit at t = 0 or 1) would repeat it: drop points within
  // 1e-6 of the curve's length of the one before (cyclically); the checks downstream refuse
  // consecutive points closer than 1e-9 of the diagonal.
  const double total = a.length + b.length;
  const double eps = 1e-6 * std::max(total, std::numeric_limits<double>::min());
  for (const Vec2& p : pts)
    if (out.curve.empty() || (p - out.curve.back()).norm() > eps) out.curve.push_back(p);
  while (out.curve.size() > 1 && (out.curve.back() - out.curve.front()).norm() <= eps) out.curve.pop_back();
  if (out.curve.size() < 3) return R::error("the result has fewer than 3 points");
  if (const auto x = first_self_crossing(out.curve))
    return R::error("the edited section would cross itself near (" + std::to_string(x->x()) + ", " +
                    std::to_string(x->y()) + ")");
  return out;
}

std::optional<std::vector<Vec2>> mirror_about_chord(const std::vector<Vec2>& open) {
  if (open.size() < 3) return std::nullopt;
  for (const Vec2& p : open)
    if (!p.allFinite()) return std::nullopt;
  const Vec2 a = open.front(), chord = open.back() - a;
  const double len = chord.norm();
  if (!(len > 0.0)) return std::nullopt;
  const Vec2 dir = chord / len, normal(-dir.y(), dir.x());
  int side = 0;
  for (std::size_t i = 1; i + 1 < open.size(); ++i) {
    const double d = (open[i] - a).dot(normal);
    const int s = d > 1e-9 * len ? 1 : d < -1e-9 * len ? -1 : 0;
    if (s == 0 || (side != 0 && s != side)) return std::nullopt;
    side = s;
  }
  std::vector<Vec2> closed = open;
  for (std::size_t i = open.size() - 1; i-- > 1;) {
    const Vec2 q = open[i] - a;
    closed.push_back(a + q.dot(dir) * dir - q.dot(normal) * normal);
  }
  return closed;
}

}  // namespace ps
