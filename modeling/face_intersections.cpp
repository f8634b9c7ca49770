// CGAL translation unit (kernel predicates and box intersection only, no PMP).
#include "modeling/face_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_3/Segment_3_Triangle_3.h>
#include <CGAL/Intersections_2/Segment_2_Triangle_2.h>
#include <CGAL/Intersections_2/Triangle_2_Triangle_2.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numbers>

#include "modeling/parallel_over.h"
#include "modeling/radix_sort.h"

namespace ps {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

Point to_point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }

// === Faces in a plane known exactly. Reconstructions from axis sections are mostly flat pieces
// of axis planes (caps, stitched zone faces) and walls parallel to an axis (prism walls, whose
// corners share their in-plane position two by two). There every neighbour pair is coplanar and
// CGAL's 3D predicates fall back to exact arithmetic (Mpzf) to find out. Two cases are known
// without arithmetic: all points share one coordinate (an axis plane), or their positions with
// one coordinate c dropped take only two distinct values (a plane containing e_c). Dropping a
// suitable coordinate then maps that plane onto 2D bijectively and affinely, so the 2D
// predicates (filtered, exact) give the same answers, at the cost of doubles.
using Point2 = K::Point_2;

// The coordinate whose dropping maps the plane of all `n` points onto 2D bijectively when that
// plane is known as above, or -1.
int flat_drop(const Point* const* pts, int n) {
  for (int c = 0; c < 3; ++c) {
    bool same = true;
    for (int i = 1; i < n && same; ++i) same = pts[i]->cartesian(c) == pts[0]->cartesian(c);
    if (same) return c;
  }
  for (int c = 0; c < 3; ++c) {
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    const Point* other = nullptr;
    bool two = true;
    for (int i = 1; i < n && two; ++i) {
      if (pts[i]->cartesian(a) == pts[0]->cartesian(a) && pts[i]->cartesian(b) == pts[0]->cartesian(b)) continue;
      if (!other) {
        other = pts[i];
        continue;
      }
      two = pts[i]->cartesian(a) == other->cartesian(a) && pts[i]->cartesian(b) == other->cartesian(b);
    }
    if (!two || !other) continue;
    // The plane holds e_c and the direction between the two positions: keep c and a coordinate
    // that direction moves along.
    return other->cartesian(a) != pts[0]->cartesian(a) ? b : a;
  }
  return -1;
}

Point2 drop(const Point& p, int c) {
  return c == 0 ? Point2(p.y(), p.z()) : c == 1 ? Point2(p.z(), p.x()) : Point2(p.x(), p.y());
}

// === A face's plane, for a filtered side test
// Most candidate pairs (about 70 per face on the refined 160k-face mesh of stress seed 938) are
// told apart by one face lying strictly on one side of the other's plane. CGAL's orientation
// predicate is exact but recomputes the plane for each point; here the plane is computed once
// per face, and each point costs a dot product and an error bound. The sign is certified only
// when it is larger than the bound; otherwise the caller asks the exact predicate.
//
// Why the bound holds: the value computed is n.(q - o) with n = (t1 - t0) x (t2 - t0), o = t0, a
// sum of six products a_i b_j d_k of differences. Each product passes through at most eight
// roundings (three differences, two products, the subtraction in n, two additions), so the
// computed value differs from det[t1 - t0, t2 - t0, q - t0] by at most ((1+u)^8 - 1) times the
// sum of the products' magnitudes, u = 2^-53; that sum computed in floating point is low by at
// most a factor (1+u)^-9. 16u covers both with room. Values so small that products could be
// subnormal (absolute rounding) are not certified, nor non-finite ones.
struct FacePlane {
  Vec3 o, n, m;  // a corner, the cross product, and |a_y b_z| + |a_z b_y| etc. for the bound
};

FacePlane face_plane(const std::vector<Vec3>& pts, const Face& f) {
  const Vec3& t0 = pts[idx(f[0])];
  const Vec3 a = pts[idx(f[1])] - t0, b = pts[idx(f[2])] - t0;
  return {t0, a.cross(b),
          Vec3(std::abs(a.y() * b.z()) + std::abs(a.z() * b.y()), std::abs(a.z() * b.x()) + std::abs(a.x() * b.z()),
               std::abs(a.x() * b.y()) + std::abs(a.y() * b.x()))};
}

// +1 or -1: q is strictly on that side of the plane (the sign of CGAL::orientation(t0, t1, t2,
// q)); 0: not certified (on the plane, or too close to tell in doubles).
int certified_side(const FacePlane& pl, const Vec3& q) {
  const Vec3 d = q - pl.o;
  const double s = pl.n.dot(d);
  const double perm = std::abs(d.x()) * pl.m.x() + std::abs(d.y()) * pl.m.y() + std::abs(d.z()) * pl.m.z();
  if (!(perm > 1e-250) || !(perm < 1e300)) return 0;
  const double bound = 0x1p-49 * perm;
  return s > bound ? 1 : s < -bound ? -1 : 0;
}

// All `count` points certified strictly on one side of the plane.
bool certified_one_side(const FacePlane& pl, const Vec3* const* q, int count) {
  const int s0 = certified_side(pl, *q[0]);
  if (s0 == 0) return false;
  for (int i = 1; i < count; ++i)
    if (certified_side(pl, *q[i]) != s0) return false;
  return true;
}

// === Separating axes in the faces' plane
// The plane tests above cannot tell apart two faces lying in one plane, nor faces that nearly
// do: the refined cap of an oblique section is flat up to the rounding of its split points, and
// most pairs of faces there reached the exact predicates, whose interval filters fail so close
// to coplanar and which then compute in multi-precision (Mpzf: about 9% of the CPU time of stress
// seed 737, perf). Two convex sets are disjoint when their projections onto some axis are; for
// coplanar ones the in-plane normals of their edges are such axes (the separating axis theorem in
// 2D), and nearly coplanar ones separate on them too when their gap exceeds the tilt. Any axis
// will do, so the axis is the computed vector itself, taken as exact; each projection is
// certified as in certified_side: relative to one point o, (p - o) . a is computed with an error
// of at most 16u times the sum of |d_k a_k| (one rounding in each difference, three in the dot
// product), plus an absolute 1e-300 for products in the subnormal range. Non-finite values
// compare false and certify nothing.

// True when the convex hulls of a (na points: a triangle or a segment) and b are certified
// disjoint on an axis n x e, for e an edge of either. n: a normal of the plane they (nearly) lie in.
bool certified_apart(const Vec3* const* a, int na, const Vec3* const* b, int nb, const Vec3& n) {
  const Vec3& o = *a[0];
  auto interval = [&](const Vec3* const* pts, int count, const Vec3& ax, double& lo, double& hi) {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (int i = 0; i < count; ++i) {
      const Vec3 d = *pts[i] - o;
      const double v = d.dot(ax);
      const double err =
          0x1p-49 * (std::abs(d.x() * ax.x()) + std::abs(d.y() * ax.y()) + std::abs(d.z() * ax.z())) + 1e-300;
      lo = std::min(lo, v - err);
      hi = std::max(hi, v + err);
    }
  };
  auto apart_on = [&](const Vec3& e) {
    const Vec3 ax = n.cross(e);
    double alo, ahi, blo, bhi;
    interval(a, na, ax, alo, ahi);
    interval(b, nb, ax, blo, bhi);
    return ahi < blo || bhi < alo;
  };
  // A triangle's three edges; a segment's one.
  for (int i = 0; i < (na == 3 ? 3 : 1); ++i)
    if (apart_on(*a[(i + 1) % na] - *a[i])) return true;
  for (int i = 0; i < (nb == 3 ? 3 : 1); ++i)
    if (apart_on(*b[(i + 1) % nb] - *b[i])) return true;
  return false;
}

// The normal of the better shaped of two faces, for certified_apart: the larger ratio of
// |cross product|^2 to the fourth power of the longest edge (a needle's computed normal points
// anywhere).
Vec3 steadier_normal(const Vec3* const* f, const FacePlane& pf, const Vec3* const* g, const FacePlane& pg) {
  auto shape = [](const Vec3* const* t, const FacePlane& pl) {
    const double l = std::max({(*t[1] - *t[0]).squaredNorm(), (*t[2] - *t[1]).squaredNorm(), (*t[0] - *t[2]).squaredNorm()});
    return l > 0 ? pl.n.squaredNorm() / (l * l) : 0.0;
  };
  return shape(f, pf) >= shape(g, pg) ? pf.n : pg.n;
}

// True when faces f and g (distinct) intersect beyond what they share combinatorially. pf and pg
// are their planes (face_plane).
bool faces_intersect(const std::vector<Vec3>& pts, const Face& f, const Face& g, bool df, bool dg,
                     const FacePlane& pf, const FacePlane& pg) {
  int shared = 0, fi = -1, gi = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (f[idx(i)] == g[idx(j)]) {
        ++shared;
        if (fi < 0) {
          fi = i;
          gi = j;
        }
      }
  // The filtered quick rejection (the exact one below decides what this leaves open): with no
  // shared vertex, one face strictly on one side of the other's plane; with one, each face's two
  // other corners strictly on one side of the other's plane.
  // Then separating axes in the plane (certified_apart) for what is left, mostly pairs of one
  // flat region: with one shared vertex, each face's opposite edge must miss the other face.
  if (!df && !dg && shared <= 1) {
    const Vec3* qf[3] = {&pts[idx(f[0])], &pts[idx(f[1])], &pts[idx(f[2])]};
    const Vec3* qg[3] = {&pts[idx(g[0])], &pts[idx(g[1])], &pts[idx(g[2])]};
    if (shared == 0) {
      if (certified_one_side(pf, qg, 3)) return false;
      if (certified_one_side(pg, qf, 3)) return false;
      if (certified_apart(qf, 3, qg, 3, steadier_normal(qf, pf, qg, pg))) return false;
    } else {
      const Vec3* g_opp[2] = {qg[(gi + 1) % 3], qg[(gi + 2) % 3]};
      const Vec3* f_opp[2] = {qf[(fi + 1) % 3], qf[(fi + 2) % 3]};
      const bool g_side = certified_one_side(pf, g_opp, 2), f_side = certified_one_side(pg, f_opp, 2);
      if (g_side && f_side) return false;
      const Vec3 n = steadier_normal(qf, pf, qg, pg);
      if ((g_side || certified_apart(qf, 3, g_opp, 2, n)) && (f_side || certified_apart(qg, 3, f_opp, 2, n)))
        return false;
    }
  }
  const Point p[3] = {to_point(pts[idx(f[0])]), to_point(pts[idx(f[1])]), to_point(pts[idx(f[2])])};
  const Point q[3] = {to_point(pts[idx(g[0])]), to_point(pts[idx(g[1])]), to_point(pts[idx(g[2])])};
  if (shared >= 3) return true;  // a duplicated face
  if (shared == 2) {
    // Shared edge: intersect only when coplanar and folded onto each other, i.e. the two
    // opposite vertices lie on the same side of the shared edge within the common plane.
    int fo = 0, go = 0;
    for (int i = 0; i < 3; ++i) {
      bool in_g = false, in_f = false;
      for (int j = 0; j < 3; ++j) {
        if (f[idx(i)] == g[idx(j)]) in_g = true;
        if (g[idx(i)] == f[idx(j)]) in_f = true;
      }
      if (!in_g) fo = i;
      if (!in_f) go = i;
    }
    const Point& a = p[(fo + 1) % 3];
    const Point& b = p[(fo + 2) % 3];
    const Point* four[4] = {&a, &b, &p[fo], &q[go]};
    if (const int c = flat_drop(four, 4); c >= 0) {
      const Point2 a2 = drop(a, c), b2 = drop(b, c);
      const CGAL::Orientation of = CGAL::orientation(a2, b2, drop(p[fo], c));
      const CGAL::Orientation og = CGAL::orientation(a2, b2, drop(q[go], c));
      if (of != CGAL::COLLINEAR && og != CGAL::COLLINEAR) return of == og;  // folded onto each other
    }
    return CGAL::coplanar(a, b, p[fo], q[go]) &&
           CGAL::coplanar_orientation(a, b, p[fo], q[go]) == CGAL::POSITIVE;
  }
  const K::Triangle_3 tf(p[0], p[1], p[2]), tg(q[0], q[1], q[2]);
  if (df || dg) {
    // CGAL's triangle tests need real triangles. A degenerate face with no shared vertex is
    // tested as its edges against the other face; with a shared vertex it cannot be told
    // apart from touching, so it is not reported.
    if (shared != 0 || (df && dg)) return false;
    const Point* seg = df ? p : q;
    const K::Triangle_3& tri = df ? tg : tf;
    for (int i = 0; i < 3; ++i) {
      const Point& s0 = seg[i];
      const Point& s1 = seg[(i + 1) % 3];
      if (s0 != s1 && CGAL::do_intersect(tri, K::Segment_3(s0, s1))) return true;
    }
    return false;
  }
  {
    const Point* six[6] = {&p[0], &p[1], &p[2], &q[0], &q[1], &q[2]};
    if (const int c = flat_drop(six, 6); c >= 0) {
      const Point2 f2[3] = {drop(p[0], c), drop(p[1], c), drop(p[2], c)};
      const Point2 g2[3] = {drop(q[0], c), drop(q[1], c), drop(q[2], c)};
      if (CGAL::orientation(f2[0], f2[1], f2[2]) != CGAL::COLLINEAR &&
          CGAL::orientation(g2[0], g2[1], g2[2]) != CGAL::COLLINEAR) {
        const K::Triangle_2 tf2(f2[0], f2[1], f2[2]), tg2(g2[0], g2[1], g2[2]);
        if (shared == 1)  // as below: each face against the other's edge opposite the shared vertex
          return CGAL::do_intersect(tf2, K::Segment_2(g2[(gi + 1) % 3], g2[(gi + 2) % 3])) ||
                 CGAL::do_intersect(tg2, K::Segment_2(f2[(fi + 1) % 3], f2[(fi + 2) % 3]));
        return CGAL::do_intersect(tf2, tg2);
      }
    }
  }
  // Quick rejection with the (filtered, exact) orientation predicate: points strictly on one
  // side of the other face's plane cannot meet it. Most candidate pairs are neighbours that
  // end here.
  auto one_side = [](const Point* t, const Point* others, int count) {
    const CGAL::Orientation o0 = CGAL::orientation(t[0], t[1], t[2], others[0]);
    if (o0 == CGAL::COPLANAR) return false;
    for (int i = 1; i < count; ++i)
      if (CGAL::orientation(t[0], t[1], t[2], others[i]) != o0) return false;
    return true;
  };
  if (shared == 1) {
    const Point f_opp[2] = {p[(fi + 1) % 3], p[(fi + 2) % 3]};
    const Point g_opp[2] = {q[(gi + 1) % 3], q[(gi + 2) % 3]};
    const bool g_misses_f = one_side(p, g_opp, 2);
    const bool f_misses_g = one_side(q, f_opp, 2);
    if (g_misses_f && f_misses_g) return false;
    return (!g_misses_f && CGAL::do_intersect(tf, K::Segment_3(g_opp[0], g_opp[1]))) ||
           (!f_misses_g && CGAL::do_intersect(tg, K::Segment_3(f_opp[0], f_opp[1])));
  }
  if (one_side(p, q, 3) || one_side(q, p, 3)) return false;
  return CGAL::do_intersect(tf, tg);
}

// The face's corners are collinear (exact predicate): a segment or a point, not a triangle.
bool collinear_face(const std::vector<Vec3>& pts, const Face& f) {
  return CGAL::collinear(to_point(pts[idx(f[0])]), to_point(pts[idx(f[1])]), to_point(pts[idx(f[2])]));
}

CGAL::Bbox_3 face_box(const std::vector<Vec3>& pts, const Face& f) {
  const Vec3& a = pts[idx(f[0])];
  const Vec3& b = pts[idx(f[1])];
  const Vec3& c = pts[idx(f[2])];
  return CGAL::Bbox_3(std::min({a.x(), b.x(), c.x()}), std::min({a.y(), b.y(), c.y()}),
                      std::min({a.z(), b.z(), c.z()}), std::max({a.x(), b.x(), c.x()}),
                      std::max({a.y(), b.y(), c.y()}), std::max({a.z(), b.z(), c.z()}));
}

// Angle between two vectors from y = |u x v| >= 0 and x = u . v, within 2e-5 rad of the exact
// value (a minimax polynomial for atan on [0, 1]); about 4x cheaper than std::atan2, which
// dominated the fan test. Only used to count turns, where errors below 1e-3 rad are harmless.
double fast_angle(double y, double x) {
  const double ax = std::abs(x);
  if (!(ax > 0.0 || y > 0.0)) return 0.0;
  const bool swap = y > ax;
  const double z = swap ? ax / y : y / ax;
  const double z2 = z * z;
  double a = z * (0.9998660 + z2 * (-0.3302995 + z2 * (0.1801410 + z2 * (-0.0851330 + z2 * 0.0208351))));
  if (swap) a = 0.5 * std::numbers::pi - a;
  return x < 0.0 ? std::numbers::pi - a : a;
}

// Vertices whose fan is a graph over the plane normal to the fan's area-weighted normal N: every
// incident face is turned towards N by a clear margin (n_f . N > 0.2 |n_f| |N|), so every face
// projects with positive orientation, and the projected angles at the vertex sum to one turn
// (not two or more). The projected faces then tile the full angle around the vertex once, and
// projection is one-to-one on each face, so two faces of the fan meet only in their shared
// vertex or edge: their exact test can be skipped. The margins keep the double computation far
// from any sign decision; a vertex that fails simply has its pairs tested exactly.
// Only vertices of the faces in `query` (all faces when it is null) are decided; the others
// come back 0. A pair that shares a vertex always has a queried face, so that is all callers need,
// and the rollback passes of mesh improvement query a few faces of a large mesh.
std::vector<std::uint8_t> embedded_fans(const std::vector<Vec3>& pts, const std::vector<Face>& faces,
                                        const std::vector<int>* query) {
  const std::size_t nv = pts.size(), nf = faces.size();
  constexpr std::size_t kMinParallel = 4096;
  std::vector<std::uint8_t> needed(nv, query ? 0 : 1), face_needed(nf, query ? 0 : 1);
  if (query) {
    for (int f : *query)
      for (int v : faces[idx(f)]) needed[idx(v)] = 1;
    for (std::size_t f = 0; f < nf; ++f)
      face_needed[f] = needed[idx(faces[f][0])] || needed[idx(faces[f][1])] || needed[idx(faces[f][2])];
  }
  // Face normals, and which faces are too degenerate to trust: the computed normal is trusted
  // only when the face is far from degenerate (sine of its angle at corner 0 above 1e-4) and its
  // edges are long compared with the rounding of its coordinates; otherwise its vertices' pairs
  // are tested exactly.
  std::vector<Vec3> face_n(nf);
  std::vector<std::uint8_t> untrusted(nf, 0);
  parallel_ranges(nf, kMinParallel, [&](std::size_t b, std::size_t e) {
    for (std::size_t f = b; f < e; ++f) {
      if (!face_needed[f]) continue;
      const Face& fc = faces[f];
      const Vec3 e1 = pts[idx(fc[1])] - pts[idx(fc[0])], e2 = pts[idx(fc[2])] - pts[idx(fc[0])];
      face_n[f] = e1.cross(e2);
      const double coord = std::max({pts[idx(fc[0])].cwiseAbs().maxCoeff(), pts[idx(fc[1])].cwiseAbs().maxCoeff(),
                                     pts[idx(fc[2])].cwiseAbs().maxCoeff()});
      const double l1 = e1.norm(), l2 = e2.norm(), l3 = (e2 - e1).norm();
      untrusted[f] = !(face_n[f].norm() > 1e-4 * l1 * l2) || !(std::min({l1, l2, l3}) > 1e-9 * coord);
    }
  });
  // Faces around each vertex, in increasing face order (corner k of face f as 3f + k).
  std::vector<std::size_t> start(nv + 1, 0);
  for (const Face& fc : faces)
    for (int v : fc)
      if (needed[idx(v)]) ++start[idx(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::size_t> corner(start[nv]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < nf; ++f)
      for (std::size_t k = 0; k < 3; ++k)
        if (needed[idx(faces[f][k])]) corner[fill[idx(faces[f][k])]++] = 3 * f + k;
  }
  std::vector<std::uint8_t> good(nv, 0);
  parallel_ranges(nv, kMinParallel, [&](std::size_t vb, std::size_t ve) {
    for (std::size_t v = vb; v < ve; ++v) {
      if (!needed[v]) continue;
      Vec3 n = Vec3::Zero();
      bool bad = false;
      for (std::size_t i = start[v]; i < start[v + 1]; ++i) {
        n += face_n[corner[i] / 3];
        bad = bad || untrusted[corner[i] / 3];
      }
      if (bad) continue;
      const double nn = n.norm();
      const Vec3 u = n / nn;
      double turn = 0;
      for (std::size_t i = start[v]; i < start[v + 1] && !bad; ++i) {
        const std::size_t f = corner[i] / 3, k = corner[i] % 3;
        if (!(face_n[f].dot(n) > 0.2 * face_n[f].norm() * nn)) {
          bad = true;
          break;
        }
        const Face& fc = faces[f];
        Vec3 e1 = pts[idx(fc[(k + 1) % 3])] - pts[v];
        Vec3 e2 = pts[idx(fc[(k + 2) % 3])] - pts[v];
        e1 -= e1.dot(u) * u;
        e2 -= e2.dot(u) * u;
        turn += fast_angle(e1.cross(e2).norm(), e1.dot(e2));
      }
      good[v] = !bad && turn > 1.5 * std::numbers::pi && turn < 2.5 * std::numbers::pi;
    }
  });
  return good;
}


// === Broad phase on a uniform grid
// Why not only CGAL::box_intersection_d: it is sequential, and on the refined meshes of mesh
// improvement its sorting and scanning were 38% of the whole improvement (perf, hand_ok, one
// thread); a query of a third of the faces took longer than a scan of all of them. The faces
// there are much alike in size, which a uniform grid suits. The queried faces are entered in the
// cells their boxes overlap (sorted by cell); pairs of queried faces are found within each cell,
// and every other face looks up the cells its box overlaps. A pair of overlapping boxes is
// reported only from the cell holding the lowest corner of their intersection, which both boxes
// overlap, so each pair exactly once and no hash set is needed. Both loops run in parallel. The
// grid declines (returns false, nothing visited) when its cost estimate is poor: boxes spanning
// many cells, or crowded cells (a fine patch in a coarse mesh); the caller then uses CGAL's
// box intersection. The pairs are the same either way.
// Without short-circuits: the outcome is close to random in the grid's pair loops, where the
// branches of && were mispredicted.
bool boxes_overlap(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  return (a.xmin() <= b.xmax()) & (b.xmin() <= a.xmax()) & (a.ymin() <= b.ymax()) & (b.ymin() <= a.ymax()) &
         (a.zmin() <= b.zmax()) & (b.zmin() <= a.zmax());
}

// The cells a box overlaps, lo[k]..hi[k] per axis (inclusive).
struct CellRange {
  std::array<std::uint32_t, 3> lo, hi;
  std::size_t count() const {
    return std::size_t{hi[0] - lo[0] + 1} * std::size_t{hi[1] - lo[1] + 1} * std::size_t{hi[2] - lo[2] + 1};
  }
};

// A queried face as entered in one cell, with what the pair loops read: its box and the cell of
// its box's lowest corner. Kept in cell order, so the loop over a cell's pairs reads memory in
// sequence (with face indices into the box array, the random reads were most of its time).
struct CellEntry {
  CGAL::Bbox_3 box;
  std::array<std::uint32_t, 3> lo;
  int face;
};

// The boxes overlap and the cell `at` holds the lowest corner of their intersection (given
// each box's lowest cell), branch-free for the same reason.
bool owned_pair(const CGAL::Bbox_3& a, const std::array<std::uint32_t, 3>& a_lo, const CGAL::Bbox_3& b,
                const std::array<std::uint32_t, 3>& b_lo, const std::array<std::uint32_t, 3>& at) {
  return boxes_overlap(a, b) & (std::max(a_lo[0], b_lo[0]) == at[0]) & (std::max(a_lo[1], b_lo[1]) == at[1]) &
         (std::max(a_lo[2], b_lo[2]) == at[2]);
}

class FaceGrid {
 public:
  // Every pair {f, g} (f < g, at least one of them queried) whose boxes overlap (closed), once:
  // `visit(f, g, chunk)`, called concurrently for different chunks in [0, chunks).
  template <class Visit>
  static bool for_each_pair(const std::vector<CGAL::Bbox_3>& boxes, const std::vector<std::uint8_t>& queried,
                            const std::vector<int>& query, std::size_t chunks, const Visit& visit) {
    const std::size_t n = boxes.size(), q = query.size();
    if (n < 2000) return false;  // CGAL's scan is as fast at this size
    FaceGrid grid(boxes);
    if (!grid.ok_) return false;
    // Every face's cell range, once (the estimates and both loops below use it).
    std::vector<CellRange> range(n);
    parallel_ranges(n, 8192, [&](std::size_t b, std::size_t e) {
      for (std::size_t f = b; f < e; ++f) range[f] = grid.range_of(boxes[f]);
    });
    // Queried faces into cells.
    std::size_t total = 0;
    for (int f : query) {
      total += range[idx(f)].count();
      if (total > 16 * q + 64) return false;  // boxes spanning many cells: the sweep is better
    }
    // Grouped by cell: a radix sort of (cell, entry number) packed into 64 bits when they fit
    // (the linear cell index of the grid's own extent), std::sort otherwise. The pair loop below
    // then orders each cell's entries by x, and the lookups of the other faces rely on that.
    std::vector<std::uint64_t> cell_of_entry;
    std::vector<int> face_of_entry;
    cell_of_entry.reserve(total);
    face_of_entry.reserve(total);
    for (int f : query)
      grid.for_each_cell(range[idx(f)], [&](std::uint64_t cell) {
        cell_of_entry.push_back(cell);
        face_of_entry.push_back(f);
      });
    std::vector<std::size_t> order(total);
    const int cbits = bits_for(grid.num_cells_), ebits = bits_for(total);
    if (cbits + ebits <= 64) {
      std::vector<std::uint64_t> packed(total);
      for (std::size_t i = 0; i < total; ++i) packed[i] = (cell_of_entry[i] << ebits) | i;
      radix_sort(packed, cbits + ebits);
      const std::uint64_t emask = (std::uint64_t{1} << ebits) - 1;
      for (std::size_t i = 0; i < total; ++i) order[i] = static_cast<std::size_t>(packed[i] & emask);
    } else {
      for (std::size_t i = 0; i < total; ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return cell_of_entry[a] < cell_of_entry[b]; });
    }
    std::vector<CellEntry> entries(total);
    std::vector<std::size_t> run_start;
    std::vector<std::uint64_t> run_cell;
    std::size_t work = 0;
    for (std::size_t i = 0; i < total;) {
      const std::uint64_t cell = cell_of_entry[order[i]];
      std::size_t j = i;
      for (; j < total && cell_of_entry[order[j]] == cell; ++j) {
        const int f = face_of_entry[order[j]];
        entries[j] = {boxes[idx(f)], range[idx(f)].lo, f};
      }
      run_start.push_back(i);
      run_cell.push_back(cell);
      work += (j - i) * (j - i - 1) / 2;
      i = j;
    }
    run_start.push_back(total);
    // Crowded cells (all faces in a few cells would make this quadratic). Fine patches in a coarse
    // mesh stay well below the limit: eight_20's thin parts, about 110 box tests per queried face,
    // took 11.8 s of checks in the grid against 20.6 s in CGAL's scan.
    if (work > 1024 * q + 4096) return false;
    // The other faces' lookups: estimated first, for the same reasons.
    std::size_t lookups = 0;
    if (q < n) {
      for (std::size_t f = 0; f < n; ++f)
        if (!queried[f]) {
          lookups += range[f].count();
          if (lookups > 16 * n) return false;
        }
    }
    const std::size_t runs = run_cell.size();
    // Pairs of queried faces, cell by cell. A pair is reported from the cell of the lowest
    // corner of the two boxes' intersection: the cell of max(a.min, b.min) per axis, which is
    // the larger of the two boxes' lowest cells (the cell of a coordinate is monotone in it).
    // Within a cell the entries are sorted by their boxes' lowest x and swept: b is tested
    // against a only while b starts (in x) before a ends. On needle-soup unions the cells hold
    // about 150 entries each (the median box extent is a needle's length), and testing every
    // pair of a cell was most of the check (stress seed 217: 64M box tests per smoothing check).
    const std::size_t step = (runs + chunks - 1) / chunks;
    parallel_over(chunks, 0, [&](std::size_t c) {
      const std::size_t r_end = std::min(runs, (c + 1) * step);
      for (std::size_t r = std::min(runs, c * step); r < r_end; ++r) {
        const auto first = entries.begin() + static_cast<std::ptrdiff_t>(run_start[r]);
        const auto last = entries.begin() + static_cast<std::ptrdiff_t>(run_start[r + 1]);
        std::sort(first, last, [](const CellEntry& a, const CellEntry& b) {
          return a.box.xmin() < b.box.xmin() || (a.box.xmin() == b.box.xmin() && a.face < b.face);
        });
        const std::array<std::uint32_t, 3> at = grid.coords(run_cell[r]);
        for (std::size_t i = run_start[r]; i < run_start[r + 1]; ++i) {
          const CellEntry& a = entries[i];
          for (std::size_t j = i + 1; j < run_start[r + 1] && entries[j].box.xmin() <= a.box.xmax(); ++j) {
            const CellEntry& b = entries[j];
            if (owned_pair(a.box, a.lo, b.box, b.lo, at)) visit(std::min(a.face, b.face), std::max(a.face, b.face), c);
          }
        }
      }
    });
    if (q == n) return true;
    // Every other face against the queried faces in its cells, found through a hash table of
    // the occupied cells (open addressing, linear probing): one or two probes per cell where a
    // binary search over the runs took about 14 dependent reads (this loop was an eighth of
    // the mesh improvement on a 60k-face model, queries of 6k-20k faces).
    int tbits = 4;
    while ((std::size_t{1} << tbits) < 2 * runs) ++tbits;
    const std::uint64_t tmask = (std::uint64_t{1} << tbits) - 1;
    auto home = [&](std::uint64_t cell) { return (cell * 0x9E3779B97F4A7C15ull) >> (64 - tbits); };
    std::vector<std::uint32_t> table(std::size_t{1} << tbits, 0);  // run index + 1, 0 = empty
    for (std::size_t r = 0; r < runs; ++r) {
      std::uint64_t s = home(run_cell[r]);
      while (table[s] != 0) s = (s + 1) & tmask;
      table[s] = static_cast<std::uint32_t>(r + 1);
    }
    auto run_of = [&](std::uint64_t cell) -> std::size_t {
      for (std::uint64_t s = home(cell);; s = (s + 1) & tmask) {
        const std::uint32_t t = table[s];
        if (t == 0) return runs;
        if (run_cell[t - 1] == cell) return t - 1;
      }
    };
    const std::size_t face_step = (n + chunks - 1) / chunks;
    parallel_over(chunks, 0, [&](std::size_t c) {
      const std::size_t f_end = std::min(n, (c + 1) * face_step);
      for (std::size_t f = std::min(n, c * face_step); f < f_end; ++f) {
        if (queried[f]) continue;
        const CellRange& rf = range[f];
        grid.for_each_cell(rf, [&](std::uint64_t cell) {
          const std::size_t r = run_of(cell);
          if (r == runs) return;
          const std::array<std::uint32_t, 3> at = grid.coords(cell);
          // Sorted by lowest x (above): the entries after one starting beyond f's box miss it.
          for (std::size_t i = run_start[r]; i < run_start[r + 1] && entries[i].box.xmin() <= boxes[f].xmax(); ++i) {
            const CellEntry& b = entries[i];
            if (owned_pair(boxes[f], rf.lo, b.box, b.lo, at))
              visit(std::min(static_cast<int>(f), b.face), std::max(static_cast<int>(f), b.face), c);
          }
        });
      }
    });
    return true;
  }

 private:
  explicit FaceGrid(const std::vector<CGAL::Bbox_3>& boxes) {
    const std::size_t n = boxes.size();
    CGAL::Bbox_3 all;
    std::vector<double> extent(n);
    for (std::size_t f = 0; f < n; ++f) {
      all += boxes[f];
      extent[f] = std::max({boxes[f].xmax() - boxes[f].xmin(), boxes[f].ymax() - boxes[f].ymin(),
                            boxes[f].zmax() - boxes[f].zmin()});
    }
    if (!std::isfinite(all.xmin()) || !std::isfinite(all.xmax()) || !std::isfinite(all.ymin()) ||
        !std::isfinite(all.ymax()) || !std::isfinite(all.zmin()) || !std::isfinite(all.zmax()))
      return;
    // Cell size: twice the median box extent (a typical box meets 1-8 cells), and at least the
    // model's extent / 2^20 so that cell coordinates fit in 21 bits. (Factors 0.7-3 measured
    // alike on hand_ok.)
    std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(n / 2), extent.end());
    const double span = std::max({all.xmax() - all.xmin(), all.ymax() - all.ymin(), all.zmax() - all.zmin()});
    const double h = std::max(2.0 * extent[n / 2], span / static_cast<double>(1u << 20));
    if (!(h > 0) || !std::isfinite(h)) return;
    inv_ = 1.0 / h;
    origin_ = {all.xmin(), all.ymin(), all.zmin()};
    // Cells per axis: every box lies in the grid's extent, so its cells are below these.
    dims_ = {cell_of(all.xmax(), 0) + 1, cell_of(all.ymax(), 1) + 1, cell_of(all.zmax(), 2) + 1};
    num_cells_ = std::uint64_t{dims_[0]} * dims_[1] * dims_[2];
    ok_ = true;
  }

  // Monotone in x, so a box's cell range holds the cell of every point of the box.
  std::uint32_t cell_of(double x, std::size_t axis) const {
    const double c = std::floor((x - origin_[axis]) * inv_);
    return static_cast<std::uint32_t>(std::clamp(c, 0.0, static_cast<double>((1u << 21) - 1)));
  }
  CellRange range_of(const CGAL::Bbox_3& b) const {
    return {{cell_of(b.xmin(), 0), cell_of(b.ymin(), 1), cell_of(b.zmin(), 2)},
            {cell_of(b.xmax(), 0), cell_of(b.ymax(), 1), cell_of(b.zmax(), 2)}};
  }
  // Linear cell index (x major, then y, then z): below num_cells_.
  std::uint64_t key(std::uint64_t x, std::uint64_t y, std::uint64_t z) const { return (x * dims_[1] + y) * dims_[2] + z; }
  std::array<std::uint32_t, 3> coords(std::uint64_t cell) const {
    const auto z = static_cast<std::uint32_t>(cell % dims_[2]);
    cell /= dims_[2];
    return {static_cast<std::uint32_t>(cell / dims_[1]), static_cast<std::uint32_t>(cell % dims_[1]), z};
  }
  template <class F>
  void for_each_cell(const CellRange& r, const F& f) const {
    for (std::uint64_t x = r.lo[0]; x <= r.hi[0]; ++x)
      for (std::uint64_t y = r.lo[1]; y <= r.hi[1]; ++y)
        for (std::uint64_t z = r.lo[2]; z <= r.hi[2]; ++z) f(key(x, y, z));
  }

  bool ok_ = false;
  double inv_ = 0;
  std::array<double, 3> origin_{};
  std::array<std::uint32_t, 3> dims_{};
  std::uint64_t num_cells_ = 0;
};
}  // namespace

std::vector<std::array<int, 2>> intersecting_face_pairs(const std::vector<Vec3>& points,
                                                        const std::vector<Face>& faces,
                                                        const std::vector<int>& query_faces,
                                                        BroadPhase broad_phase) {
  std::vector<std::array<int, 2>> pairs;
  if (query_faces.empty() || faces.empty()) return pairs;
  const std::vector<std::uint8_t> embedded =
      embedded_fans(points, faces, 2 * query_faces.size() >= faces.size() ? nullptr : &query_faces);
  // Candidate pairs first (box overlaps, minus pairs sharing a vertex whose fan is embedded),
  // then the exact tests, in parallel chunks when there are many (a full check of a refined
  // 100k-face mesh has about a million; mesh improvement runs one per round).
  std::vector<std::array<int, 2>> candidates;
  auto shares_embedded_vertex = [&](int f, int g) {
    for (int v : faces[idx(f)])
      if (embedded[idx(v)] && (v == faces[idx(g)][0] || v == faces[idx(g)][1] || v == faces[idx(g)][2])) return true;
    return false;
  };
  auto candidate = [&](int f, int g) {
    if (f == g || shares_embedded_vertex(f, g)) return;
    candidates.push_back({f, g});
  };
  constexpr std::size_t kChunks = 64;
  if (broad_phase == BroadPhase::kAuto) {
    // The parallel grid (FaceGrid), testing each pair as it is found.
    std::vector<CGAL::Bbox_3> boxes(faces.size());
    std::vector<std::uint8_t> queried(faces.size(), 0), degenerate(faces.size(), 0);
    std::vector<FacePlane> planes(faces.size());
    for (int f : query_faces) queried[idx(f)] = 1;
    std::vector<int> query;  // each queried face once, in order
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (queried[f]) query.push_back(static_cast<int>(f));
    parallel_ranges(faces.size(), 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t f = b; f < e; ++f) {
        const Face& fc = faces[f];
        boxes[f] = face_box(points, fc);
        degenerate[f] = collinear_face(points, fc) ? 1 : 0;
        planes[f] = face_plane(points, fc);
      }
    });
    std::vector<std::vector<std::array<int, 2>>> found(kChunks);
    const bool gridded = FaceGrid::for_each_pair(boxes, queried, query, kChunks, [&](int f, int g, std::size_t c) {
      if (shares_embedded_vertex(f, g)) return;
      if (faces_intersect(points, faces[idx(f)], faces[idx(g)], degenerate[idx(f)] != 0, degenerate[idx(g)] != 0,
                          planes[idx(f)], planes[idx(g)]))
        found[c].push_back({f, g});
    });
    if (gridded) {
      for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
      std::sort(pairs.begin(), pairs.end());
      return pairs;
    }
  }
  // Brute-force scanning below 100 boxes: measured fastest on refined union meshes (10: 1.5x,
  // 2000 as in PMP: 2.5x slower).
  const std::ptrdiff_t cutoff = 100;
  std::vector<Box> all;
  all.reserve(faces.size());
  if (2 * query_faces.size() >= faces.size()) {
    for (std::size_t f = 0; f < faces.size(); ++f)
      all.emplace_back(face_box(points, faces[f]), static_cast<int>(f));
  } else {
    // Few faces queried (the rollback passes of mesh improvement): only faces whose boxes meet
    // the hull of the query boxes can intersect one, so the scan sorts those instead of all.
    CGAL::Bbox_3 hull = face_box(points, faces[idx(query_faces.front())]);
    for (int f : query_faces) hull += face_box(points, faces[idx(f)]);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const CGAL::Bbox_3 b = face_box(points, faces[f]);
      if (CGAL::do_overlap(b, hull)) all.emplace_back(b, static_cast<int>(f));
    }
  }
  if (2 * query_faces.size() >= faces.size()) {
    // Most faces are queried: one complete self-intersection scan reports each pair once.
    std::vector<std::uint8_t> queried(faces.size(), 0);
    for (int f : query_faces) queried[idx(f)] = 1;
    CGAL::box_self_intersection_d(
        all.begin(), all.end(),
        [&](const Box& a, const Box& b) {
          if (queried[idx(a.info())] || queried[idx(b.info())]) candidate(a.info(), b.info());
        },
        cutoff);
  } else {
    std::vector<Box> query;
    query.reserve(query_faces.size());
    for (int f : query_faces) query.emplace_back(face_box(points, faces[idx(f)]), f);
    CGAL::box_intersection_d(
        query.begin(), query.end(), all.begin(), all.end(),
        [&](const Box& a, const Box& b) { candidate(a.info(), b.info()); }, cutoff,
        CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
  }
  // Degeneracy (collinear corners) of the faces the candidates name, computed up front so the
  // parallel tests only read it.
  std::vector<std::uint8_t> degenerate(faces.size(), 0), named(faces.size(), 0);
  std::vector<FacePlane> planes(faces.size());
  for (const auto& c : candidates) named[idx(c[0])] = named[idx(c[1])] = 1;
  auto mark_degenerate = [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f)
      if (named[f]) {
        const Face& fc = faces[f];
        degenerate[f] = collinear_face(points, fc) ? 1 : 0;
        planes[f] = face_plane(points, fc);
      }
  };
  auto test_range = [&](std::size_t begin, std::size_t end, std::vector<std::array<int, 2>>& out) {
    for (std::size_t i = begin; i < end; ++i) {
      const int f = candidates[i][0], g = candidates[i][1];
      if (faces_intersect(points, faces[idx(f)], faces[idx(g)], degenerate[idx(f)] != 0, degenerate[idx(g)] != 0,
                          planes[idx(f)], planes[idx(g)]))
        out.push_back({std::min(f, g), std::max(f, g)});
    }
  };
  // Below this many candidates the hand-over to another thread costs more than it saves.
  constexpr std::size_t kParallelCandidates = 20000;
  if (candidates.size() < kParallelCandidates) {
    mark_degenerate(0, faces.size());
    test_range(0, candidates.size(), pairs);
  } else {
    const std::size_t face_step = (faces.size() + kChunks - 1) / kChunks;
    parallel_over(kChunks, 0, [&](std::size_t c) {
      mark_degenerate(std::min(faces.size(), c * face_step), std::min(faces.size(), (c + 1) * face_step));
    });
    const std::size_t step = (candidates.size() + kChunks - 1) / kChunks;
    std::vector<std::vector<std::array<int, 2>>> found(kChunks);
    parallel_over(kChunks, 0, [&](std::size_t c) {
      test_range(std::min(candidates.size(), c * step), std::min(candidates.size(), (c + 1) * step), found[c]);
    });
    for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

std::vector<std::array<int, 2>> self_intersecting_pairs(const TriMesh& mesh) {
  std::vector<int> all(mesh.faces.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return intersecting_face_pairs(mesh.vertices, mesh.faces, all);
}

}  // namespace ps
