#pragma once
// Zone partition for planes of any orientation (thesis 6.2): the reconstruction box split by
// every plane holding a section into convex polyhedral zones (zone_arrangement.h), the zones'
// neighbours across each face, the section regions clipped into pieces per zone face (CGAL 2D
// Booleans on an exact kernel), and the zone types empty / end / body.
//
// Conventions:
//   * PolyPartition::planes holds the section planes (indices 0 .. section_planes-1, those of
//     ValidatedSections::sections.planes) followed by the six box planes.
//   * A face's polygon is counter-clockwise seen from outside its zone; `normal` is its outward
//     unit normal and `offset` such that normal . p <= offset inside the zone.
//   * Both zones sharing a face see the same SharedFace (same polygon up to orientation, same
//     pieces): pieces belong to shared faces, so the two sides get identical caps.
//   * A piece loop is counter-clockwise (outer) or clockwise (hole) in plane_frame(plane). Every
//     point carries the planes it lies on (`tags`: its own plane first, then the planes of the
//     face edges it lies on), so the union can make it exact on all of them. Points of the
//     input curves are kept bit for bit.
#include <array>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/section_validate.h"
#include "modeling/status.h"
#include "modeling/zone_partition.h"

namespace ps {

using PlaneTags = std::array<int, 3>;  // plane indices, -1 for unused slots

struct PolyPiece {
  int plane = -1;        // section plane
  int shared_face = -1;  // index into PolyPartition::shared_faces
  std::vector<std::vector<Vec3>> loops;
  std::vector<std::vector<Vec2>> loops2d;  // the same points in plane_frame(planes[plane])
  std::vector<std::vector<PlaneTags>> tags;
};

struct SharedFace {
  int plane = -1;                // index into PolyPartition::planes
  std::array<int, 2> zones{-1, -1};  // [0]: zone on the plane's negative side, [1]: positive (-1: none)
  std::vector<int> pieces;       // real section pieces on this face
};

struct PolyFace {
  std::vector<Vec3> polygon;
  int plane = -1;
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;
  int shared = -1;               // index into PolyPartition::shared_faces
  int neighbour = -1;            // zone across the face; -1 on the box
  std::vector<int> edge_plane;   // per polygon edge i -> i+1: the other plane holding it
  bool on_box() const { return neighbour < 0; }
};

struct PolyZone {
  std::vector<PolyFace> faces;
  ZoneType type = ZoneType::kEmpty;
  Vec3 centroid = Vec3::Zero();
  double diameter = 0.0;         // largest vertex distance
  // True when p lies inside the zone with at least `margin` from every face plane.
  bool contains(const Vec3& p, double margin) const;
};

struct PolyPartition {
  Box3 box;
  std::vector<Plane> planes;
  int section_planes = 0;
  std::vector<PolyZone> zones;
  std::vector<SharedFace> shared_faces;
  std::vector<PolyPiece> pieces;
  int count(ZoneType t) const;
};

// Requires validated input (points on their planes) and a box holding every point strictly
// inside. Planes holding no curve do not split the box.
Result<PolyPartition> partition_polyhedral(const ValidatedSections& sections, const Box3& box);

}  // namespace ps
