#pragma once
// Repair of section curves that touch or cross themselves (opt-in: `planesketch reconstruct
// --repair`, `planesketch convert --repair`).
//
// Contours traced from scans and medical images often pinch: a curve comes back to a vertex it
// already passed (a hole or a bay joined to the boundary at one point), folds back on itself
// (a spike of zero width), or twists through a tiny loop. Stroke rule 3 refuses such curves
// (section_validate.h), and a sketch should still be refused: the designer redraws. A file of
// a thousand traced contours cannot be redrawn, so this repair turns each such curve into
// simple curves with the same region.
//
// The region of a curve is the set of points around which it winds a non-zero number of times
// (both lobes of a figure eight, a loop twisted back, the part of a curve wound twice).
// The repair:
//   1. splits the curve at every place where it touches or crosses itself into loops, each of
//      them simple (a spike, a loop with no area, is dropped);
//   2. keeps a loop only where it bounds the region: the region is on one side of it and not on
//      the other (a loop wound twice in the same direction is dropped);
//   3. drops loops whose area is below `min_area_fraction` of the curve's largest loop;
//   4. separates loops that still touch: the contact vertex of the smaller loop moves into that
//      loop by `separation` of its shorter adjacent edge, at most `max_separation` of the
//      curve's bounding-box diagonal. The loops then nest (rule 2: a pinched hole becomes a
//      hole, a second lobe a second curve).
// The result is checked exactly (polyline_crossing.h): simple loops, no two touching. A curve
// whose loops cross each other after the split (it crosses itself twice between the same
// parts) is not repaired and keeps its error.
//
// Sign conventions: loops are returned in the orientation they had in the curve; nesting, not
// orientation, decides holes downstream (section_validate.h).
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/section_validate.h"
#include "modeling/status.h"

namespace ps {

struct CurveRepairOptions {
  double min_area_fraction = 1e-4;  // loops below this fraction of the largest loop are dropped
  double separation = 0.1;          // of the shorter edge next to a contact vertex
  double max_separation = 1e-4;     // of the curve's bounding-box diagonal
};

// One 2D closed curve (each point once, the last joined to the first). Returns the simple loops
// (largest area first), or an error naming what could not be repaired. A simple curve comes
// back unchanged as one loop.
Result<std::vector<std::vector<Vec2>>> repair_closed_curve(const std::vector<Vec2>& curve,
                                                           const CurveRepairOptions& options = {});

// Every curve of `sections` that touches or crosses itself is replaced by its repaired loops:
// the largest keeps the curve's index, the others are appended (on the same plane). Points of
// the input are kept bit for bit; only contact points (new) and moved contact vertices change.
// A warning per repaired curve names it and what was done. Curves that cannot be repaired are
// left as they are (validation then refuses them with its own message) and named in a warning.
//
// Then, per plane, each group of curves that cross or touch one another (two traced organs
// overlapping, a hole crossing its boundary) is replaced by the boundary of the region they
// make: a curve at even depth among the plane's curves (counted by most of its vertices) adds
// its inside, one at odd depth takes it away, in order of depth (exact: polygon_boolean_2.h).
// Touching results are separated as above. The group's lowest indices take the new curves;
// extra curves are appended; when fewer curves result, the curves after them are renumbered
// (a warning says so).
// Returns the number of curves repaired plus the number of groups merged.
int repair_section_curves(SectionSet& sections, std::vector<std::string>* warnings = nullptr,
                          const CurveRepairOptions& options = {});

// Curves on `plane` from loops in its 2D `frame`: a loop point equal, bit for bit, to the 2D
// image of a point of `inputs` (curves of that plane) takes that input point, so input points
// survive exactly; any other point is lifted by the frame.
std::vector<CrossSection> lift_loops(const std::vector<std::vector<Vec2>>& loops,
                                     const std::vector<const CrossSection*>& inputs, const PlaneFrame& frame, int plane);

// === CSL components (contour_io.h): labels and hole flags rather than nesting
// A CSL plane lists components, each with a label (0: outside) and optionally a hole flag with
// its parent. For one object the section is the union over labelled components of (component
// minus its holes), minus the components labelled 0. Usually nesting says the same (rule 2),
// and the curves stand as read; multi-material files (Abdomen: nine organs) nest labelled
// components without hole flags, or let them overlap.
struct CslComponent {
  std::vector<Vec2> loop;
  bool hole = false;
  int parent = -1;  // for a hole: the component it is a hole of
  int label = 1;
};

// Whether no two components of different labels cross or touch, and every component that
// crosses or touches no other has a nesting depth among the plane's components (by most of its
// vertices) that is odd exactly for holes and label-0 components. Components of one label
// crossing each other, and components crossing themselves, are left out of the depth test
// (validation refuses them, --repair splits or merges them by nesting).
bool components_agree_with_nesting(const std::vector<CslComponent>& comps);

// The nesting test used there: most of loop a's vertices (a sample of 16; those on b's boundary
// are not counted) lie inside loop b. The CSL writer uses it too, so that what it writes as holes
// is what the reader takes for holes.
bool loop_mostly_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

// The boundary curves of the union described above (exact 2D Booleans; pinches split and
// separated as in repair_section_curves). A component that crosses itself is first split as
// repair_closed_curve does (non-zero winding).
Result<std::vector<std::vector<Vec2>>> region_of_components(const std::vector<CslComponent>& comps,
                                                            const CurveRepairOptions& options = {});

}  // namespace ps
