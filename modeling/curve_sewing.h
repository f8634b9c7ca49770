#pragma once
// Curve sewing: stroke rule 4 (thesis 3.3.2, Eqs. 3.2-3.4).
//
// Rule 4: for curves on two non-parallel planes Pa and Pb, the points where the curves on Pa
// cross Pb must be the points where the curves on Pb cross Pa (all of them lie on the line
// L = Pa ∩ Pb). Users cannot draw that exactly, so sew_curves makes it true:
//   1. for every pair of non-parallel planes that both hold curves, compute the crossings of
//      each side's curves with the other plane and sort both sets along L;
//   2. if the counts differ, drop near-tangent crossing pairs (an arc that dips less than
//      tangent_tolerance across the plane; it is then pushed back to its side); if they still
//      differ, refuse, naming the curves;
//   3. pair the sorted sets in order (on a line this pairs closest points); each pair's midpoint
//      is the new position of a handle point on both curves; a handle is an existing curve point
//      when one lies within snap_fraction of an edge length from the crossing, otherwise a point
//      inserted on the curve at the crossing;
//   4. deform each curve once, in its plane's 2D coordinates, with all its handles as hard
//      constraints: 2D Laplacian editing with a rotation and isotropic scale per point (Eqs.
//      3.3, 3.4 linearised as in Sorkine et al. 2004) plus a weak pull to the old positions;
//   5. repeat from 1 while crossings still disagree (at most max_iterations times).
// Curves whose crossings all agree already are returned untouched (bit for bit).
//
// Postconditions on success: for every pair of planes the crossing sets match pairwise within
// 1e-9 of the bounding-box diagonal; every curve point lies on its plane (exactly for
// axis-aligned planes, to rounding otherwise); planes, units and curve order are unchanged;
// curves may gain points (inserted handles).
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

struct SewingParams {
  // How far a handle's move spreads along the curve, as a fraction of the curve's points. It
  // sets the weight of the pull towards the old positions in Eq. 3.3 (the fitting term, free
  // points only) to mu = (influence * n)^-4, n = points on the curve (the deformation decays
  // over ~mu^-1/4 points). 0.25 measured best on ellipses of 40-400 points: dents next to the
  // handle under 1% of the move, points far from it moving 20-30% of it (docs/strokes.md).
  double influence = 0.25;
  // Second solve with the per-point scale of T_i divided out (keeps detail next to handles).
  bool normalize_scale = true;
  // A crossing snaps to an existing curve point closer than snap_fraction * (edge length);
  // otherwise a point is inserted there.
  double snap_fraction = 0.15;
  // Near-tangent crossing pairs (relative to the bounding-box diagonal) that may be ignored when
  // the crossing counts differ.
  double tangent_tolerance = 5e-3;
  // Shared points closer than common_point_radius * diagonal to the common point of their two
  // planes and a third plane holding curves are moved to that common point (all curves then
  // pass through it); see docs/strokes.md.
  double common_point_radius = 0.02;
  // Crossings that agree within match_tolerance * diagonal need no sewing.
  double match_tolerance = 1e-10;
  int max_iterations = 4;
};

struct SewingReport {
  struct Handle {
    int curve = -1;          // curve that was moved
    int partner_plane = -1;  // the plane whose line it was sewn to
    Vec3 from = Vec3::Zero();  // crossing before sewing
    Vec3 to = Vec3::Zero();    // shared point after sewing
    double moved = 0.0;        // |to - from|
  };
  std::vector<Handle> handles;   // first iteration's handle moves (what the user drew off)
  std::vector<Vec3> crossings;   // the shared points after sewing, each listed once per plane pair
  double max_moved = 0.0;        // largest handle move
  double max_displacement = 0.0; // largest move of an input curve point (dropped ones excluded)
  int iterations = 0;
  int tangents_removed = 0;      // near-tangent crossing pairs pushed off a plane
};

// Sew every pair of curves on non-parallel planes. Refuses (model unchanged) when crossing counts
// differ: "curve 3 crosses the line shared with curve 5's plane at 2 points, curve 5 at 4 points";
// when sewing would make new crossings (curves too far off), make a curve cross itself or another
// curve on its plane, or change nesting. `report` is filled on success and, with the first round's
// handle moves, on refusals after matching.
Result<SectionSet> sew_curves(const SectionSet& sections, const SewingParams& params = {},
                              SewingReport* report = nullptr);

// The points where existing curves cross (or touch) `target_plane`: where a new curve drawn on
// that plane must pass (thesis: highlighted before the user draws). Curves on planes parallel
// to the target are skipped. Sorted by curve, then along each curve.
std::vector<Vec3> required_crossings(const SectionSet& sections, const Plane& target_plane);

}  // namespace ps
