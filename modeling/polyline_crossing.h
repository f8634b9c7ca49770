#pragma once
// Self-crossing and mutual-crossing tests for small 2D polylines (stroke rule 3, thesis 3.3.2).
//
// Written by hand, not with CGAL: strokes have tens to a few thousand points, the test runs on
// every pen-up, and CGAL's kernels and sweep headers must stay out of the stroke hot path (they
// cost ~1 minute of compile time per translation unit and pull in GMP for exactness). The
// predicate is exact anyway: orient2d uses a floating-point filter with an exact
// expansion-arithmetic fallback (Shewchuk's technique, written from the paper's description),
// so "crosses" / "does not cross" never depends on rounding. Only the reported location is a
// rounded construction.
//
// Candidate pairs come from a uniform grid of about one cell per segment (expected O(n) for
// strokes, whose segments have similar lengths).
//
// Conventions:
//   A closed polyline lists each point once; the last point connects to the first. Touching
//   counts as crossing (a curve that touches itself is refused like one that crosses), and so
//   does a fold-back (consecutive segments overlapping). Consecutive duplicate points are
//   ignored.
#include <optional>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

// Exact sign of the orientation of the triangle (a, b, c): +1 counter-clockwise (c left of the
// directed line a->b, in a y-up frame), -1 clockwise, 0 collinear. Inputs must be finite.
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c);

// Whether closed segments [p0, p1] and [q0, q1] share at least one point (exact).
bool segments_intersect(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);

// The first place where a closed polyline crosses or touches itself, or nothing if it is simple.
// "First" follows the drawing: walking the polyline from point 0, the first point at which it
// reaches a place it has already passed (the crossing on the segment with the smallest
// end index, nearest that segment's start). Needs at least 3 distinct points to be simple.
std::optional<Vec2> first_self_crossing(const std::vector<Vec2>& closed_polyline);

// Same for an open polyline (no closing segment).
std::optional<Vec2> first_self_crossing_open(const std::vector<Vec2>& open_polyline);

// A point where two closed polylines cross or touch each other (rule 3: two curves on one
// plane), or nothing. Among all crossings, the one on a's segment with the smallest index.
std::optional<Vec2> first_crossing_between(const std::vector<Vec2>& closed_a,
                                           const std::vector<Vec2>& closed_b);

}  // namespace ps
