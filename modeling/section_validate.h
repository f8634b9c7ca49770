#pragma once
// Validation of cross-section input against the stroke rules (thesis 3.3.2, docs/contours.md)
// and the nesting of curves per plane (rule 2). Used by reconstruct() and by the app to refuse a
// stroke: every refusal names the curve (index into the INPUT SectionSet) and what is wrong.
//
// Conventions of the canonical output:
//   * Planes are unit-normal; axis-aligned normals are snapped to exactly +e_k (the offset is
//     negated when the normal was -e_k: orientation of a plane carries no meaning).
//   * Coincident planes are merged into one (warning); planes holding no curve are kept.
//   * Points are projected onto their plane (silently below 1e-6 of the bounding-box diagonal,
//     with a warning up to 1e-3, an error beyond); on an axis plane the axis coordinate is then
//     exactly the offset. On other planes a point within 1e-14 of the diagonal is kept as is
//     (doubles cannot do better; the union makes it exact).
//   * Curve indices are unchanged (curve i of the output is curve i of the input).
//   * Nesting (rule 2): depth[i] = number of curves on the same plane that contain curve i.
//     Even depth: outer boundary of a region; odd depth: a hole. A point of the plane is inside
//     the section region iff it lies inside an odd number of that plane's curves.
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// A 2D frame on a plane: p = origin + x u + y v, with u x v == normal. For an axis plane
// (normal e_k) u = e_{k+1}, v = e_{k+2} (indices mod 3) and the origin is offset * e_k, so
// to_2d / to_3d copy coordinates exactly.
struct PlaneFrame {
  Vec3 origin = Vec3::Zero(), u = Vec3::UnitX(), v = Vec3::UnitY(), normal = Vec3::UnitZ();
  int axis = -1;
  double offset = 0.0;
  Vec2 to_2d(const Vec3& p) const;
  Vec3 to_3d(const Vec2& q) const;
};
PlaneFrame plane_frame(const Plane& plane);

// One connected section region on a plane: an outer curve (even depth) and its direct holes.
struct SectionRegion {
  int plane = -1;
  int outer = -1;          // curve index
  std::vector<int> holes;  // curve indices (depth of outer + 1, directly inside it)
};

struct ValidatedSections {
  SectionSet sections;            // canonical copy (see above)
  std::vector<int> depth;         // per curve
  std::vector<int> parent;        // per curve: the innermost curve containing it, or -1
  std::vector<SectionRegion> regions;
  std::vector<std::string> warnings;
  double diagonal = 0.0;          // bounding-box diagonal of all points
};

// Checks (each failure names the curve index): empty set, zero / non-finite normal, bad plane
// index, fewer than 3 points, NaN/inf coordinates, consecutive points closer than 1e-9 of the
// diagonal, a point off its plane beyond 1e-3 of the diagonal, zero area, a curve crossing or
// touching itself, two curves of one plane crossing or touching (rule 3).
Result<ValidatedSections> validate_sections(const SectionSet& sections);

// Curve sewing for stroke rule 4. Any two non-parallel planes meet along a line; for axis
// planes it is described here with exact coordinates, for other pairs the shared point is the
// point of the general line (within rounding of both planes). Where a curve on plane x_k = a crosses the
// line {x_k = a, x_j = b} and a curve on plane x_j = b crosses it nearby (closer than
// `tolerance`, absolute), both get one shared vertex at the mean of the two crossing points
// (an existing vertex within 1e-6 of the diagonal of the crossing is moved, otherwise a vertex is
// inserted). Crossings without a partner are reported as warnings (a large disagreement).
// Input: a canonical validated set (axis normals +e_k, points exactly on their planes).
// Returns the number of shared crossing points made.
int sew_crossings(SectionSet& sections, double tolerance, std::vector<std::string>* warnings = nullptr);

// Relative tolerances, shared with the reconstruction (fractions of the bounding-box diagonal).
inline constexpr double kOffPlaneError = 1e-3;
inline constexpr double kOffPlaneWarn = 1e-6;
inline constexpr double kDuplicatePoint = 1e-9;
// Crossing points of curves on two planes closer than this become one (rule 4, sew_crossings).
inline constexpr double kSewTolerance = 0.02;

}  // namespace ps
