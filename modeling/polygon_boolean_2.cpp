#include "modeling/polygon_boolean_2.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Polygon_set_2.h>

#include "modeling/exact_polygon_2.h"

namespace ps {

std::vector<std::vector<std::vector<Vec2>>> boolean_of_loops(const std::vector<std::vector<Vec2>>& loops,
                                                             const std::vector<bool>& add) {
  using namespace exact2;
  CGAL::Polygon_set_2<EK> region;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const EPolygon p = to_exact(loops[i], true);
    if (add[i]) region.join(p);
    else region.difference(p);
  }
  std::vector<EPwh> pieces;
  region.polygons_with_holes(std::back_inserter(pieces));
  auto to_double = [](const EPolygon& p) {
    std::vector<Vec2> out;
    out.reserve(p.size());
    for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v)
      out.emplace_back(CGAL::to_double(v->x()), CGAL::to_double(v->y()));
    return out;
  };
  std::vector<std::vector<std::vector<Vec2>>> out;
  for (const EPwh& pwh : pieces) {
    out.emplace_back();
    out.back().push_back(to_double(pwh.outer_boundary()));
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) out.back().push_back(to_double(*h));
  }
  return out;
}

}  // namespace ps
