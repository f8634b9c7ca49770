// Self-intersection test of snapped frusta: see the header.
#include "modeling/snapped_self_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <cmath>
#include <cstddef>
#include <optional>

namespace ps::exact {
namespace {

using Vertex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

struct Found {};  // thrown out of the box sweep at the first intersecting pair

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

// How two faces h and g touch combinatorially: `shared` corners; for one, its positions si in h
// and sj in g; for two, the positions r in h and s in g of the corners not shared.
struct Shape {
  int shared = 0, si = -1, sj = -1, r = -1, s = -1;
};

template <class T>
const T& at(const std::array<T, 3>& c, int i) {
  return c[static_cast<std::size_t>(((i % 3) + 3) % 3)];
}

// Coplanar faces, given by their projections into a plane where the projection is one-to-one:
// the 2D form of the rules below.
template <class Kt>
bool faces_meet_2(const std::array<typename Kt::Point_2, 3>& h, const std::array<typename Kt::Point_2, 3>& g,
                  const Shape& sh) {
  if (sh.shared == 2) {
    // The third corners on the same side of the shared edge: folded onto each other.
    const auto& a = at(h, sh.r + 1);
    const auto& b = at(h, sh.r + 2);
    const CGAL::Orientation o1 = CGAL::orientation(a, b, at(h, sh.r));
    const CGAL::Orientation o2 = CGAL::orientation(a, b, at(g, sh.s));
    return o1 != CGAL::COLLINEAR && o1 == o2;
  }
  const typename Kt::Triangle_2 th(h[0], h[1], h[2]), tg(g[0], g[1], g[2]);
  if (sh.shared == 1)
    return CGAL::do_intersect(th, typename Kt::Segment_2(at(g, sh.sj + 1), at(g, sh.sj + 2))) ||
           CGAL::do_intersect(tg, typename Kt::Segment_2(at(h, sh.si + 1), at(h, sh.si + 2)));
  return CGAL::do_intersect(th, tg);
}

// The axis of the component of n largest in magnitude: dropping it projects a plane with
// normal n one-to-one.
int largest_axis(const Vec3& n) {
  int c = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[c])) c = k;
  return c;
}

// Drops coordinate c of a point.
template <class Kt>
typename Kt::Point_2 drop(const typename Kt::Point_3& p, int c) {
  return c == 0 ? typename Kt::Point_2(p.y(), p.z()) : c == 1 ? typename Kt::Point_2(p.z(), p.x())
                                                              : typename Kt::Point_2(p.x(), p.y());
}

// True when the projections along axis c prove that the faces do not meet improperly; false
// when they do not decide. A point where a segment meets a triangle in 3D projects into both
// projections, so disjoint projections (exact 2D predicates) mean disjoint faces; with a shared
// edge, third corners on opposite sides of it in a projection where the face h is not flat
// are on opposite sides within any common plane too. Neighbouring faces of a smooth wall or an
// almost flat cap are nearly coplanar, which sends CGAL's 3D predicates to exact arithmetic;
// their projections along the normal's largest axis are far from degenerate.
template <class Kt>
bool separated_in_projection(const std::array<typename Kt::Point_3, 3>& h, const std::array<typename Kt::Point_3, 3>& g,
                             const Shape& sh, int c) {
  using P2 = typename Kt::Point_2;
  const std::array<P2, 3> h2{drop<Kt>(h[0], c), drop<Kt>(h[1], c), drop<Kt>(h[2], c)};
  const std::array<P2, 3> g2{drop<Kt>(g[0], c), drop<Kt>(g[1], c), drop<Kt>(g[2], c)};
  const CGAL::Orientation oh = CGAL::orientation(h2[0], h2[1], h2[2]);
  if (oh == CGAL::COLLINEAR) return false;
  if (sh.shared == 2) {
    const P2& a = at(h2, sh.r + 1);
    const P2& b = at(h2, sh.r + 2);
    const CGAL::Orientation o1 = CGAL::orientation(a, b, at(h2, sh.r));
    const CGAL::Orientation o2 = CGAL::orientation(a, b, at(g2, sh.s));
    return o2 != CGAL::COLLINEAR && o1 != o2;
  }
  if (CGAL::orientation(g2[0], g2[1], g2[2]) == CGAL::COLLINEAR) return false;
  const typename Kt::Triangle_2 th(h2[0], h2[1], h2[2]), tg(g2[0], g2[1], g2[2]);
  if (sh.shared == 1)
    return !CGAL::do_intersect(th, typename Kt::Segment_2(at(g2, sh.sj + 1), at(g2, sh.sj + 2))) &&
           !CGAL::do_intersect(tg, typename Kt::Segment_2(at(h2, sh.si + 1), at(h2, sh.si + 2)));
  return !CGAL::do_intersect(th, tg);
}

// CGAL's rules (Polygon_mesh_processing/self_intersections.h, do_faces_intersect): a shared
// edge is an intersection when the four corners are coplanar and the third corners lie on the
// same side of it; a shared vertex when the edge of either face opposite it meets the other
// face; otherwise any contact. `c` is the axis to try projecting along first.
template <class Kt>
bool faces_meet_3(const std::array<typename Kt::Point_3, 3>& h, const std::array<typename Kt::Point_3, 3>& g,
                  const Shape& sh, int c) {
  if (c >= 0 && separated_in_projection<Kt>(h, g, sh, c)) return false;
  if (sh.shared == 2) {
    const auto& a = at(h, sh.r + 1);
    const auto& b = at(h, sh.r + 2);
    const auto& r = at(h, sh.r);
    const auto& s = at(g, sh.s);
    return CGAL::coplanar(a, b, r, s) && CGAL::coplanar_orientation(a, b, r, s) == CGAL::POSITIVE;
  }
  const typename Kt::Triangle_3 th(h[0], h[1], h[2]), tg(g[0], g[1], g[2]);
  if (sh.shared == 1)
    return CGAL::do_intersect(th, typename Kt::Segment_3(at(g, sh.sj + 1), at(g, sh.sj + 2))) ||
           CGAL::do_intersect(tg, typename Kt::Segment_3(at(h, sh.si + 1), at(h, sh.si + 2)));
  return CGAL::do_intersect(th, tg);
}

}  // namespace

bool snapped_self_intersects(const SurfaceMesh& sm, const std::vector<std::array<int, 3>>& tags,
                             const std::vector<Plane>& planes) {
  // Corners per face in CGAL's order (target of the face's halfedge, then around).
  std::vector<std::array<Vertex, 3>> corners;
  std::vector<Box> boxes;
  corners.reserve(sm.number_of_faces());
  boxes.reserve(sm.number_of_faces());
  for (FaceIndex f : sm.faces()) {
    const auto h = sm.halfedge(f);
    const std::array<Vertex, 3> c{sm.target(h), sm.target(sm.next(h)), sm.source(h)};
    CGAL::Bbox_3 b = sm.point(c[0]).bbox() + sm.point(c[1]).bbox() + sm.point(c[2]).bbox();
    boxes.emplace_back(b, corners.size());
    corners.push_back(c);
  }

  // Whether vertex v lies exactly on plane p: asked once per (vertex, plane), for tagged
  // planes only (-1 unknown, 0 no, 1 yes).
  const std::size_t nv = sm.number_of_vertices();
  std::vector<std::array<signed char, 3>> on(nv, {-1, -1, -1});
  auto tag_of = [&](Vertex v, int k) {
    const std::size_t i = v.idx();
    return i < tags.size() ? tags[i][static_cast<std::size_t>(k)] : -1;
  };
  auto exactly_on = [&](Vertex v, int k) {
    signed char& s = on[v.idx()][static_cast<std::size_t>(k)];
    if (s < 0) {
      const Plane& pl = planes[static_cast<std::size_t>(tag_of(v, k))];
      const K::Point_3& p = sm.point(v);
      s = (K::FT(pl.normal.x()) * p.x() + K::FT(pl.normal.y()) * p.y() + K::FT(pl.normal.z()) * p.z() ==
           K::FT(pl.offset))
              ? 1
              : 0;
    }
    return s == 1;
  };
  // A plane holding all six corners of the pair exactly, or -1.
  auto common_plane = [&](const std::array<Vertex, 3>& a, const std::array<Vertex, 3>& b) {
    for (int k = 0; k < 3; ++k) {
      const int t = tag_of(a[0], k);
      if (t < 0 || static_cast<std::size_t>(t) >= planes.size()) continue;
      bool all = true;
      for (const auto* face : {&a, &b})
        for (Vertex v : *face) {
          int kv = -1;
          for (int j = 0; j < 3 && kv < 0; ++j)
            if (tag_of(v, j) == t) kv = j;
          if (kv < 0 || !exactly_on(v, kv)) {
            all = false;
            break;
          }
        }
      if (all) return t;
    }
    return -1;
  };

  // Points exactly representable as doubles (every untagged point, and tagged ones that happen
  // to be): pairs made only of such points are tested on CGAL's Epick kernel, whose exact
  // fallback (Mpzf) is far cheaper than the lazy kernel's rationals. The top of a frustum is
  // such a cap: planar only up to rounding, so its pairs are never decided by intervals.
  // (The points were evaluated exactly by the caller, so an approximation that is a single
  // double is the exact value.)
  std::vector<std::optional<Epick::Point_3>> as_double(nv);
  for (Vertex v : sm.vertices()) {
    const auto& a = CGAL::approx(sm.point(v));
    if (a.x().is_point() && a.y().is_point() && a.z().is_point())
      as_double[v.idx()] = Epick::Point_3(a.x().inf(), a.y().inf(), a.z().inf());
  }

  auto pair_intersects = [&](const std::array<Vertex, 3>& hv, const std::array<Vertex, 3>& gv) {
    Shape shape;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (hv[static_cast<std::size_t>(i)] == gv[static_cast<std::size_t>(j)]) {
          if (shape.shared == 0) {
            shape.si = i;
            shape.sj = j;
          }
          ++shape.shared;
        }
    if (shape.shared >= 3) return true;  // the same triangle twice
    if (shape.shared == 2) {
      for (int i = 0; i < 3; ++i)
        if (hv[static_cast<std::size_t>(i)] != gv[0] && hv[static_cast<std::size_t>(i)] != gv[1] &&
            hv[static_cast<std::size_t>(i)] != gv[2])
          shape.r = i;
      for (int j = 0; j < 3; ++j)
        if (gv[static_cast<std::size_t>(j)] != hv[0] && gv[static_cast<std::size_t>(j)] != hv[1] &&
            gv[static_cast<std::size_t>(j)] != hv[2])
          shape.s = j;
    }
    const int plane = common_plane(hv, gv);
    if (plane >= 0) {
      // In the plane, projected along the axis of its normal's largest component.
      const int c = largest_axis(planes[static_cast<std::size_t>(plane)].normal);
      auto Q = [&](Vertex v) { return drop<K>(sm.point(v), c); };
      return faces_meet_2<K>({Q(hv[0]), Q(hv[1]), Q(hv[2])}, {Q(gv[0]), Q(gv[1]), Q(gv[2])}, shape);
    }
    bool doubles = true;
    for (Vertex v : hv) doubles = doubles && as_double[v.idx()].has_value();
    for (Vertex v : gv) doubles = doubles && as_double[v.idx()].has_value();
    if (doubles) {
      auto D = [&](Vertex v) { return *as_double[v.idx()]; };
      const std::array<Epick::Point_3, 3> h{D(hv[0]), D(hv[1]), D(hv[2])};
      // Projected first along the axis of the largest component of h's normal.
      auto V = [](const Epick::Point_3& p) { return Vec3(p.x(), p.y(), p.z()); };
      const int c = largest_axis((V(h[1]) - V(h[0])).cross(V(h[2]) - V(h[0])));
      return faces_meet_3<Epick>(h, {D(gv[0]), D(gv[1]), D(gv[2])}, shape, c);
    }
    auto P = [&](Vertex v) { return sm.point(v); };
    return faces_meet_3<K>({P(hv[0]), P(hv[1]), P(hv[2])}, {P(gv[0]), P(gv[1]), P(gv[2])}, shape, -1);
  };

  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
      if (pair_intersects(corners[a.info()], corners[b.info()])) throw Found{};
    });
  } catch (const Found&) {
    return true;
  }
  return false;
}

}  // namespace ps::exact
