#include "modeling/stroke_classify.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "modeling/polygon_triangulate.h"
#include "modeling/polyline_crossing.h"

namespace ps {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt(const char* format, double a) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

double turn_deg(const Vec2& a, const Vec2& b) {
  const double c = a.x() * b.x() + a.y() * b.y();
  const double s = a.x() * b.y() - a.y() * b.x();
  return std::abs(std::atan2(s, c)) * 180.0 / kPi;
}

}  // namespace

std::string_view stroke_class_name(StrokeClass c) {
  switch (c) {
    case StrokeClass::kClosed: return "closed";
    case StrokeClass::kScratchOut: return "scratch-out";
    case StrokeClass::kOpenCutting: return "open-cutting";
    case StrokeClass::kOpenDeformation: return "open-deformation";
    case StrokeClass::kOpenMiss: return "open-miss";
  }
  return "unknown";
}

bool parse_stroke_class(std::string_view name, StrokeClass& out) {
  for (StrokeClass c : {StrokeClass::kClosed, StrokeClass::kScratchOut, StrokeClass::kOpenCutting,
                        StrokeClass::kOpenDeformation, StrokeClass::kOpenMiss})
    if (stroke_class_name(c) == name) {
      out = c;
      return true;
    }
  return false;
}

Result<StrokeClassification> classify_stroke(const std::vector<Vec2>& raw, const InsideModelFn& inside_model,
                                             const StrokeClassifyParams& params) {
  using R = Result<StrokeClassification>;
  // === Input checks
  if (raw.empty()) return R::error("stroke is empty");
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (!raw[i].allFinite())
      return R::error("stroke sample " + std::to_string(i) + " is not finite (" + fmt("%g", raw[i].x()) + ", " +
                      fmt("%g", raw[i].y()) + ")");
  if (raw.size() < 2) return R::error("stroke has only 1 sample; a stroke needs at least 2");
  auto finite_at_least = [](double v, double lo) { return std::isfinite(v) && v >= lo; };
  if (!finite_at_least(params.fine_spacing_px, 0.0) || !(params.silhouette_step_px > 0.0) ||
      !finite_at_least(params.min_leg_px, 0.5) || !finite_at_least(params.min_leg_fraction, 0.0) ||
      !(params.min_overdraw > 0.0) || !(params.reversal_turn_deg > 0.0 && params.reversal_turn_deg < 180.0) ||
      params.min_reversals < 1 || std::isnan(params.min_length_px))
    return R::error(
        "stroke classification parameters invalid: need finite fine_spacing_px >= 0, min_leg_px >= 0.5, "
        "min_leg_fraction >= 0, silhouette_step_px > 0, min_overdraw > 0, 0 < reversal_turn_deg < 180, "
        "min_reversals >= 1");

  StrokeClassification out;
  StrokeFeatures& f = out.features;
  f.raw_count = static_cast<int>(raw.size());
  f.length_px = polyline_length(raw, false);
  if (f.length_px < params.min_length_px)
    return R::error("stroke is too short (" + fmt("%.1f", f.length_px) + " px; strokes need at least " +
                    fmt("%.1f", params.min_length_px) + " px)");
  Vec2 lo = raw.front(), hi = raw.front();
  for (const Vec2& p : raw) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  f.bbox_diagonal_px = (hi - lo).norm();
  f.end_gap_px = (raw.back() - raw.front()).norm();
  f.overdraw = f.bbox_diagonal_px > 0.0 ? f.length_px / f.bbox_diagonal_px : 0.0;

  // === Closedness, exactly as for cross sections (overshoot cut included)
  StrokeParams cp = params.closedness;
  cp.force_open = cp.force_closed = false;
  if (auto pre = preprocess_stroke(raw, cp); pre && pre->closed) {
    f.closed = true;
    f.closed_simple = !first_self_crossing(pre->points);
    const double len = polyline_length(pre->points, true);
    f.closed_area_ratio = len > 0.0 ? 0.5 * std::abs(signed_area_2d(pre->points)) / (len * len) : 0.0;
    Vec2 plo = pre->points.front(), phi = plo;
    for (const Vec2& p : pre->points) plo = plo.cwiseMin(p), phi = phi.cwiseMax(p);
    f.closed_overdraw = (phi - plo).norm() > 0.0 ? len / (phi - plo).norm() : 0.0;
  }
  // A closed stroke that doubles back on itself is refused by preprocess_stroke ("encloses no
  // area"); it is not closed here either, and the shape analysis below decides.

  // === Shape: turns measured over a window of arc length, reversals as runs of sharp turns
  const std::vector<Vec2> fine = filter_close_points(raw, params.fine_spacing_px);
  f.window_px = std::max(params.min_leg_px, params.min_leg_fraction * f.bbox_diagonal_px);
  {
    const double fine_len = polyline_length(fine, false);
    const double h = std::max(0.5, f.window_px / 8.0);
    const int count = static_cast<int>(std::clamp(std::ceil(fine_len / h) + 1.0, 2.0, 20000.0));
    const std::vector<Vec2> even = resample_polyline(fine, count, false);
    const double step = count > 1 ? fine_len / (count - 1) : 0.0;
    const std::size_t k = step > 0.0 ? static_cast<std::size_t>(std::ceil(f.window_px / step)) : even.size();
    bool in_run = false;
    for (std::size_t i = k; i + k < even.size(); ++i) {
      const double t = turn_deg(even[i] - even[i - k], even[i + k] - even[i]);
      f.max_turn_deg = std::max(f.max_turn_deg, t);
      if (!in_run && t > params.reversal_turn_deg) {
        ++f.reversals;
        in_run = true;
      } else if (in_run && t < params.reversal_turn_deg - 30.0) {
        in_run = false;
      }
    }
  }
  const bool scratch = f.reversals >= params.min_reversals && f.overdraw >= params.min_overdraw;

  // === Silhouette, probed along the fine polyline
  if (inside_model) {
    int inside = 0, probes = 0;
    bool last = false;
    auto probe = [&](const Vec2& p) {
      const bool in = inside_model(p);
      if (probes == 0) f.starts_inside = in;
      else if (in != last) ++f.silhouette_crossings;
      last = in;
      ++probes;
      inside += in ? 1 : 0;
    };
    probe(fine.front());
    for (std::size_t i = 1; i < fine.size(); ++i) {
      const Vec2 a = fine[i - 1], d = fine[i] - fine[i - 1];
      const double pieces = std::ceil(d.norm() / params.silhouette_step_px);
      const int n = static_cast<int>(std::clamp(pieces, 1.0, 1e6));
      for (int k = 1; k <= n; ++k) probe(a + (static_cast<double>(k) / n) * d);
    }
    f.ends_inside = last;
    f.inside_fraction = static_cast<double>(inside) / probes;
  }

  // === Decision
  const bool outline = f.closed_area_ratio >= params.closed_keeps_area && f.closed_overdraw < params.closed_max_overdraw;
  if (f.closed && (!scratch || outline)) {
    out.cls = StrokeClass::kClosed;
    out.reason = "closed: its ends meet (gap " + fmt("%.1f", f.end_gap_px) + " px on a length of " +
                 fmt("%.0f", f.length_px) + " px)";
    if (scratch)
      out.reason += "; its " + std::to_string(f.reversals) + " sharp corners outline an area (" +
                    fmt("%.3f", f.closed_area_ratio) + " x length^2)";
    return out;
  }
  if (scratch) {
    out.cls = StrokeClass::kScratchOut;
    out.reason = "scratch-out: " + std::to_string(f.reversals) + " sharp reversals, length " +
                 fmt("%.1f", f.overdraw) + " x its extent";
    return out;
  }
  std::string shape = f.reversals > 0 ? " (" + std::to_string(f.reversals) + " reversal" +
                                             (f.reversals > 1 ? "s" : "") + ", fewer than " +
                                             std::to_string(params.min_reversals) + " for a scratch-out)"
                                       : "";
  if (f.reversals >= params.min_reversals)
    shape = " (" + std::to_string(f.reversals) + " reversals but length only " + fmt("%.1f", f.overdraw) +
            " x its extent: it does not go back over itself)";
  const int inside_pct = static_cast<int>(std::lround(100.0 * f.inside_fraction));
  if (f.inside_fraction == 0.0) {
    out.cls = StrokeClass::kOpenMiss;
    out.reason = std::string("open stroke") + shape + " that never touches the model" +
                 (inside_model ? "" : " (no model)");
  } else if (!f.starts_inside && !f.ends_inside) {
    out.cls = StrokeClass::kOpenCutting;
    out.reason = "open-cutting: starts and ends outside the silhouette, " + std::to_string(inside_pct) +
                 "% over the model, " + std::to_string(f.silhouette_crossings) + " silhouette crossings" + shape;
  } else {
    out.cls = StrokeClass::kOpenDeformation;
    out.reason = std::string("open-deformation: ") +
                 (f.starts_inside && f.ends_inside ? "starts and ends on the model"
                  : f.starts_inside                ? "starts on the model"
                                                   : "ends on the model") +
                 ", " + std::to_string(inside_pct) + "% over it" + shape;
  }
  return out;
}

}  // namespace ps
