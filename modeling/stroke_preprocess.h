#pragma once
// Input stroke preprocessing (thesis 3.3.1) and lifting of window strokes onto planes.
//
// Pipeline for one pen stroke, in window pixels (x right, y down, see modeling/camera.h):
//   1. refuse non-finite samples;
//   2. filter: drop samples closer than `min_spacing_px` to the last kept one (the pen-up
//      sample is always kept, see docs/strokes.md);
//   3. classify open / closed (ends within `closed_gap_factor` mean filtered segment lengths,
//      or the tail crossing the head: an overshooting loop is cut at that crossing);
//   4. resample by arc length to N points (N from the length and `target_spacing_px`, or the
//      thesis's fixed N_pre when `fixed_count` > 0); closed strokes are resampled around the
//      whole loop, which bridges the gap between the ends;
//   5. smooth with Eq. 3.1, P'_i = (P_{i-1} + 4 P_i + P_{i+1}) / 6, wrapping around for closed
//      strokes, endpoints fixed for open ones.
// Degenerate strokes (fewer than 3 points after filtering, too short, zero area when closed)
// are refused with a Status naming what is wrong.
//
// The polyline helpers below work on 2D and 3D points alike.
#include <optional>
#include <string>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct StrokeParams {
  // Step 2: samples closer than this to the last kept sample are dropped (thesis-facts: 15 px
  // for cross sections, 25 px for handle / target curves, 20 px for silhouettes).
  double min_spacing_px = 15.0;
  // Step 4: N = round(length / target_spacing_px), clamped to [min_points, max_points]
  // (a closed stroke gets at least min_points_closed). fixed_count > 0 forces N = fixed_count.
  double target_spacing_px = 10.0;
  int min_points = 8;
  int min_points_closed = 16;
  int max_points = 2000;
  int fixed_count = 0;
  // Step 5: number of Eq. 3.1 passes (the thesis uses one).
  int smoothing_passes = 1;
  // Step 3: closed when |end - start| <= closed_gap_factor * mean filtered segment length and
  // <= closed_gap_max_fraction * stroke length. force_closed / force_open override the test.
  double closed_gap_factor = 3.0;
  double closed_gap_max_fraction = 0.25;
  bool force_closed = false;
  bool force_open = false;
  // Degeneracy: a stroke shorter than max(min_length_px, min_length_fraction * viewport
  // diagonal) is refused (the viewport term only when viewport_px is non-zero); a closed stroke
  // whose |area| < min_area_ratio * length^2 is refused (a circle has 1/(4 pi) ~ 0.08; 1e-3 is
  // a sliver whose width is under ~1/200 of its length).
  double min_length_px = 10.0;
  double min_length_fraction = 0.02;
  Vec2 viewport_px = Vec2::Zero();
  double min_area_ratio = 1e-3;
};

struct PreprocessedStroke {
  std::vector<Vec2> points;  // resampled and smoothed; closed strokes do not repeat point 0
  bool closed = false;
  double length = 0.0;       // of the filtered polyline (closing segment included if closed)
  int raw_count = 0;         // samples in
  int filtered_count = 0;    // samples left after step 2 (and overshoot trimming)
};

// === One-shot pipeline (steps 1-5)
Result<PreprocessedStroke> preprocess_stroke(const std::vector<Vec2>& window_points,
                                             const StrokeParams& params = {});

// Step 3 on its own, for an already filtered polyline: whether its ends meet (see StrokeParams).
bool is_closed_stroke(const std::vector<Vec2>& filtered_points, const StrokeParams& params = {});

// === Lifting
// Each window point is lifted onto `plane` by intersecting its camera ray with the plane. Refused
// when a ray is parallel to the plane or meets it behind the eye (or farther than the camera's
// far plane), or when a point or the camera is not finite. Lifted points are projected onto the
// plane so that their signed distance is zero up to rounding.
Result<std::vector<Vec3>> lift_stroke(const std::vector<Vec2>& window_points, const Camera& camera,
                                      const Plane& plane);

// The whole path of a cross-section stroke: preprocess (viewport taken from the camera), refuse
// a closed stroke that crosses itself (rule 3: "stroke crosses itself at (x, y)"), lift.
struct LiftedStroke {
  std::vector<Vec2> window_points;  // preprocessed, in pixels
  std::vector<Vec3> points;         // on the plane, one per window point
  bool closed = false;
};
Result<LiftedStroke> prepare_plane_stroke(const std::vector<Vec2>& window_points,
                                          const Camera& camera, const Plane& plane,
                                          const StrokeParams& params = {});

// === Polyline helpers (2D and 3D)
// Drop points closer than min_spacing to the last kept point; the last input point is kept
// (replacing the last kept point when it is closer than min_spacing / 2 to it).
// A stroke (window pixels) given to an operation: at least `min_points` points, all finite.
// `what` names it in the message ("the cutting stroke has 1 point(s); it needs at least 2").
Status check_window_points(const std::vector<Vec2>& points, std::size_t min_points, const char* what);
// A window point for messages: "(x, y)" with one decimal (pixels).
std::string format_window_point(const Vec2& p);

std::vector<Vec2> filter_close_points(const std::vector<Vec2>& pts, double min_spacing);
std::vector<Vec3> filter_close_points(const std::vector<Vec3>& pts, double min_spacing);

// Arc-length resampling to `count` points. Open: the first and last points are kept, spacing
// length / (count - 1). Closed: spacing length / count around the loop, starting at point 0.
// Needs count >= 2 and a polyline of positive length; otherwise returns the input unchanged.
std::vector<Vec2> resample_polyline(const std::vector<Vec2>& pts, int count, bool closed);
std::vector<Vec3> resample_polyline(const std::vector<Vec3>& pts, int count, bool closed);

// Eq. 3.1 smoothing, `passes` times. Open polylines keep their endpoints.
std::vector<Vec2> smooth_polyline(const std::vector<Vec2>& pts, bool closed, int passes = 1);
std::vector<Vec3> smooth_polyline(const std::vector<Vec3>& pts, bool closed, int passes = 1);

double polyline_length(const std::vector<Vec2>& pts, bool closed);
double polyline_length(const std::vector<Vec3>& pts, bool closed);

}  // namespace ps
