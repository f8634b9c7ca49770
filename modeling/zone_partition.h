#pragma once
// Zone partition (thesis 4.2): a fixed bounding box is split by every plane holding a section
// into cuboid zones; the section regions are clipped into pieces per zone face, and each zone is
// classified as empty (no face holds a piece), end (one face) or body (two or more).
//
// Orthogonal input only (every section plane is an axis plane). A zone is stored both as a box
// and as its six half-spaces (normal . p <= offset, outward normals), the form a convex zone of
// an arrangement of arbitrary planes (thesis chapter 6) also takes.
//
// Faces of a zone are numbered f = 2 * axis + side, side 0 the min face (outward normal -e_axis),
// side 1 the max face (outward normal +e_axis).
#include <array>
#include <vector>

#include "modeling/content_cache.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/section_validate.h"
#include "modeling/status.h"

namespace ps {

enum class ZoneType { kEmpty, kEnd, kBody };

// A section region clipped to one zone face rectangle. Loops are in the plane's 2D frame
// (PlaneFrame of an axis plane: coordinates (axis+1)%3, (axis+2)%3): loops[0] is the outer
// boundary, counter-clockwise; the others are holes, clockwise. Points on the rectangle's
// border have their border coordinate exactly equal to the rectangle's.
struct SectionPiece {
  int plane = -1;        // index into ValidatedSections::sections.planes
  int axis = 0;          // the plane's normal axis
  int layer = 0;         // index of the plane's coordinate in ZoneGrid::coords[axis]
  std::array<int, 2> cell{0, 0};  // cell index along axes (axis+1)%3 and (axis+2)%3
  std::vector<std::vector<Vec2>> loops;
};

struct HalfSpace {
  Vec3 normal;
  double offset;
};

struct Zone {
  std::array<int, 3> cell{0, 0, 0};
  Vec3 min, max;
  ZoneType type = ZoneType::kEmpty;
  std::array<std::vector<int>, 6> face_pieces;  // piece indices per face
  std::array<bool, 6> on_box{};                 // face lies on the bounding box
  std::array<HalfSpace, 6> half_spaces{};
  bool face_has_section(int f) const { return !face_pieces[static_cast<std::size_t>(f)].empty(); }
  double extent(int axis) const { return max[axis] - min[axis]; }
};

struct ZoneGrid {
  Box3 box;
  std::array<std::vector<double>, 3> coords;  // sorted; front = box.min, back = box.max
  int cells(int axis) const { return static_cast<int>(coords[static_cast<std::size_t>(axis)].size()) - 1; }
  int index(const std::array<int, 3>& c) const { return (c[2] * cells(1) + c[1]) * cells(0) + c[0]; }
  int size() const { return cells(0) * cells(1) * cells(2); }
};

struct Partition {
  ZoneGrid grid;
  std::vector<SectionPiece> pieces;
  std::vector<Zone> zones;  // indexed by ZoneGrid::index
  int count(ZoneType t) const;
};

// The box used when none is given: centred on the points' box, twice its size along each axis
// (a flat direction gets half the largest size, so a single section still has room).
Box3 default_reconstruction_box(const std::vector<Vec3>& points);

// The clipping of one region (its loops in the plane's 2D frame) by the face rectangles it
// overlaps (the grid coordinates spanning it), for the progressive reconstructor: pieces with
// their cell relative to the first overlapped cell, in clipping order.
struct RegionClipKey {
  std::vector<std::vector<Vec2>> loops;
  std::vector<double> cu, cv;
  bool operator==(const RegionClipKey&) const = default;
};
struct ClippedPiece {
  std::array<int, 2> cell{0, 0};
  std::vector<std::vector<Vec2>> loops;
};
using ClipCache = ContentCache<RegionClipKey, std::vector<ClippedPiece>>;

// Requires orthogonal validated input and a box containing every point strictly inside.
// Regions found in `previous` are not clipped again; every region's clipping goes to `next`.
Result<Partition> partition_zones(const ValidatedSections& sections, const Box3& box,
                                  const ClipCache* previous = nullptr, ClipCache* next = nullptr);

}  // namespace ps
