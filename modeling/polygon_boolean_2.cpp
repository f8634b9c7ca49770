#include "modeling/polygon_boolean_2.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Polygon_set_2.h>

#include <optional>

#include "modeling/exact_polygon_2.h"

namespace ps {

namespace {

// The loop without consecutive repeated points (CGAL's polygons must not have zero-length
// edges), or nothing when fewer than 3 points or no area are left.
std::optional<exact2::EPolygon> clean(const std::vector<Vec2>& loop) {
  std::vector<Vec2> pts;
  for (const Vec2& q : loop)
    if (pts.empty() || pts.back() != q) pts.push_back(q);
  while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
  if (pts.size() < 3) return std::nullopt;
  exact2::EPolygon p;
  for (const Vec2& q : pts) p.push_back(exact2::EPoint(q.x(), q.y()));
  const auto side = p.orientation();
  if (side == CGAL::COLLINEAR) return std::nullopt;
  if (side == CGAL::CLOCKWISE) p.reverse_orientation();
  return p;
}

std::vector<std::vector<std::vector<Vec2>>> pieces_of(const CGAL::Polygon_set_2<exact2::EK>& region) {
  using namespace exact2;
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

}  // namespace

std::vector<std::vector<std::vector<Vec2>>> boolean_of_loops(const std::vector<std::vector<Vec2>>& loops,
                                                             const std::vector<bool>& add) {
  using namespace exact2;
  CGAL::Polygon_set_2<EK> region;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const auto p = clean(loops[i]);
    if (!p) continue;
    if (add[i]) region.join(*p);
    else region.difference(*p);
  }
  return pieces_of(region);
}

std::vector<std::vector<std::vector<Vec2>>> union_of_parts(const std::vector<RegionPart>& parts,
                                                           const std::vector<std::vector<Vec2>>& subtract) {
  using namespace exact2;
  CGAL::Polygon_set_2<EK> region;
  for (const RegionPart& part : parts) {
    CGAL::Polygon_set_2<EK> piece;
    for (const auto& l : part.add)
      if (const auto p = clean(l)) piece.join(*p);
    for (const auto& l : part.remove)
      if (const auto p = clean(l)) piece.difference(*p);
    region.join(piece);
  }
  for (const auto& l : subtract)
    if (const auto p = clean(l)) region.difference(*p);
  return pieces_of(region);
}

}  // namespace ps
