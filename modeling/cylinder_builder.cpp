// Cylinders (prisms) per zone, thesis 4.3 (Eq. 4.1) and 4.4. Caps are CGAL constrained Delaunay
// triangulations (exact predicates) of the section pieces.
#include "modeling/cylinder_builder.h"

#include "modeling/face_intersections.h"
#include "modeling/cdt_domains.h"
#include "modeling/polyline_crossing.h"

#include <algorithm>
#include <list>

namespace ps {
namespace {

using cdt::CDT;
using cdt::mark_domains;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

Vec3 lift(int k, double coord, const Vec2& q) { return axis_frame_point(k, coord, q); }

struct PieceCache {
  std::vector<Vec2> points;                   // concatenated loops
  std::vector<std::array<int, 2>> loop_range;  // [begin, end) per loop
  std::vector<std::array<int, 3>> tris;        // counter-clockwise in 2D
  bool simple = false;  // loops simple and pairwise disjoint (exact 2D test), so a straight prism is valid
};


// === Axis ranks for the pull factors (4.3)
// The pull factors must differ between axes (below), but a factor tied to an axis's name made the
// result depend on how the input names its axes: a cyclic permutation of x, y and z, exact in
// doubles, changed the volume of generated inputs by up to 0.5%. So the axes are ranked by what
// the input itself says about them, all of which a permutation of the axes carries along: the
// box's extent, then the number of grid planes, then their offsets relative to the box. Only
// axes equal in all three are ranked by name. The box is fixed while sketching, so the ranks
// change only in that tie.
using AxisRanks = std::array<int, 3>;

AxisRanks axis_ranks(const ZoneGrid& g) {
  std::array<std::vector<double>, 3> key;
  for (std::size_t a = 0; a < 3; ++a) {
    const double lo = g.box.min[static_cast<int>(a)], ext = g.box.max[static_cast<int>(a)] - lo;
    key[a].push_back(ext);
    key[a].push_back(static_cast<double>(g.coords[a].size()));
    for (double c : g.coords[a]) key[a].push_back(ext > 0.0 ? (c - lo) / ext : 0.0);
  }
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return key[uz(y)] < key[uz(x)]; });
  AxisRanks rank{};
  for (int r = 0; r < 3; ++r) rank[uz(order[uz(r)])] = r;
  return rank;
}

// The top's 2D points, with points on side faces that carry a section pulled into the zone
// (thesis 4.3). Halves the pull (starting from `first_scale` of it) until no cap triangle flips
// and no wall edge reverses its direction (a pulled point moved past its unpulled neighbour
// folds the wall quad between them: a self-intersecting prism, stress seed 281).
std::vector<Vec2> perturbed_top(const PieceCache& pc, const SectionPiece& piece, const Zone& zone,
                                const CylinderOptions& opt, const AxisRanks& rank, double first_scale = 1.0) {
  const int k = piece.axis;
  const int ax[2] = {(k + 1) % 3, (k + 2) % 3};
  std::vector<Vec2> top = pc.points;
  bool any = false;
  for (int d = 0; d < 2; ++d)
    for (int side = 0; side < 2; ++side) any = any || zone.face_has_section(2 * ax[d] + side);
  if (!any || opt.perturb <= 0.0) return top;
  // The pull never exceeds a fifth of the piece's own extent along the pull axis, so a small
  // piece clipped at a zone corner keeps a top that sits over its bottom (larger pulls sheared
  // the walls of tiny pieces into self-intersection).
  Vec2 lo = pc.points.front(), hi = pc.points.front();
  for (const auto& q : pc.points) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  double scale = first_scale;
  for (int attempt = 0; attempt < 12; ++attempt, scale *= 0.5) {
    top = pc.points;
    for (std::size_t i = 0; i < top.size(); ++i) {
      for (int d = 0; d < 2; ++d) {
        const int a = ax[d];
        // The factor differs per (prism axis, pull axis) pair so that prisms of different
        // axes never get walls of equal slope: equal slopes made exactly coincident edge-edge
        // contacts between primitives, which the corefinement turns into zero-area fins. The
        // axes enter by their rank (axis_ranks), not their name, so that permuting the input's
        // axes permutes the output.
        const double factor = 1.0 + 0.173 * rank[uz(k)] + 0.291 * rank[uz(a)];
        const double delta = scale * std::min(opt.perturb * factor * zone.extent(a), 0.2 * (hi[d] - lo[d]));
        if (pc.points[i][d] == zone.min[a] && zone.face_has_section(2 * a)) top[i][d] = pc.points[i][d] + delta;
        if (pc.points[i][d] == zone.max[a] && zone.face_has_section(2 * a + 1)) top[i][d] = pc.points[i][d] - delta;
      }
    }
    bool ok = true;
    for (const auto& t : pc.tris) {
      const double before = orient(pc.points[uz(t[0])], pc.points[uz(t[1])], pc.points[uz(t[2])]);
      const double after = orient(top[uz(t[0])], top[uz(t[1])], top[uz(t[2])]);
      if (!(after > 1e-3 * before)) {
        ok = false;
        break;
      }
    }
    for (const auto& r : pc.loop_range)
      for (int i = r[0]; ok && i < r[1]; ++i) {
        const int j = i + 1 == r[1] ? r[0] : i + 1;
        const Vec2 b = pc.points[uz(j)] - pc.points[uz(i)], t = top[uz(j)] - top[uz(i)];
        if (!(t.dot(b) > 1e-3 * b.squaredNorm())) ok = false;
      }
    if (ok) return top;
  }
  return pc.points;
}

// A prism between the axis coordinates c0 (bottom, the piece's plane side) and c1 along axis k,
// bottom points `bottom`, top points `top` (2D, same indexing). Outward oriented.
TriMesh prism(const PieceCache& pc, int k, double c0, double c1, const std::vector<Vec2>& top) {
  TriMesh m;
  const int n = static_cast<int>(pc.points.size());
  m.vertices.reserve(uz(2 * n));
  for (const auto& q : pc.points) m.vertices.push_back(lift(k, c0, q));
  for (const auto& q : top) m.vertices.push_back(lift(k, c1, q));
  // Built for a prism going towards +e_k (c1 > c0): bottom cap faces -e_k, top cap faces +e_k.
  for (const auto& t : pc.tris) {
    m.faces.push_back({t[0], t[2], t[1]});
    m.faces.push_back({t[0] + n, t[1] + n, t[2] + n});
  }
  if (c1 < c0)
    for (auto& f : m.faces) std::swap(f[1], f[2]);
  // Walls: one quad per loop edge, outward oriented (a, b, c, d). A top pulled at one end of the
  // edge only makes the quad non-planar, and then its diagonal decides the solid: it is chosen
  // by the geometry, the one giving the convex fold (exact orientation test), so that the prism
  // does not depend on the direction of its loops (a mirrored input traverses them the other way
  // round; with the diagonal tied to the loop order a half turn of the input moved its volume by
  // up to 6.5e-5). A planar quad keeps a-c: either diagonal gives the same solid. Planar by
  // construction, without the test: both ends moved alike (a rectangle or parallelogram), or the
  // edge and the difference of the moves along one axis (exact zeros below); the exact test of
  // such a quad falls back to multiprecision and made the primitives stage 60% dearer.
  auto point = [&](int v) {
    const Vec3& p = m.vertices[uz(v)];
    return cdt::K::Point_3(p.x(), p.y(), p.z());
  };
  for (const auto& r : pc.loop_range) {
    for (int i = r[0]; i < r[1]; ++i) {
      const int j = i + 1 == r[1] ? r[0] : i + 1;
      const std::array<int, 4> q =
          c1 < c0 ? std::array<int, 4>{i, i + n, j + n, j} : std::array<int, 4>{i, j, j + n, i + n};
      const Vec2 e = pc.points[uz(j)] - pc.points[uz(i)];
      const Vec2 dp = (top[uz(j)] - pc.points[uz(j)]) - (top[uz(i)] - pc.points[uz(i)]);
      const bool planar = (e.x() == 0.0 || dp.y() == 0.0) && (e.y() == 0.0 || dp.x() == 0.0);
      const bool across_ac =
          planar || CGAL::orientation(point(q[0]), point(q[1]), point(q[2]), point(q[3])) != CGAL::POSITIVE;
      if (across_ac) {
        m.faces.push_back({q[0], q[1], q[2]});
        m.faces.push_back({q[0], q[2], q[3]});
      } else {
        m.faces.push_back({q[0], q[1], q[3]});
        m.faces.push_back({q[1], q[2], q[3]});
      }
    }
  }
  return m;
}

bool self_intersects(const TriMesh& m) { return !self_intersecting_pairs(m).empty(); }

// The prism of a zone's last segment with the perturbed top, checked: the top test above is
// local (caps and wall edges in 2D), so the whole prism is tested for self-intersection and
// rebuilt with a quarter, a sixteenth, then none of the pull (a straight prism over a simple
// piece cannot intersect itself). Corefinement's contract needs valid operands; its
// preconditions are compiled out.
TriMesh checked_prism(const PieceCache& pc, const SectionPiece& piece, const Zone& zone, int k, double c0, double c1,
                      const CylinderOptions& opt, const AxisRanks& rank, const CylinderCache* previous,
                      CylinderCache* next, bool* verified) {
  for (const double first : {1.0, 0.25, 0.0625}) {
    const std::vector<Vec2> top = perturbed_top(pc, piece, zone, opt, rank, first);
    if (top == pc.points) break;  // not pulled: the straight prism below
    PrismKey key{prism(pc, k, c0, c1, top)};
    ContentHash hash;
    hash.mesh(key.prism);
    if (!cached(previous ? &previous->self_intersecting : nullptr, next ? &next->self_intersecting : nullptr, hash.h,
                key, [&] { return self_intersects(key.prism); })) {
      *verified = true;
      return std::move(key.prism);
    }
  }
  *verified = pc.simple;
  return prism(pc, k, c0, c1, pc.points);
}

}  // namespace

Vec3 axis_frame_point(int k, double coord, const Vec2& q) {
  Vec3 p;
  p[k] = coord;
  p[(k + 1) % 3] = q.x();
  p[(k + 2) % 3] = q.y();
  return p;
}

// (cylinder_builder.h) Whether a straight prism over the piece is free of self-intersections: every loop has at least
// three points, no two consecutive points equal (a zero-length wall), and the loops neither
// cross nor touch themselves or each other. Exact (orient2d with an exact fallback). Pieces with
// more than kMaxPairwiseLoops loops are not tested pairwise and count as unproven: the union
// then runs its own 3D test, as it does for every operand it is not told is valid.
bool piece_is_simple(const SectionPiece& piece) {
  constexpr std::size_t kMaxPairwiseLoops = 16;
  if (piece.loops.empty() || piece.loops.size() > kMaxPairwiseLoops) return false;
  for (const auto& loop : piece.loops) {
    if (loop.size() < 3) return false;
    for (std::size_t i = 0; i < loop.size(); ++i)
      if (loop[i] == loop[(i + 1) % loop.size()]) return false;
    if (first_self_crossing(loop)) return false;
  }
  for (std::size_t a = 0; a < piece.loops.size(); ++a)
    for (std::size_t b = a + 1; b < piece.loops.size(); ++b)
      if (first_crossing_between(piece.loops[a], piece.loops[b])) return false;
  return true;
}

std::vector<std::array<int, 3>> triangulate_piece(const SectionPiece& piece) {
  CDT cdt;
  int base = 0;
  for (const auto& loop : piece.loops) {
    std::vector<CDT::Vertex_handle> vh;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      vh.push_back(cdt.insert(CDT::Point(loop[i].x(), loop[i].y())));
      vh.back()->info() = base + static_cast<int>(i);
    }
    for (std::size_t i = 0; i < vh.size(); ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % vh.size()]);
    base += static_cast<int>(loop.size());
  }
  mark_domains(cdt);
  std::vector<std::array<int, 3>> tris;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info().nesting % 2 == 1)
      tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return tris;
}

std::vector<ZonePrimitives> build_cylinders(const Partition& part, const CylinderOptions& opt,
                                            const CylinderCache* previous, CylinderCache* next) {
  const ZoneGrid& g = part.grid;
  const AxisRanks rank = axis_ranks(g);
  std::vector<PieceCache> cache(part.pieces.size());
  for (std::size_t i = 0; i < part.pieces.size(); ++i) {
    const SectionPiece& p = part.pieces[i];
    PieceCache& pc = cache[i];
    for (const auto& loop : p.loops) {
      const int b = static_cast<int>(pc.points.size());
      pc.points.insert(pc.points.end(), loop.begin(), loop.end());
      pc.loop_range.push_back({b, static_cast<int>(pc.points.size())});
    }
    ContentHash hash;
    for (const auto& loop : p.loops) hash.points(loop);
    pc.tris = cached(previous ? &previous->caps : nullptr, next ? &next->caps : nullptr, hash.h, p.loops,
                     [&] { return triangulate_piece(p); });
    pc.simple = piece_is_simple(p);
  }

  std::vector<ZonePrimitives> out(part.zones.size());
  for (std::size_t zi = 0; zi < part.zones.size(); ++zi) {
    const Zone& z = part.zones[zi];
    if (z.type == ZoneType::kEmpty) continue;
    for (int f = 0; f < 6; ++f) {
      const int k = f / 2;
      const double dir = f % 2 == 0 ? 1.0 : -1.0;  // into the zone
      for (int pid : z.face_pieces[uz(f)]) {
        const SectionPiece& piece = part.pieces[uz(pid)];
        const PieceCache& pc = cache[uz(pid)];
        const double c0 = f % 2 == 0 ? z.min[k] : z.max[k];
        if (z.type == ZoneType::kBody) {
          // === Body zone: Eq. 4.1 with the 4.3 perturbation.
          const double h = z.extent(k) * (1.0 - opt.height_margin);
          bool verified = false;
          out[zi].solids.push_back(checked_prism(pc, piece, z, k, c0, c0 + dir * h, opt, rank, previous, next, &verified));
          out[zi].info.push_back({pid, f, true, static_cast<int>(pc.points.size()), verified});
          continue;
        }
        // === End zone: stretch across empty zones (4.4), one segment per zone.
        std::array<int, 3> cell = z.cell;
        double bottom = c0;
        const int far_face = 2 * k + (f % 2 == 0 ? 1 : 0);
        for (bool first = true;; first = false) {
          const std::size_t id = uz(g.index(cell));
          const Zone& zz = part.zones[id];
          const bool last = zz.on_box[uz(far_face)] || (!first && zz.type != ZoneType::kEmpty);
          if (last) {
            const double h = zz.extent(k) * (1.0 - opt.height_margin);
            bool verified = false;
            out[id].solids.push_back(checked_prism(pc, piece, zz, k, bottom, bottom + dir * h, opt, rank, previous, next, &verified));
            out[id].info.push_back({pid, f, false, static_cast<int>(pc.points.size()), verified});
            break;
          }
          const double top = f % 2 == 0 ? zz.max[k] : zz.min[k];
          out[id].solids.push_back(prism(pc, k, bottom, top, pc.points));
          out[id].info.push_back({pid, f, false, static_cast<int>(pc.points.size()), pc.simple});
          bottom = top;
          cell[uz(k)] += f % 2 == 0 ? 1 : -1;
        }
      }
    }
  }
  return out;
}

}  // namespace ps
