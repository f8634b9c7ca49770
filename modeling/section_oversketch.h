#pragma once
// Editing a closed section with an open stroke (thesis 3.2.1: the sections "calculated from the
// previewed model and reference planes ... can be modified through oversketching"; a stroke may
// be "just a part of the cross section", 4.6). One operation serves both uses:
//
//   oversketch  the open stroke's two ends lie near a section the user drew on the same plane:
//               the part of that section between the ends, the one the stroke runs along, is
//               replaced by the stroke; the rest of the section keeps its points bit for bit.
//   completion  the ends lie near a curve of the preview's cross section on the plane (the
//               model sliced by it): the stroke is completed into a closed curve by the part of
//               that curve it does not run along, and the result is a new section.
//
// Conventions: 2D polylines in one plane frame (modeling/section_validate.h's PlaneFrame), a
// closed polyline lists each point once. Which of the two parts between the ends is replaced:
// the one the stroke runs closer to (mean distance of the stroke's points to each part), so a
// stroke hugging the long side replaces the long side; on a tie, the shorter part.
//
// Blending (thesis-facts, as the original did): the new part is 0.8 of the stroke and 0.2 of
// the replaced part (matched by arc length), so a hand-drawn stroke settles a little towards the
// curve it redraws, and the step where the stroke's ends meet the curve fades over the three
// kept points on each side (moved by 0.7, 0.4 and 0.1 of it). Every other kept point keeps its
// bits.
#include <cstddef>
#include <optional>
#include <vector>

#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// The point of a closed polyline nearest to `p`: on segment `segment` (from point `segment` to
// the next, cyclically) at parameter t in [0, 1].
struct ClosedCurveHit {
  std::size_t segment = 0;
  double t = 0.0;
  Vec2 point = Vec2::Zero();
  double distance = 0.0;
};
// Needs at least 2 points (the caller checks).
ClosedCurveHit nearest_on_closed(const std::vector<Vec2>& closed, const Vec2& p);

struct Splice {
  std::vector<Vec2> curve;      // the closed result
  std::size_t kept_points = 0;  // points of the input curve kept (bit for bit)
  double replaced_length = 0.0, kept_length = 0.0;  // along the input curve
};

struct SpliceBlend {
  double stroke_weight = 0.8;            // of the stroke against the replaced part, in [0, 1]
  std::vector<double> fade = {0.7, 0.4, 0.1};  // of the end step, on the kept points nearest each end
};

// Replaces the part of `closed` between the points nearest to the ends of `open` by `open`,
// blended as above (`SpliceBlend{1.0, {}}`: the stroke itself, its ends moved onto the curve).
// Refused, naming the reason: too few or non-finite points, a non-positive `snap`, an end
// farther than `snap` from the curve, both ends meeting the curve within `snap` of each other
// (nothing to tell the parts apart), a weight outside [0, 1], or a result that crosses or
// touches itself.
Result<Splice> splice_open_stroke(const std::vector<Vec2>& closed, const std::vector<Vec2>& open, double snap,
                                  const SpliceBlend& blend = {});

// An open stroke with no curve under its ends (thesis-facts: the original did this): when every
// inner point lies strictly on one side of the chord from its first to its last point (farther
// than 1e-9 of the chord's length), the closed curve made of the stroke and its mirror image
// in the chord (the image's points in reverse, the ends shared); nothing otherwise (a stroke
// that crosses or touches its chord, or has no inner point).
std::optional<std::vector<Vec2>> mirror_about_chord(const std::vector<Vec2>& open);

}  // namespace ps
