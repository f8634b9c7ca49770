// Union of stacked straight prisms in a slab zone (zone_stacked_union.h). The arrangement of two
// sets of loops is written by hand: CGAL's Arrangement_2 or Polygon_set_2 would compute it, but
// not keep which input edge each piece came from and where along it, which is what ties the
// caps at b and a to the walls around them. Cap regions are triangulated by CGAL's CDT.
#include "modeling/zone_stacked_union.h"

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/cdt_domains.h"
#include "modeling/polyline_crossing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <list>
#include <utility>

namespace ps {
namespace {

using cdt::CDT;
using cdt::mark_domains;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

Vec2 frame_point(const Vec3& p, int k) { return Vec2(p[(k + 1) % 3], p[(k + 2) % 3]); }

Vec3 lift(int k, double coord, const Vec2& q) { return axis_frame_point(k, coord, q); }

// One side's region: its primitives' loops over a shared point list.
struct Side {
  std::vector<std::vector<int>> loops;  // point ids, region on the left
  std::vector<const TriMesh*> prisms;   // with the id of their first bottom vertex
  std::vector<int> first_id;
  double bottom = 0, top = 0;           // the prisms' bottom (on the zone face) and top coordinates
};

// === Acceptance: a straight prism over its piece, along axis k, bottom at `base`.
// Returns the prism's top coordinate, or NaN.
double straight_prism_top(const TriMesh& m, const SectionPiece& piece, int k, double base) {
  std::size_t n = 0;
  for (const auto& l : piece.loops) n += l.size();
  if (m.vertices.size() != 2 * n || n == 0) return std::nan("");
  const double top = m.vertices[n][k];
  std::size_t i = 0;
  for (const auto& l : piece.loops)
    for (const auto& q : l) {
      const Vec3& b = m.vertices[i];
      const Vec3& t = m.vertices[i + n];
      if (b[k] != base || t[k] != top || frame_point(b, k) != q || frame_point(t, k) != q) return std::nan("");
      ++i;
    }
  return top;
}

// Exact point-in-region (even-odd over the loops; `p` must not lie on an edge).
bool inside(const Vec2& p, const std::vector<Vec2>& pts, const std::vector<std::vector<int>>& loops) {
  bool in = false;
  for (const auto& l : loops)
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2& c = pts[uz(l[i])];
      const Vec2& d = pts[uz(l[(i + 1) % l.size()])];
      if ((c.y() > p.y()) == (d.y() > p.y())) continue;
      const int o = orient2d(c, d, p);
      if (d.y() > c.y() ? o > 0 : o < 0) in = !in;
    }
  return in;
}

struct Edge {
  int loop, index;  // edge from loops[loop][index] to the next point
  Vec2 a, b;
};

std::vector<Edge> edges_of(const Side& s, const std::vector<Vec2>& pts) {
  std::vector<Edge> out;
  for (std::size_t l = 0; l < s.loops.size(); ++l)
    for (std::size_t i = 0; i < s.loops[l].size(); ++i)
      out.push_back({static_cast<int>(l), static_cast<int>(i), pts[uz(s.loops[l][i])],
                     pts[uz(s.loops[l][(i + 1) % s.loops[l].size()])]});
  return out;
}

struct Crossing {
  double t;  // parameter along the edge
  int id;    // point id of the crossing
};


// Counter-clockwise triangles (point ids) of the region bounded by the given edges (closed
// loops, pairwise meeting at most at shared end points), or nothing when the triangulation had
// to add a point (rounded edges crossing).
std::optional<std::vector<std::array<int, 3>>> triangulate_region(const std::vector<std::array<int, 2>>& edges,
                                                                   const std::vector<Vec2>& pts) {
  std::vector<std::array<int, 3>> tris;
  if (edges.empty()) return tris;
  CDT cdt;
  std::vector<CDT::Vertex_handle> vh(pts.size());
  std::size_t inserted = 0;
  auto vertex = [&](int id) {
    if (vh[uz(id)] == CDT::Vertex_handle()) {
      vh[uz(id)] = cdt.insert(CDT::Point(pts[uz(id)].x(), pts[uz(id)].y()));
      vh[uz(id)]->info() = id;
      ++inserted;
    }
    return vh[uz(id)];
  };
  for (const auto& e : edges) cdt.insert_constraint(vertex(e[0]), vertex(e[1]));
  if (cdt.number_of_vertices() != inserted) return std::nullopt;
  mark_domains(cdt);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info().nesting % 2 == 1) tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return tris;
}

}  // namespace

std::optional<TriMesh> stacked_zone_union(const Partition& part, const Zone& zone, const ZonePrimitives& prims) {
  if (prims.solids.empty() || prims.info.size() != prims.solids.size()) return std::nullopt;
  // === Sides: primitives on the low face (2k) and the high face (2k + 1) of one axis k.
  const int k = prims.info.front().face / 2;
  std::array<Side, 2> side;
  std::array<int, 2> plane{-1, -1};
  std::array<std::array<int, 2>, 2> cell{};
  std::vector<Vec2> pts;
  std::vector<const SectionPiece*> side_pieces[2];
  for (std::size_t i = 0; i < prims.solids.size(); ++i) {
    const PrimitiveInfo& info = prims.info[i];
    if (info.face / 2 != k || info.piece < 0 || uz(info.piece) >= part.pieces.size()) return std::nullopt;
    const int s = info.face % 2;  // a piece on a min face rises from the zone's min face
    const SectionPiece& piece = part.pieces[uz(info.piece)];
    if (plane[uz(s)] == -1) {
      plane[uz(s)] = piece.plane;
      cell[uz(s)] = piece.cell;
    } else if (piece.plane != plane[uz(s)] || piece.cell != cell[uz(s)]) {
      return std::nullopt;  // pieces of different planes may overlap
    }
    const double base = s == 0 ? zone.min[k] : zone.max[k];
    const double top = straight_prism_top(prims.solids[i], piece, k, base);
    if (std::isnan(top)) return std::nullopt;
    Side& sd = side[uz(s)];
    if (sd.prisms.empty()) {
      sd.bottom = base;
      sd.top = top;
    } else if (top != sd.top) {
      return std::nullopt;
    }
    if (!(s == 0 ? top > base && top <= zone.max[k] : top < base && top >= zone.min[k])) return std::nullopt;
    sd.prisms.push_back(&prims.solids[i]);
    sd.first_id.push_back(static_cast<int>(pts.size()));
    for (const auto& l : piece.loops) {
      std::vector<int> ids;
      for (const auto& q : l) {
        ids.push_back(static_cast<int>(pts.size()));
        pts.push_back(q);
      }
      sd.loops.push_back(std::move(ids));
    }
    side_pieces[s].push_back(&piece);
  }
  // Pieces of one side: each simple, pairwise disjoint (one face of one zone of the section's
  // plane, so disjoint by the stroke rules; checked exactly since clipping rounds).
  for (int s = 0; s < 2; ++s) {
    const auto& ps_ = side_pieces[s];
    for (std::size_t i = 0; i < ps_.size(); ++i) {
      if (!piece_is_simple(*ps_[i])) return std::nullopt;
      for (std::size_t j = i + 1; j < ps_.size(); ++j)
        for (const auto& la : ps_[i]->loops)
          for (const auto& lb : ps_[j]->loops)
            if (first_crossing_between(la, lb)) return std::nullopt;
    }
  }

  const bool both = !side[0].prisms.empty() && !side[1].prisms.empty();
  const double a = side[0].top, b = side[1].top;  // low prisms reach up to a, high ones down to b
  TriMesh out;
  auto append = [&](const TriMesh& m) {
    const int base = static_cast<int>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), m.vertices.begin(), m.vertices.end());
    for (const auto& f : m.faces) out.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  };
  if (!both || b > a) {
    // === Disjoint prisms: their concatenation.
    for (const auto& sd : side)
      for (const TriMesh* m : sd.prisms) append(*m);
    return out;
  }
  if (!(b < a) || !(zone.min[k] < b) || !(a < zone.max[k])) return std::nullopt;

  // === Crossings of the two sides' edges (sweep over x intervals, exact tests).
  const int first_crossing = static_cast<int>(pts.size());  // ids from here on are crossings
  const std::vector<Edge> ea = edges_of(side[0], pts), eb = edges_of(side[1], pts);
  std::vector<std::vector<Crossing>> on_a(ea.size()), on_b(eb.size());
  {
    std::vector<int> order_b(eb.size());
    for (std::size_t i = 0; i < eb.size(); ++i) order_b[i] = static_cast<int>(i);
    auto xmin = [](const Edge& e) { return std::min(e.a.x(), e.b.x()); };
    auto xmax = [](const Edge& e) { return std::max(e.a.x(), e.b.x()); };
    std::sort(order_b.begin(), order_b.end(), [&](int i, int j) { return xmin(eb[uz(i)]) < xmin(eb[uz(j)]); });
    std::vector<double> starts;
    for (int i : order_b) starts.push_back(xmin(eb[uz(i)]));
    double longest_b = 0;
    for (const auto& e : eb) longest_b = std::max(longest_b, xmax(e) - xmin(e));
    for (std::size_t i = 0; i < ea.size(); ++i) {
      const Edge& e = ea[i];
      const double lo = xmin(e) - longest_b, hi = xmax(e);
      auto it = std::lower_bound(starts.begin(), starts.end(), lo);
      for (auto pos = static_cast<std::size_t>(it - starts.begin()); pos < starts.size() && starts[pos] <= hi; ++pos) {
        const std::size_t j = uz(order_b[pos]);
        const Edge& f = eb[j];
        if (xmax(f) < xmin(e) || std::max(f.a.y(), f.b.y()) < std::min(e.a.y(), e.b.y()) ||
            std::min(f.a.y(), f.b.y()) > std::max(e.a.y(), e.b.y()))
          continue;
        if (!segments_intersect(e.a, e.b, f.a, f.b)) continue;
        const int o1 = orient2d(e.a, e.b, f.a), o2 = orient2d(e.a, e.b, f.b);
        const int o3 = orient2d(f.a, f.b, e.a), o4 = orient2d(f.a, f.b, e.b);
        if (o1 * o2 >= 0 || o3 * o4 >= 0) return std::nullopt;  // touching, a vertex on an edge, overlap
        const Vec2 r = e.b - e.a, q = f.b - f.a, w = f.a - e.a;
        const double den = r.x() * q.y() - r.y() * q.x();
        const double t = (w.x() * q.y() - w.y() * q.x()) / den;
        const double u = (w.x() * r.y() - w.y() * r.x()) / den;
        constexpr double kMargin = 1e-9;
        if (!(t > kMargin && t < 1 - kMargin && u > kMargin && u < 1 - kMargin)) return std::nullopt;
        const int id = static_cast<int>(pts.size());
        pts.push_back(e.a + t * r);
        on_a[i].push_back({t, id});
        on_b[j].push_back({u, id});
      }
    }
  }
  // No two points equal (the triangulations would merge them).
  {
    std::vector<Vec2> sorted(pts);
    std::sort(sorted.begin(), sorted.end(),
              [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return std::nullopt;
  }

  // === Split loops: point ids with crossings inserted; per split edge, inside the other side.
  struct Split {
    std::vector<std::vector<int>> loops;
    std::vector<std::vector<char>> in_other;                    // edge loops[l][i] -> next
    std::vector<std::vector<std::vector<int>>> edge_crossings;  // per original edge, in order
  };
  auto split = [&](const Side& sd, std::vector<std::vector<Crossing>>& on, const Side& other) -> std::optional<Split> {
    Split sp;
    std::size_t e = 0;
    for (const auto& loop : sd.loops) {
      std::vector<int> ids;
      std::vector<std::vector<int>> per_edge;
      for (std::size_t i = 0; i < loop.size(); ++i, ++e) {
        auto& c = on[e];
        std::sort(c.begin(), c.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
        for (std::size_t m = 1; m < c.size(); ++m)
          if (!(c[m].t > c[m - 1].t)) return std::nullopt;
        ids.push_back(loop[i]);
        std::vector<int> xs;
        for (const auto& x : c) {
          ids.push_back(x.id);
          xs.push_back(x.id);
        }
        per_edge.push_back(std::move(xs));
      }
      // Inside the other side: decided exactly at the loop's first point (an input point, on
      // no edge of the other side: checked above), toggled at every crossing.
      bool in = inside(pts[uz(loop.front())], pts, other.loops);
      std::vector<char> flags;
      for (std::size_t i = 0; i < ids.size(); ++i) {
        flags.push_back(in ? 1 : 0);
        if (ids[(i + 1) % ids.size()] >= first_crossing) in = !in;
      }
      if (in != (inside(pts[uz(loop.front())], pts, other.loops))) return std::nullopt;  // odd crossings
      sp.loops.push_back(std::move(ids));
      sp.in_other.push_back(std::move(flags));
      sp.edge_crossings.push_back(std::move(per_edge));
    }
    return sp;
  };
  const auto sa = split(side[0], on_a, side[1]);
  const auto sb = split(side[1], on_b, side[0]);
  if (!sa || !sb) return std::nullopt;

  // === Caps at b (P_B \ P_A, facing -e_k) and at a (P_A \ P_B, facing +e_k).
  std::vector<std::array<int, 2>> cap_b, cap_a;
  auto collect = [](const Split& sp, bool want_in, bool reverse, std::vector<std::array<int, 2>>& out_edges) {
    for (std::size_t l = 0; l < sp.loops.size(); ++l) {
      const auto& ids = sp.loops[l];
      for (std::size_t i = 0; i < ids.size(); ++i) {
        if ((sp.in_other[l][i] != 0) != want_in) continue;
        const int p = ids[i], q = ids[(i + 1) % ids.size()];
        out_edges.push_back(reverse ? std::array<int, 2>{q, p} : std::array<int, 2>{p, q});
      }
    }
  };
  collect(*sb, false, false, cap_b);
  collect(*sa, true, true, cap_b);
  collect(*sa, false, false, cap_a);
  collect(*sb, true, true, cap_a);
  const auto tris_b = triangulate_region(cap_b, pts);
  const auto tris_a = triangulate_region(cap_a, pts);
  if (!tris_b || !tris_a) return std::nullopt;

  // === Assembly. Levels: 0 = the low face, 1 = b, 2 = a, 3 = the high face.
  const std::array<double, 4> level_coord{zone.min[k], b, a, zone.max[k]};
  std::array<std::vector<int>, 4> vid;
  for (auto& v : vid) v.assign(pts.size(), -1);
  auto V = [&](int level, int id) {
    int& slot = vid[uz(level)][uz(id)];
    if (slot < 0) {
      slot = static_cast<int>(out.vertices.size());
      out.vertices.push_back(lift(k, level_coord[uz(level)], pts[uz(id)]));
    }
    return slot;
  };
  // Bottom caps of the prisms, unchanged: the low side's at level 0, the high side's at 3.
  for (int s = 0; s < 2; ++s) {
    const Side& sd = side[uz(s)];
    for (std::size_t p = 0; p < sd.prisms.size(); ++p) {
      const TriMesh& m = *sd.prisms[p];
      const int n = static_cast<int>(m.vertices.size() / 2);
      for (const auto& f : m.faces)
        if (f[0] < n && f[1] < n && f[2] < n)
          out.faces.push_back({V(3 * s, sd.first_id[p] + f[0]), V(3 * s, sd.first_id[p] + f[1]),
                               V(3 * s, sd.first_id[p] + f[2])});
    }
  }
  // Outer walls: P_A over [0, b] with its edge at b split; P_B over [a, 3] with its edge at a
  // split. Each original edge p -> q is a polygon fanned from one corner.
  for (std::size_t l = 0; l < side[0].loops.size(); ++l) {
    const auto& loop = side[0].loops[l];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int p = loop[i], q = loop[(i + 1) % loop.size()];
      std::vector<int> chain{V(1, q)};  // along the top edge, from q back to p
      const auto& xs = sa->edge_crossings[l][i];
      for (auto it = xs.rbegin(); it != xs.rend(); ++it) chain.push_back(V(1, *it));
      chain.push_back(V(1, p));
      const int p0 = V(0, p);
      out.faces.push_back({p0, V(0, q), chain.front()});
      for (std::size_t c = 0; c + 1 < chain.size(); ++c) out.faces.push_back({p0, chain[c], chain[c + 1]});
    }
  }
  for (std::size_t l = 0; l < side[1].loops.size(); ++l) {
    const auto& loop = side[1].loops[l];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int p = loop[i], q = loop[(i + 1) % loop.size()];
      std::vector<int> chain{V(2, p)};  // along the bottom edge, from p to q
      for (int x : sb->edge_crossings[l][i]) chain.push_back(V(2, x));
      chain.push_back(V(2, q));
      const int p3 = V(3, p);
      for (std::size_t c = 0; c + 1 < chain.size(); ++c) out.faces.push_back({chain[c], chain[c + 1], p3});
      out.faces.push_back({chain.back(), V(3, q), p3});
    }
  }
  // Middle walls over [b, a]: split edges of either side outside the other.
  for (const Split* sp : {&*sa, &*sb})
    for (std::size_t l = 0; l < sp->loops.size(); ++l) {
      const auto& ids = sp->loops[l];
      for (std::size_t i = 0; i < ids.size(); ++i) {
        if (sp->in_other[l][i] != 0) continue;
        const int p = ids[i], q = ids[(i + 1) % ids.size()];
        const int pb = V(1, p), qb = V(1, q), qa = V(2, q), pa = V(2, p);
        out.faces.push_back({pb, qb, qa});
        out.faces.push_back({pb, qa, pa});
      }
    }
  for (const auto& t : *tris_b) out.faces.push_back({V(1, t[0]), V(1, t[2]), V(1, t[1])});
  for (const auto& t : *tris_a) out.faces.push_back({V(2, t[0]), V(2, t[1]), V(2, t[2])});

  // === The only inexact step is the rounding of crossing points: check the result. Faces
  // whose vertices are all input points are pieces of the exact union's boundary (caps
  // triangulated with exact predicates, walls in their exact planes), so only faces touching a
  // rounded crossing are tested against the rest. (The stitched surface is tested whole again.)
  const MeshTopology topo = mesh_topology(out);
  if (!topo.closed || !topo.manifold() || !topo.consistently_oriented || topo.degenerate_faces > 0 ||
      !(topo.signed_volume > 0))
    return std::nullopt;
  std::vector<char> rounded(out.vertices.size(), 0);
  for (int level = 1; level <= 2; ++level)
    for (std::size_t id = uz(first_crossing); id < pts.size(); ++id)
      if (vid[uz(level)][id] >= 0) rounded[uz(vid[uz(level)][id])] = 1;
  const std::vector<int> near_rounded = faces_touching(out, rounded);
  if (!near_rounded.empty() && !intersecting_face_pairs(out.vertices, out.faces, near_rounded).empty())
    return std::nullopt;
  return out;
}

}  // namespace ps
