#include "modeling/smoothing_clearance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>

#include "modeling/parallel_over.h"
#include "modeling/point_triangle_distance.h"

namespace ps {
namespace {

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

// === Uniform grid over the faces' boxes (rest positions)
// Cells of the mean face extent; each face is listed in every cell its box overlaps (refined
// meshes have faces of similar size, so that is a few cells each). CSR storage.
//
// The queries read the listed items of a few cells per moved vertex, hundreds of items in all on
// a needle-soup refinement (stress seed 737: 2.2M items for 200k faces, 500-600 read per query,
// over a gigabyte per call), so an item is kept to 16 bytes: the face, three flags and the face's
// normal. The flags say whether the cell is the face's lowest cell along each axis, which is all
// the ownership rule below needs (until 2026-12-07 the item held that cell's coordinates, 28
// bytes; the items array went from 62 to 35 MB and is no longer zeroed before it is filled).
class Grid {
 public:
  struct Item {
    std::uint32_t key;  // face << 3 | first-cell flags (bit k: the face's lowest cell along axis k)
    float nx, ny, nz;   // the face's unit rest normal
    int face() const { return static_cast<int>(key >> 3); }
  };
  static_assert(sizeof(Item) == 16);

  Grid(const std::vector<Vec3>& p, const std::vector<Face>& faces, const std::vector<Vec3>& normals) {
    Box3 all;
    double extent_sum = 0;
    std::vector<Box3> boxes(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (int v : faces[f]) boxes[f].extend(p[idx(v)]);
      extent_sum += boxes[f].size().maxCoeff();
      all.extend(boxes[f].min);
      all.extend(boxes[f].max);
    }
    origin_ = all.min;
    const Vec3 size = all.size();
    double h = faces.empty() ? 1.0 : extent_sum / static_cast<double>(faces.size());
    // At most about four cells per face, and never a zero cell (flat or point-like input).
    const double max_cells = 4.0 * static_cast<double>(std::max<std::size_t>(faces.size(), 1)) + 8.0;
    h = std::max(h, 1e-300);
    for (;;) {
      for (int k = 0; k < 3; ++k) dims_[idx(k)] = static_cast<long>(std::floor(size[k] / h)) + 1;
      if (static_cast<double>(dims_[0]) * static_cast<double>(dims_[1]) * static_cast<double>(dims_[2]) <= max_cells) break;
      h *= 1.5;
    }
    inv_h_ = 1.0 / h;
    const std::size_t cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
    start_.assign(cells + 1, 0);
    // fn(cell, flags) for every cell of the box's range; flags as in Item::key.
    auto for_cells = [&](const Box3& b, auto&& fn) {
      const auto lo = cell_of(b.min), hi = cell_of(b.max);
      for (long z = lo[2]; z <= hi[2]; ++z)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long x = lo[0]; x <= hi[0]; ++x)
            fn(static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x),
               (x == lo[0] ? 1u : 0u) | (y == lo[1] ? 2u : 0u) | (z == lo[2] ? 4u : 0u));
    };
    for (const Box3& b : boxes) for_cells(b, [&](std::size_t c, std::uint32_t) { ++start_[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    items_.reset(new Item[start_[cells]]);  // every item is written below
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const float nx = static_cast<float>(normals[f].x()), ny = static_cast<float>(normals[f].y()),
                  nz = static_cast<float>(normals[f].z());
      const std::uint32_t key = static_cast<std::uint32_t>(f) << 3;
      for_cells(boxes[f], [&](std::size_t c, std::uint32_t flags) { items_[fill[c]++] = Item{key | flags, nx, ny, nz}; });
    }
  }

  std::array<long, 3> cell_of(const Vec3& q) const {
    std::array<long, 3> c{};
    for (int k = 0; k < 3; ++k) {
      const double t = std::floor((q[k] - origin_[k]) * inv_h_);
      c[idx(k)] = static_cast<long>(std::clamp(t, 0.0, static_cast<double>(dims_[idx(k)] - 1)));
    }
    return c;
  }

  // A cell range, {lo x, y, z, hi x, y, z}: the cells of the box [lo, hi].
  using CellRange = std::array<long, 6>;
  CellRange range_of(const Vec3& lo, const Vec3& hi) const {
    const auto a = cell_of(lo), b = cell_of(hi);
    return {a[0], a[1], a[2], b[0], b[1], b[2]};
  }

  // fn(item) once for every face listed in a cell of `range` and not in a cell of `skip` (the
  // range of an earlier query inside this one, or none): a face listed in several of those cells
  // is reported by one of them, the one holding the lowest corner of the intersection of its
  // cell range with the query's. Along an axis that cell is the query's first cell or the face's
  // own first one, so the item's flags decide it. A face listed in a skipped cell was reported
  // by that earlier query; a face that is not lies only in cells outside it, its reporting cell
  // among them.
  template <class Fn>
  void for_each_near(const CellRange& range, const CellRange* skip, Fn&& fn) const {
    for (long z = range[2]; z <= range[5]; ++z)
      for (long y = range[1]; y <= range[4]; ++y)
        for (long x = range[0]; x <= range[3]; ++x) {
          if (skip && x >= (*skip)[0] && x <= (*skip)[3] && y >= (*skip)[1] && y <= (*skip)[4] && z >= (*skip)[2] &&
              z <= (*skip)[5])
            continue;
          // Flags the item must have: none along an axis where this is the query's first cell.
          const std::uint32_t need = (x != range[0] ? 1u : 0u) | (y != range[1] ? 2u : 0u) | (z != range[2] ? 4u : 0u);
          const std::size_t c = static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x);
          for (std::size_t i = start_[c]; i < start_[c + 1]; ++i) {
            const Item& item = items_[i];
            if ((item.key & need) != need) continue;
            fn(item);
          }
        }
  }

 private:
  Vec3 origin_ = Vec3::Zero();
  double inv_h_ = 1.0;
  std::array<long, 3> dims_{1, 1, 1};
  std::vector<std::size_t> start_;
  std::unique_ptr<Item[]> items_;
};

}  // namespace

// === The limit
int limit_moves_by_clearance(std::vector<Vec3>& positions, const std::vector<Vec3>& rest,
                             const std::vector<Face>& faces, const std::vector<std::uint8_t>* only) {
  const std::size_t nv = rest.size();
  if (positions.size() != nv || faces.empty() || (only && only->size() != nv)) return 0;
  std::vector<int> moved;
  for (std::size_t v = 0; v < nv; ++v)
    if (positions[v] != rest[v] && (!only || (*only)[v])) moved.push_back(static_cast<int>(v));
  if (moved.empty()) return 0;

  // Rest normals: unit per face, area-weighted unit per vertex.
  std::vector<Vec3> face_n(faces.size()), vertex_n(nv, Vec3::Zero());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Face& fc = faces[f];
    const Vec3 n = (rest[idx(fc[1])] - rest[idx(fc[0])]).cross(rest[idx(fc[2])] - rest[idx(fc[0])]);
    for (int v : fc) vertex_n[idx(v)] += n;
    const double len = n.norm();
    face_n[f] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  for (auto& n : vertex_n) {
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }

  const Grid grid(rest, faces, face_n);
  std::vector<std::uint8_t> limited(moved.size(), 0);
  parallel_ranges(moved.size(), 2048, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const int v = moved[i];
      const Vec3& r = rest[idx(v)];
      const Vec3 move = positions[idx(v)] - r;
      const double d = move.norm();
      const Vec3& nv_ = vertex_n[idx(v)];
      if (!(d > 0) || nv_ == Vec3::Zero()) continue;
      // Only faces nearer than d / kShare can limit the move.
      const double limit = d / kClearanceShare;
      double best = limit;  // the nearest facing face's rest distance
      const float nx = static_cast<float>(nv_.x()), ny = static_cast<float>(nv_.y()), nz = static_cast<float>(nv_.z());
      auto visit = [&](const Grid::Item& item) {
        if (!(item.nx * nx + item.ny * ny + item.nz * nz < 0.0f)) return;
        const Face& fc = faces[idx(item.face())];
        if (fc[0] == v || fc[1] == v || fc[2] == v) return;
        const Vec3 &a = rest[idx(fc[0])], &b = rest[idx(fc[1])], &c = rest[idx(fc[2])];
        // Box test first: most candidates are farther than the best distance so far.
        const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
        const Vec3 gap = (lo - r).cwiseMax(r - hi).cwiseMax(Vec3::Zero());
        if (gap.squaredNorm() >= best * best) return;
        best = std::min(best, point_triangle_distance(r, a, b, c));
      };
      // The cube of half the reach first: every face nearer than half the reach meets it, so a
      // facing face found within that distance (less the rounding of the cube's corners) is
      // the nearest one and the whole cube (eight times the volume) is not searched. best is
      // the minimum over the same faces either way, so the result is bit for bit that of one
      // search of the whole cube (eight_20: a quarter less time in the limit, output identical).
      const double rounding = 4.0 * std::numeric_limits<double>::epsilon() * (r.cwiseAbs().maxCoeff() + limit);
      // The second search skips the first one's cells: their faces were all seen (a face seen
      // again cannot lower best), and the order of the others is unchanged.
      const Grid::CellRange inner = grid.range_of(r - Vec3::Constant(0.5 * limit), r + Vec3::Constant(0.5 * limit));
      grid.for_each_near(inner, nullptr, visit);
      if (!(best <= 0.5 * limit - rounding))
        grid.for_each_near(grid.range_of(r - Vec3::Constant(limit), r + Vec3::Constant(limit)), &inner, visit);
      // Shortened to kShare c along its direction.
      const double allowed = kClearanceShare * best;
      if (best < limit && d > allowed) {  // (best == limit: nothing near; kShare * (d / kShare) may round below d)
        positions[idx(v)] = r + (allowed / d) * move;
        limited[i] = 1;
      }
    }
  });
  int count = 0;
  for (std::uint8_t l : limited) count += l;
  return count;
}

}  // namespace ps
