#pragma once
// Stroke recognition for the sculpting tool (thesis 3.2.2, issue 6 point 1).
//
// A pen stroke drawn over the model is one of:
//   kClosed           its ends meet (as preprocess_stroke decides: gap <= 3 mean filtered
//                     segments and <= 25% of the length, or an overshooting tail crossing the
//                     head). Starts extrusion / tunneling.
//   kScratchOut       it goes back and forth over a small region: at least `min_reversals`
//                     sharp reversals (turns of more than `reversal_turn_deg`) and a length at
//                     least `min_overdraw` times its bounding-box diagonal. Starts smoothing.
//   kOpenCutting      open; it crosses the model's silhouette in image space, entering and
//                     leaving it: the first and last samples are outside the silhouette and
//                     some part of the stroke is inside. Starts cutting.
//   kOpenDeformation  open; it touches the model and is not cutting (it stays on the model,
//                     or starts or ends on it). Starts the deformation tool.
//   kOpenMiss         open and never over the model. No operation applies; the app shows a
//                     message ("the stroke misses the model") and leaves the model unchanged.
//
// Input: the stroke's raw samples in window pixels (x right, y down, modeling/camera.h), in
// drawing order, pen-down first, pen-up last. Time stamps are not used: the decision depends
// only on the path, so drawing speed only changes the sampling density, which filtering by
// distance removes (tested over 80-2500 px/s).
//
// The model: `inside_model(p)` is true when window pixel position p (continuous, in pixels) is
// covered by the model's image-space silhouette (e.g. a lookup in a rasterized coverage mask
// of the current view, or a point-in-polygon test of the projected outline). It is called about
// once per `silhouette_step_px` of stroke length, never with a non-finite point; it must not
// throw. An empty function means "no model": every open stroke is then kOpenMiss.
//
// Errors (Result with a message, never a crash): an empty stroke, a stroke with fewer than 2
// samples, a non-finite sample (naming its index), a stroke shorter than `min_length_px`,
// parameters out of range.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"
#include "modeling/stroke_preprocess.h"

namespace ps {

enum class StrokeClass { kClosed, kScratchOut, kOpenCutting, kOpenDeformation, kOpenMiss };

// "closed", "scratch-out", "open-cutting", "open-deformation", "open-miss".
std::string_view stroke_class_name(StrokeClass c);
// Inverse of stroke_class_name; false for an unknown name.
bool parse_stroke_class(std::string_view name, StrokeClass& out);

using InsideModelFn = std::function<bool(const Vec2&)>;

struct StrokeClassifyParams {
  // Closedness: preprocess_stroke with these parameters (15 px filter, 3 x mean segment gap,
  // 25% of the length, overshoot cut) decides open / closed, as for cross sections.
  StrokeParams closedness = {};
  // Strokes shorter than this (raw polyline length, px) are refused: a tap, not a stroke.
  double min_length_px = 10.0;
  // Shape analysis runs on the samples filtered at `fine_spacing_px` (drops duplicates and
  // sub-pixel tremor), resampled every window / 8 of arc length. The turn at a point is the
  // angle between the chord arriving over the last `window` of arc length and the chord
  // leaving over the next one (0 = straight on, 180 = straight back), with
  // window = max(min_leg_px, min_leg_fraction * bbox diagonal). A reversal is a run of points
  // turning by more than reversal_turn_deg (the run ends when the turn drops 30 degrees below
  // it). Both legs of a reversal are therefore at least `window` long: hooks at the pen-down /
  // pen-up, jitter and smooth waves do not count.
  double fine_spacing_px = 1.5;
  double reversal_turn_deg = 120.0;
  double min_leg_px = 8.0;
  double min_leg_fraction = 0.15;
  // Scratch-out: at least min_reversals reversals ("several": a Z or N with 2 is open) and
  // length >= min_overdraw * bbox diagonal (it covers its region more than once).
  int min_reversals = 3;
  double min_overdraw = 2.0;
  // A closed loop enclosing |area| >= closed_keeps_area * length^2 whose length is below
  // closed_max_overdraw * bbox diagonal (both of the preprocessed loop) stays closed even with sharp corners (a star
  // outline: area 0.033, overdraw 2.5; a circle: 0.080 and 2.2). A scratch-out whose ends meet
  // encloses less or runs longer (docs/strokes.md).
  double closed_keeps_area = 0.025;
  double closed_max_overdraw = 3.0;
  // Silhouette sampling: the fine polyline is probed every silhouette_step_px of arc length
  // (and at every sample end point).
  double silhouette_step_px = 2.0;
};

struct StrokeFeatures {
  int raw_count = 0;            // samples in
  double length_px = 0.0;       // raw polyline length
  double bbox_diagonal_px = 0.0;
  double end_gap_px = 0.0;      // distance between the first and the last sample
  bool closed = false;          // preprocess_stroke's closedness (with overshoot cut)
  bool closed_simple = false;   // closed and its preprocessed loop does not cross itself
  double closed_area_ratio = 0.0;  // |area| / length^2 of the preprocessed loop (closed only)
  double closed_overdraw = 0.0;    // loop length / bbox diagonal (closed only; overshoot cut off)
  double window_px = 0.0;       // arc length over which turns are measured
  int reversals = 0;            // runs turning by more than reversal_turn_deg
  double max_turn_deg = 0.0;    // sharpest turn over the window
  double overdraw = 0.0;        // length / bbox diagonal
  // Silhouette (open strokes and closed ones alike; all zero / false without a model).
  bool starts_inside = false, ends_inside = false;
  double inside_fraction = 0.0;  // of the probed points
  int silhouette_crossings = 0;  // inside/outside changes along the stroke
};

struct StrokeClassification {
  StrokeClass cls = StrokeClass::kOpenDeformation;
  StrokeFeatures features;
  std::string reason;  // one line, e.g. "scratch-out: 5 sharp reversals, length 4.1 x its extent"
};

Result<StrokeClassification> classify_stroke(const std::vector<Vec2>& window_points,
                                             const InsideModelFn& inside_model,
                                             const StrokeClassifyParams& params = {});

}  // namespace ps
