#pragma once
// Internal to the CGAL translation units that clip section regions (zone_partition.cpp,
// polyhedral_partition.cpp): exact 2D polygon types and the conversion of a double loop. Not
// for other headers: it pulls in CGAL.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <vector>

#include "modeling/mesh.h"

namespace ps::exact2 {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using EPoint = EK::Point_2;
using EPolygon = CGAL::Polygon_2<EK>;
using EPwh = CGAL::Polygon_with_holes_2<EK>;

// The loop as an exact polygon, oriented counter-clockwise (ccw) or clockwise.
inline EPolygon to_exact(const std::vector<Vec2>& loop, bool ccw) {
  EPolygon p;
  for (const auto& q : loop) p.push_back(EPoint(q.x(), q.y()));
  if (p.is_counterclockwise_oriented() != ccw) p.reverse_orientation();
  return p;
}

}  // namespace ps::exact2
