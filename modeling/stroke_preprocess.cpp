#include "modeling/stroke_preprocess.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

#include "modeling/polyline_crossing.h"

namespace ps {

namespace {

std::string fmt(const char* format, double a) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

// === Generic polyline helpers (any fixed-size Eigen vector)
template <class V>
double length_of(const std::vector<V>& pts, bool closed) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  if (closed && pts.size() > 1) len += (pts.front() - pts.back()).norm();
  return len;
}

template <class V>
std::vector<V> filter_impl(const std::vector<V>& pts, double min_spacing) {
  std::vector<V> out;
  if (pts.empty()) return out;
  out.push_back(pts.front());
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - out.back()).norm() >= min_spacing) out.push_back(pts[i]);
  // Keep the pen-up sample: the stroke ends where the user lifted the pen.
  const V& last = pts.back();
  if (pts.size() > 1 && out.back() != last) {
    if (out.size() > 1 && (last - out.back()).norm() < 0.5 * min_spacing)
      out.back() = last;
    else
      out.push_back(last);
  }
  return out;
}

template <class V>
std::vector<V> resample_impl(const std::vector<V>& pts, int count, bool closed) {
  const double total = length_of(pts, closed);
  if (count < 2 || pts.size() < 2 || !(total > 0.0)) return pts;
  const std::size_t n = pts.size();
  const std::size_t segs = closed ? n : n - 1;
  const double step = closed ? total / count : total / (count - 1);
  std::vector<V> out;
  out.reserve(static_cast<std::size_t>(count));
  out.push_back(pts.front());
  // "Travel" along the polyline; place a point every `step` of arc length.
  std::size_t seg = 0;
  double seg_start = 0.0;  // arc length at the start of segment `seg`
  for (int k = 1; k < count; ++k) {
    if (!closed && k == count - 1) {
      out.push_back(pts.back());
      break;
    }
    const double s = step * k;
    double seg_len = (pts[(seg + 1) % n] - pts[seg]).norm();
    while (seg + 1 < segs && seg_start + seg_len < s) {
      seg_start += seg_len;
      ++seg;
      seg_len = (pts[(seg + 1) % n] - pts[seg]).norm();
    }
    const double t = seg_len > 0.0 ? std::clamp((s - seg_start) / seg_len, 0.0, 1.0) : 0.0;
    out.push_back(pts[seg] + t * (pts[(seg + 1) % n] - pts[seg]));
  }
  return out;
}

template <class V>
std::vector<V> smooth_impl(const std::vector<V>& pts, bool closed, int passes) {
  std::vector<V> cur = pts;
  const std::size_t n = cur.size();
  if (n < 3) return cur;
  std::vector<V> next(n);
  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!closed && (i == 0 || i == n - 1)) {
        next[i] = cur[i];
        continue;
      }
      const V& prev = cur[(i + n - 1) % n];
      const V& succ = cur[(i + 1) % n];
      next[i] = (prev + 4.0 * cur[i] + succ) / 6.0;  // Eq. 3.1
    }
    std::swap(cur, next);
  }
  return cur;
}

double signed_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % n];
    a += (u.x() - p[0].x()) * (v.y() - p[0].y()) - (v.x() - p[0].x()) * (u.y() - p[0].y());
  }
  return 0.5 * a;
}

// An overshooting loop: the tail (last 20% of the length) crosses the head (first 20%). Returns
// the loop between the two crossing segments, starting at the crossing point, or nothing.
std::optional<std::vector<Vec2>> cut_overshoot(const std::vector<Vec2>& pts) {
  const std::size_t n = pts.size();
  if (n < 4) return std::nullopt;
  const double total = length_of(pts, false);
  std::vector<double> arc(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double head = 0.2 * total, tail = 0.8 * total;
  // Earliest tail segment j (in drawing order) that meets a head segment i < j - 1.
  for (std::size_t j = 1; j + 1 < n; ++j) {
    if (arc[j + 1] < tail) continue;
    for (std::size_t i = 0; i + 1 < j && arc[i] <= head; ++i) {
      if (!segments_intersect(pts[i], pts[i + 1], pts[j], pts[j + 1])) continue;
      // Crossing point on segment i (rounded construction; the loop is re-checked later).
      const Vec2 r = pts[i + 1] - pts[i], q = pts[j + 1] - pts[j];
      const double denom = r.x() * q.y() - r.y() * q.x();
      Vec2 x = pts[j];
      if (denom != 0.0) {
        const Vec2 w = pts[j] - pts[i];
        x = pts[i] + std::clamp((w.x() * q.y() - w.y() * q.x()) / denom, 0.0, 1.0) * r;
      }
      std::vector<Vec2> loop;
      loop.push_back(x);
      for (std::size_t k = i + 1; k <= j; ++k)
        if (pts[k] != loop.back()) loop.push_back(pts[k]);
      if (loop.size() < 3) return std::nullopt;
      return loop;
    }
  }
  return std::nullopt;
}

}  // namespace

// === Polyline helpers
double polyline_length(const std::vector<Vec2>& p, bool closed) { return length_of(p, closed); }
double polyline_length(const std::vector<Vec3>& p, bool closed) { return length_of(p, closed); }
std::vector<Vec2> filter_close_points(const std::vector<Vec2>& p, double s) { return filter_impl(p, s); }
std::vector<Vec3> filter_close_points(const std::vector<Vec3>& p, double s) { return filter_impl(p, s); }
std::vector<Vec2> resample_polyline(const std::vector<Vec2>& p, int c, bool closed) {
  return resample_impl(p, c, closed);
}
std::vector<Vec3> resample_polyline(const std::vector<Vec3>& p, int c, bool closed) {
  return resample_impl(p, c, closed);
}
std::vector<Vec2> smooth_polyline(const std::vector<Vec2>& p, bool closed, int passes) {
  return smooth_impl(p, closed, passes);
}
std::vector<Vec3> smooth_polyline(const std::vector<Vec3>& p, bool closed, int passes) {
  return smooth_impl(p, closed, passes);
}

bool is_closed_stroke(const std::vector<Vec2>& pts, const StrokeParams& params) {
  if (pts.size() < 3) return false;
  const double len = length_of(pts, false);
  const double mean_segment = len / static_cast<double>(pts.size() - 1);
  const double gap = (pts.back() - pts.front()).norm();
  return gap <= params.closed_gap_factor * mean_segment && gap <= params.closed_gap_max_fraction * len;
}

// === Preprocessing pipeline
Result<PreprocessedStroke> preprocess_stroke(const std::vector<Vec2>& raw, const StrokeParams& params) {
  if (raw.empty()) return Result<PreprocessedStroke>::error("stroke is empty");
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (!std::isfinite(raw[i].x()) || !std::isfinite(raw[i].y()))
      return Result<PreprocessedStroke>::error("stroke sample " + std::to_string(i) + " is not finite (" +
                                               std::to_string(raw[i].x()) + ", " + std::to_string(raw[i].y()) +
                                               ")");
  if (!(params.min_spacing_px >= 0.0) || !(params.target_spacing_px > 0.0) || params.max_points < 3 ||
      params.fixed_count < 0 || (params.fixed_count > 0 && params.fixed_count < 3))
    return Result<PreprocessedStroke>::error(
        "stroke parameters invalid: need min_spacing_px >= 0, target_spacing_px > 0, max_points >= 3, "
        "fixed_count 0 or >= 3");

  // === Degeneracy: length relative to the viewport
  double min_length = params.min_length_px;
  if (params.viewport_px.x() > 0.0 && params.viewport_px.y() > 0.0)
    min_length = std::max(min_length, params.min_length_fraction * params.viewport_px.norm());
  const double raw_length = length_of(raw, false);
  if (raw_length < min_length)
    return Result<PreprocessedStroke>::error("stroke is too short (" + fmt("%.1f", raw_length) +
                                             " px; strokes need at least " + fmt("%.1f", min_length) + " px)");

  // === Step 2: filtering
  std::vector<Vec2> pts = filter_impl(raw, params.min_spacing_px);
  if (pts.size() < 3)
    return Result<PreprocessedStroke>::error(
        "stroke has only " + std::to_string(pts.size()) + " points after dropping samples closer than " +
        fmt("%.1f", params.min_spacing_px) + " px to their predecessor (needs 3); draw a longer stroke");

  // === Step 3: open or closed
  bool closed = false;
  if (params.force_closed && !params.force_open) {
    closed = true;
  } else if (!params.force_open) {
    if (auto loop = cut_overshoot(pts)) {
      pts = std::move(*loop);
      closed = true;
    } else {
      closed = is_closed_stroke(pts, params);
    }
  }
  if (closed) {
    // Close exactly: drop end points that duplicate the start; resampling bridges the gap.
    while (pts.size() > 3 && (pts.back() - pts.front()).norm() < params.min_spacing_px) pts.pop_back();
    if (pts.size() < 3)
      return Result<PreprocessedStroke>::error("closed stroke has fewer than 3 distinct points");
  }
  const double length = length_of(pts, closed);
  // Zero area, for simple loops only: a self-crossing loop (a figure eight has zero signed area)
  // is left to first_self_crossing, whose message says where it crosses.
  if (closed && !first_self_crossing(pts)) {
    const double area = std::abs(signed_area(pts));
    if (area < params.min_area_ratio * length * length)
      return Result<PreprocessedStroke>::error("closed stroke encloses no area (" + fmt("%.1f", area) +
                                               " px^2 for a length of " + fmt("%.1f", length) +
                                               " px); it doubles back on itself");
  }

  // === Step 4: resampling
  int count = params.fixed_count;
  if (count == 0) {
    const int lo = std::min(closed ? params.min_points_closed : params.min_points, params.max_points);
    const double wanted = std::round(length / params.target_spacing_px);
    count = static_cast<int>(std::clamp(wanted, static_cast<double>(std::max(lo, 3)),
                                        static_cast<double>(params.max_points)));
  }
  std::vector<Vec2> res = resample_impl(pts, count, closed);

  // === Step 5: smoothing (Eq. 3.1)
  res = smooth_impl(res, closed, std::max(0, params.smoothing_passes));

  PreprocessedStroke out;
  out.points = std::move(res);
  out.closed = closed;
  out.length = length;
  out.raw_count = static_cast<int>(raw.size());
  out.filtered_count = static_cast<int>(pts.size());
  return out;
}

// === Lifting
Result<std::vector<Vec3>> lift_stroke(const std::vector<Vec2>& window_points, const Camera& camera,
                                      const Plane& plane) {
  using R = Result<std::vector<Vec3>>;
  if (camera.width <= 0 || camera.height <= 0) return R::error("camera viewport has no area");
  if (!camera.eye.allFinite() || !camera.target.allFinite() || !camera.up.allFinite() ||
      (camera.target - camera.eye).norm() == 0.0 ||
      (camera.target - camera.eye).cross(camera.up).norm() == 0.0)
    return R::error("camera is degenerate (eye, target and up must be finite and not collinear)");
  if (!plane.normal.allFinite() || !std::isfinite(plane.offset) || std::abs(plane.normal.norm() - 1.0) > 1e-9)
    return R::error("plane is invalid (normal must be a finite unit vector)");
  const Vec3 forward = (camera.target - camera.eye).normalized();
  std::vector<Vec3> out;
  out.reserve(window_points.size());
  for (std::size_t i = 0; i < window_points.size(); ++i) {
    const Vec2& w = window_points[i];
    auto where = [&] { return "stroke point " + std::to_string(i) + " at " + format_window_point(w); };
    if (!w.allFinite()) return R::error("stroke point " + std::to_string(i) + " is not finite");
    const Ray r = camera.ray(w.x(), w.y());
    const double denom = plane.normal.dot(r.direction);
    if (std::abs(denom) < 1e-9) return R::error(where() + ": its view ray runs parallel to the plane (the plane is seen edge-on)");
    const double t = (plane.offset - plane.normal.dot(r.origin)) / denom;
    if (!std::isfinite(t)) return R::error(where() + ": its view ray does not meet the plane");
    if (t < 0.0) return R::error(where() + ": the plane is behind the eye there");
    const double depth = t * r.direction.dot(forward);
    if (depth > camera.far_plane)
      return R::error(where() + ": the view ray meets the plane beyond the far plane (depth " + fmt("%.3g", depth) +
                      ", far " + fmt("%.3g", camera.far_plane) + "); the plane is seen too obliquely there");
    out.push_back(plane.project(r.origin + t * r.direction));
  }
  return out;
}

Result<LiftedStroke> prepare_plane_stroke(const std::vector<Vec2>& window_points, const Camera& camera,
                                          const Plane& plane, const StrokeParams& params) {
  StrokeParams p = params;
  if (p.viewport_px.x() <= 0.0 || p.viewport_px.y() <= 0.0)
    p.viewport_px = Vec2(static_cast<double>(camera.width), static_cast<double>(camera.height));
  auto pre = preprocess_stroke(window_points, p);
  if (!pre) return pre.status();
  if (pre->closed)
    if (auto x = first_self_crossing(pre->points))
      return Result<LiftedStroke>::error("stroke crosses itself at " + format_window_point(*x));
  auto lifted = lift_stroke(pre->points, camera, plane);
  if (!lifted) return lifted.status();
  LiftedStroke out;
  out.window_points = std::move(pre->points);
  out.points = std::move(*lifted);
  out.closed = pre->closed;
  return out;
}

Status check_window_points(const std::vector<Vec2>& s, std::size_t min_points, const char* what) {
  if (s.size() < min_points)
    return Status::error(std::string(what) + " has " + std::to_string(s.size()) + " point(s); it needs at least " +
                         std::to_string(min_points));
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!s[i].allFinite()) return Status::error(std::string(what) + " point " + std::to_string(i) + " is not finite");
  return Status::ok();
}

std::string format_window_point(const Vec2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.1f, %.1f)", p.x(), p.y());
  return buf;
}

}  // namespace ps
