// Zone partition (thesis 4.2). The clipping of section regions (with holes and concavities) to
// zone face rectangles uses CGAL's 2D Boolean set operations on an exact kernel, so crossing
// points are computed exactly once and rounded the same way for both zones sharing the face.
#include "modeling/zone_partition.h"

#include <CGAL/Boolean_set_operations_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "modeling/exact_polygon_2.h"

namespace ps {
namespace {

using namespace exact2;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

std::vector<Vec2> to_double(const EPolygon& p) {
  std::vector<Vec2> out;
  out.reserve(p.size());
  for (auto it = p.vertices_begin(); it != p.vertices_end(); ++it)
    out.emplace_back(CGAL::to_double(it->x()), CGAL::to_double(it->y()));
  return out;
}

// Index of the grid cell containing [lo, hi] along one axis range (first cell overlapping).
int first_cell(const std::vector<double>& c, double lo) {
  const auto it = std::upper_bound(c.begin(), c.end(), lo);
  return std::max(0, static_cast<int>(it - c.begin()) - 1);
}

}  // namespace

int Partition::count(ZoneType t) const {
  return static_cast<int>(std::count_if(zones.begin(), zones.end(), [&](const Zone& z) { return z.type == t; }));
}

Box3 default_reconstruction_box(const std::vector<Vec3>& points) {
  const Box3 b = bounding_box(points);
  Box3 out;
  if (b.empty()) return out;
  const Vec3 c = b.center();
  // Relative to the points only: an absolute floor here made the box of a model 1e-30 across
  // 1e-12 wide. Coincident points (refused by validation anyway) get a unit box.
  const double extent = b.size().maxCoeff();
  const double largest = extent > 0 ? extent : 1.0;
  for (int k = 0; k < 3; ++k) {
    const double half = std::max(b.size()[k], 0.5 * largest);
    out.min[k] = c[k] - half;
    out.max[k] = c[k] + half;
  }
  return out;
}

Result<Partition> partition_zones(const ValidatedSections& vs, const Box3& box, const ClipCache* previous,
                                  ClipCache* next) {
  const SectionSet& s = vs.sections;
  Partition part;
  part.grid.box = box;

  // === Grid: the sorted distinct coordinates of planes holding sections, per axis.
  std::vector<char> plane_used(s.planes.size(), 0);
  for (const auto& c : s.curves) plane_used[uz(c.plane)] = 1;
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    if (!plane_used[i]) continue;
    const int k = s.planes[i].axis();
    if (k < 0 || s.planes[i].normal[k] < 0.0)
      return Result<Partition>::error("plane " + std::to_string(i) + " is not an axis plane; the orthogonal partition needs axis planes");
    const double c = s.planes[i].offset;
    if (!(c > box.min[k] && c < box.max[k]))
      return Result<Partition>::error("plane " + std::to_string(i) + " lies outside the reconstruction box");
    part.grid.coords[uz(k)].push_back(c);
  }
  for (int k = 0; k < 3; ++k) {
    auto& c = part.grid.coords[uz(k)];
    c.push_back(box.min[k]);
    c.push_back(box.max[k]);
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  const ZoneGrid& g = part.grid;

  // === Zones
  part.zones.resize(uz(g.size()));
  for (int k2 = 0; k2 < g.cells(2); ++k2)
    for (int k1 = 0; k1 < g.cells(1); ++k1)
      for (int k0 = 0; k0 < g.cells(0); ++k0) {
        const std::array<int, 3> cell{k0, k1, k2};
        Zone& z = part.zones[uz(g.index(cell))];
        z.cell = cell;
        for (int a = 0; a < 3; ++a) {
          const auto& c = g.coords[uz(a)];
          z.min[a] = c[uz(cell[uz(a)])];
          z.max[a] = c[uz(cell[uz(a)] + 1)];
          z.on_box[uz(2 * a)] = cell[uz(a)] == 0;
          z.on_box[uz(2 * a + 1)] = cell[uz(a)] + 1 == g.cells(a);
          z.half_spaces[uz(2 * a)] = HalfSpace{-Vec3::Unit(a), -z.min[a]};
          z.half_spaces[uz(2 * a + 1)] = HalfSpace{Vec3::Unit(a), z.max[a]};
        }
      }

  // === Pieces: each region clipped to every face rectangle of its plane it overlaps.
  for (std::size_t ri = 0; ri < vs.regions.size(); ++ri) {
    const SectionRegion& r = vs.regions[ri];
    const Plane& pl = s.planes[uz(r.plane)];
    const PlaneFrame fr = plane_frame(pl);
    const int k = pl.axis();
    const int au = (k + 1) % 3, av = (k + 2) % 3;
    const auto& cu = g.coords[uz(au)];
    const auto& cv = g.coords[uz(av)];
    const int layer = static_cast<int>(std::lower_bound(g.coords[uz(k)].begin(), g.coords[uz(k)].end(), pl.offset) -
                                       g.coords[uz(k)].begin());
    RegionClipKey key;
    key.loops.emplace_back();
    for (const auto& p : s.curves[uz(r.outer)].points) key.loops[0].push_back(fr.to_2d(p));
    for (int h : r.holes) {
      key.loops.emplace_back();
      for (const auto& p : s.curves[uz(h)].points) key.loops.back().push_back(fr.to_2d(p));
    }
    const std::vector<Vec2>& outer = key.loops[0];
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (const auto& q : outer) {
      u0 = std::min(u0, q.x()); u1 = std::max(u1, q.x());
      v0 = std::min(v0, q.y()); v1 = std::max(v1, q.y());
    }
    // Cells [a0, a1) x [b0, b1) overlap the region's box; their coordinates are part of the key.
    const int a0 = first_cell(cu, u0), b0 = first_cell(cv, v0);
    int a1 = a0, b1 = b0;
    while (a1 < static_cast<int>(cu.size()) - 1 && cu[uz(a1)] < u1) ++a1;
    while (b1 < static_cast<int>(cv.size()) - 1 && cv[uz(b1)] < v1) ++b1;
    key.cu.assign(cu.begin() + a0, cu.begin() + std::min(a1 + 1, static_cast<int>(cu.size())));
    key.cv.assign(cv.begin() + b0, cv.begin() + std::min(b1 + 1, static_cast<int>(cv.size())));
    // The outer rectangle sides strictly beyond the region's box touch nothing: they are moved
    // to a place fixed by the region alone, so a plane added beyond the region (which moves
    // them) leaves the key and the pieces unchanged, cached or fresh.
    auto canonical_ends = [](std::vector<double>& c, double lo, double hi) {
      if (c.front() < lo) c.front() = lo - (hi - lo);
      if (c.back() > hi) c.back() = hi + (hi - lo);
    };
    canonical_ends(key.cu, u0, u1);
    canonical_ends(key.cv, v0, v1);
    ContentHash hash;
    for (const auto& loop : key.loops) hash.points(loop);
    hash.doubles(key.cu);
    hash.doubles(key.cv);
    const std::vector<ClippedPiece> clipped = cached(previous, next, hash.h, key, [&] {
      EPwh region(to_exact(key.loops[0], true));
      for (std::size_t h = 1; h < key.loops.size(); ++h) region.add_hole(to_exact(key.loops[h], false));
      std::vector<ClippedPiece> out;
      for (int a = a0; a < a1; ++a) {
        for (int b = b0; b < b1; ++b) {
          EPolygon rect;
          const double ua = key.cu[uz(a - a0)], ub = key.cu[uz(a - a0 + 1)];
          const double va = key.cv[uz(b - b0)], vb = key.cv[uz(b - b0 + 1)];
          rect.push_back(EPoint(ua, va));
          rect.push_back(EPoint(ub, va));
          rect.push_back(EPoint(ub, vb));
          rect.push_back(EPoint(ua, vb));
          std::vector<EPwh> pieces;
          CGAL::intersection(region, rect, std::back_inserter(pieces));
          for (const auto& c : pieces) {
            ClippedPiece piece;
            piece.cell = {a - a0, b - b0};
            piece.loops.push_back(to_double(c.outer_boundary()));
            for (auto h = c.holes_begin(); h != c.holes_end(); ++h) piece.loops.push_back(to_double(*h));
            out.push_back(std::move(piece));
          }
        }
      }
      return out;
    });
    for (const auto& c : clipped) {
      SectionPiece piece;
      piece.plane = r.plane;
      piece.axis = k;
      piece.layer = layer;
      const int a = a0 + c.cell[0], b = b0 + c.cell[1];
      piece.cell = {a, b};
      piece.loops = c.loops;
      const int id = static_cast<int>(part.pieces.size());
      part.pieces.push_back(std::move(piece));
      // The piece lies on the max face of the zone below the plane and the min face of the
      // zone above it.
      std::array<int, 3> cell{};
      cell[uz(k)] = layer - 1;
      cell[uz(au)] = a;
      cell[uz(av)] = b;
      part.zones[uz(g.index(cell))].face_pieces[uz(2 * k + 1)].push_back(id);
      cell[uz(k)] = layer;
      part.zones[uz(g.index(cell))].face_pieces[uz(2 * k)].push_back(id);
    }
  }

  // === Classification
  for (auto& z : part.zones) {
    int faces = 0;
    for (int f = 0; f < 6; ++f) faces += z.face_has_section(f) ? 1 : 0;
    z.type = faces == 0 ? ZoneType::kEmpty : faces == 1 ? ZoneType::kEnd : ZoneType::kBody;
  }
  return part;
}

}  // namespace ps
