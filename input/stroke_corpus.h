#pragma once
// A labelled corpus of sculpting strokes for measuring stroke recognition
// (modeling/stroke_classify.h, docs/strokes.md "Stroke recognition").
//
// Every stroke is generated from an intended path in window pixels (1280 x 800 by default)
// over one of three image-space silhouettes (a disc, a rotated ellipse, a non-convex
// three-lobed blob), then "drawn" as pen samples: a sample every `sample_interval_ms`, a
// speed drawn per stroke from [min_speed, max_speed] px/s, slower at both ends, smooth hand
// jitter (knots every 70 ms) of up to `max_jitter_px` plus white sensor noise of 0.3 x that.
// Size, rotation, direction (reversed paths) and start point vary per stroke. The label is the
// intention the path was built for, never the classifier's output:
//   closed            ellipses, wobbly loops, rounded squares, five-pointed star outlines,
//                     drawn closed, overshooting the start by up to 15% of the perimeter,
//                     or ending short of the start by a gap (hard case "slow-gap": 80-160
//                     px/s with a 12-30 px gap);
//   scratch-out       3-8 sharp reversals over a region 30-160 px wide, legs drifting by up
//                     to 25% of the width, rounded tips;
//   open-cutting      a line, bow or wave across the silhouette, ending 3-80 px outside it on
//                     both sides (hard case "just-outside": 3-8 px);
//   open-deformation  a line, bow or wave at least 6 px inside the silhouette (hard cases:
//                     "long-wavy", "zigzag-2" with only 2 reversals, "just-inside" ending
//                     3-6 px inside the outline).
// Deterministic for a seed (SynthRandom: the same on every standard library).
#include <cstdint>
#include <string>
#include <vector>

#include "input/stroke_log.h"
#include "modeling/status.h"
#include "modeling/stroke_classify.h"

namespace ps {

// A silhouette as a closed polygon in window pixels (the last point joins the first).
struct CorpusSilhouette {
  std::string name;
  std::vector<Vec2> outline;
  bool inside(const Vec2& p) const;
  // Distance from p to the outline (unsigned).
  double boundary_distance(const Vec2& p) const;
};

// disc, ellipse, blob, centred in a width x height window.
std::vector<CorpusSilhouette> corpus_silhouettes(int width = 1280, int height = 800);

struct LabelledStroke {
  StrokeClass label = StrokeClass::kOpenDeformation;
  std::string kind;             // generator variant, e.g. "ellipse", "slow-gap", "zigzag-2"
  std::size_t silhouette = 0;   // index into corpus_silhouettes()
  std::vector<PenSample> samples;  // down, move..., up (t from 0)
};

struct StrokeCorpusOptions {
  std::uint32_t seed = 20260601;
  int per_class = 150;              // strokes per class (closed, scratch-out, cutting, deformation)
  double hard_fraction = 0.3;       // of each class drawn as one of its hard cases
  double sample_interval_ms = 5.0;  // 200 Hz tablet; 8-16 for a mouse
  double min_speed_px_s = 80.0;
  double max_speed_px_s = 2500.0;
  double max_jitter_px = 1.5;
  int width = 1280, height = 800;
};

std::vector<LabelledStroke> make_stroke_corpus(const StrokeCorpusOptions& options = {});

// The down..up positions of a stroke.
std::vector<Vec2> stroke_positions(const std::vector<PenSample>& samples);

// A stroke log holding `strokes` (all over one silhouette), each bracketed by proximity-in /
// proximity-out, with pauses between them, in tool mode "sculpt". Times are shifted so the log
// is in order.
StrokeLog corpus_log(const std::vector<LabelledStroke>& strokes, int width = 1280, int height = 800,
                     const std::string& generator = "");

// Label sidecar for a log (assets/logs/strokes/NAME.labels.json):
//   {"silhouette": [[x, y], ...], "labels": ["closed", "scratch-out", ...]}
// one label per stroke of the log, in order (stroke_class_name spelling).
struct StrokeLabels {
  std::vector<Vec2> silhouette;
  std::vector<StrokeClass> labels;
};
std::string format_stroke_labels(const StrokeLabels& labels);
Result<StrokeLabels> parse_stroke_labels(const std::string& text, const std::string& name);

}  // namespace ps
