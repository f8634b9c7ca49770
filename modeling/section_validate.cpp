// Stroke-rule validation of cross sections and nesting per plane. Segment tests use CGAL's
// exact predicates (Epick) so touching and crossing are decided exactly on the projected points.
#include "modeling/section_validate.h"

#include "modeling/polygon_triangulate.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace ps {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;
using S2 = K::Segment_2;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

std::string fmt(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Axis-aligned bounding box of a 2D polyline, for cheap rejection.
struct Box2 {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void add(const Vec2& p) {
    x0 = std::min(x0, p.x()); y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x()); y1 = std::max(y1, p.y());
  }
  bool overlaps(const Box2& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

Box2 seg_box(const Vec2& a, const Vec2& b) {
  Box2 r;
  r.add(a);
  r.add(b);
  return r;
}



}  // namespace

// === Plane frames
PlaneFrame plane_frame(const Plane& plane) {
  PlaneFrame f;
  f.normal = plane.normal;
  f.offset = plane.offset;
  f.axis = plane.axis();
  if (f.axis >= 0 && plane.normal[f.axis] > 0.0) {
    const int k = f.axis;
    f.u = Vec3::Unit((k + 1) % 3);
    f.v = Vec3::Unit((k + 2) % 3);
    f.origin = Vec3::Zero();
    f.origin[k] = plane.offset;
  } else {
    f.axis = -1;
    plane.basis(f.u, f.v);
    f.origin = plane.offset * plane.normal;
  }
  return f;
}

Vec2 PlaneFrame::to_2d(const Vec3& p) const {
  if (axis >= 0) return Vec2(p[(axis + 1) % 3], p[(axis + 2) % 3]);
  const Vec3 d = p - origin;
  return Vec2(d.dot(u), d.dot(v));
}

Vec3 PlaneFrame::to_3d(const Vec2& q) const {
  if (axis >= 0) {
    Vec3 p;
    p[axis] = offset;
    p[(axis + 1) % 3] = q.x();
    p[(axis + 2) % 3] = q.y();
    return p;
  }
  return origin + q.x() * u + q.y() * v;
}

// === Validation
Result<ValidatedSections> validate_sections(const SectionSet& in) {
  ValidatedSections out;
  if (in.curves.empty()) return Result<ValidatedSections>::error("no cross sections: the set is empty");
  SectionSet s = in;

  // --- Planes: finite, non-zero normals, normalised, axis normals snapped to +e_k.
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    Plane& p = s.planes[i];
    if (!p.normal.allFinite() || !std::isfinite(p.offset))
      return Result<ValidatedSections>::error("plane " + std::to_string(i) + ": non-finite normal or offset");
    const double len = p.normal.norm();
    if (!(len > 1e-12)) return Result<ValidatedSections>::error("plane " + std::to_string(i) + ": zero normal");
    p.normal /= len;
    p.offset /= len;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(std::abs(p.normal[k]) - 1.0) < 1e-12) {
        const double sign = p.normal[k] > 0.0 ? 1.0 : -1.0;
        p.normal = Vec3::Unit(k);
        p.offset *= sign;
      }
    }
  }

  // --- Curves: plane index, point count, finite coordinates.
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    const CrossSection& c = s.curves[i];
    const std::string name = "curve " + std::to_string(i);
    if (c.plane < 0 || uz(c.plane) >= s.planes.size())
      return Result<ValidatedSections>::error(name + ": plane index " + std::to_string(c.plane) + " does not exist");
    if (c.points.size() < 3)
      return Result<ValidatedSections>::error(name + ": has " + std::to_string(c.points.size()) +
                                              " points; a closed curve needs at least 3");
    for (std::size_t j = 0; j < c.points.size(); ++j)
      if (!c.points[j].allFinite())
        return Result<ValidatedSections>::error(name + ": point " + std::to_string(j) + " is not a finite number");
  }
  const Box3 box = bounding_box(s.all_points());
  const double diag = std::max(box.diagonal(), 1e-300);
  out.diagonal = box.diagonal();

  // --- Coincident planes: merge (a plane given twice).
  std::vector<int> plane_map(s.planes.size());
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    plane_map[i] = static_cast<int>(i);
    for (std::size_t j = 0; j < i; ++j) {
      if (plane_map[j] != static_cast<int>(j)) continue;
      const Plane& a = s.planes[i];
      const Plane& b = s.planes[j];
      const double same = (a.normal - b.normal).norm(), opposite = (a.normal + b.normal).norm();
      const bool coincide = (same < 1e-9 && std::abs(a.offset - b.offset) < kOffPlaneWarn * diag) ||
                            (opposite < 1e-9 && std::abs(a.offset + b.offset) < kOffPlaneWarn * diag);
      if (coincide) {
        plane_map[i] = static_cast<int>(j);
        out.warnings.push_back("planes " + std::to_string(j) + " and " + std::to_string(i) +
                               " coincide; merged into plane " + std::to_string(j));
        break;
      }
    }
  }
  for (auto& c : s.curves) c.plane = plane_map[uz(c.plane)];

  // --- Projection onto planes, duplicate points, zero area.
  std::vector<std::vector<Vec2>> poly2(s.curves.size());
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    CrossSection& c = s.curves[i];
    const std::string name = "curve " + std::to_string(i);
    const Plane& pl = s.planes[uz(c.plane)];
    const PlaneFrame fr = plane_frame(pl);
    double worst = 0.0;
    for (auto& p : c.points) {
      const double off = std::abs(pl.signed_distance(p));
      worst = std::max(worst, off);
      // On an axis plane the projection is exact. On other planes a double point cannot lie
      // exactly on the plane anyway (the union snaps it exactly, zone_union.h); a point already
      // within rounding of it is kept bit for bit, so a crossing point shared by two curves
      // (curve sewing) stays shared.
      if (fr.axis >= 0 || off > 1e-14 * diag) p = fr.to_3d(fr.to_2d(pl.project(p)));
    }
    if (worst > kOffPlaneError * diag)
      return Result<ValidatedSections>::error(name + ": lies off its plane " + std::to_string(c.plane) + " by " +
                                              std::to_string(worst) + " (more than 1e-3 of the diagonal " +
                                              std::to_string(diag) + ")");
    if (worst > kOffPlaneWarn * diag)
      out.warnings.push_back(name + ": projected onto its plane (moved up to " + std::to_string(worst) + ")");
    for (std::size_t j = 0; j < c.points.size(); ++j) {
      const std::size_t k = (j + 1) % c.points.size();
      if ((c.points[j] - c.points[k]).norm() <= kDuplicatePoint * diag)
        return Result<ValidatedSections>::error(name + ": points " + std::to_string(j) + " and " + std::to_string(k) +
                                                " coincide at " + fmt(c.points[j]));
    }
    for (const auto& p : c.points) poly2[i].push_back(fr.to_2d(p));
    // Zero area: all points on one line (a bow tie has zero signed area but is reported as
    // crossing itself below).
    const auto& q = poly2[i];
    std::size_t far = 0;
    for (std::size_t j = 1; j < q.size(); ++j)
      if ((q[j] - q[0]).squaredNorm() > (q[far] - q[0]).squaredNorm()) far = j;
    const Vec2 dir = (q[far] - q[0]).normalized();
    double spread = 0.0;
    for (const auto& x : q) spread = std::max(spread, std::abs(dir.x() * (x - q[0]).y() - dir.y() * (x - q[0]).x()));
    if (!(spread > kDuplicatePoint * diag))
      return Result<ValidatedSections>::error(name + ": encloses zero area");
  }

  // --- Self-crossing (any two non-adjacent edges meeting, or adjacent edges overlapping).
  auto edge = [&](std::size_t ci, std::size_t j) {
    const auto& p = poly2[ci];
    const Vec2& a = p[j];
    const Vec2& b = p[(j + 1) % p.size()];
    return S2(P2(a.x(), a.y()), P2(b.x(), b.y()));
  };
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    const auto& p = poly2[i];
    const std::size_t n = p.size();
    std::vector<Box2> boxes(n);
    for (std::size_t j = 0; j < n; ++j) boxes[j] = seg_box(p[j], p[(j + 1) % n]);
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        if (!boxes[j].overlaps(boxes[k])) continue;
        const S2 a = edge(i, j), b = edge(i, k);
        const bool adjacent = (k == j + 1) || (j == 0 && k == n - 1);
        bool bad = false;
        if (adjacent) {
          // Adjacent edges share one vertex; they are bad only if they overlap (fold back).
          const auto& shared = (k == j + 1) ? a.target() : a.source();
          const auto& other_a = (k == j + 1) ? a.source() : a.target();
          const auto& other_b = (k == j + 1) ? b.target() : b.source();
          bad = CGAL::collinear(other_a, shared, other_b) && !CGAL::collinear_are_strictly_ordered_along_line(other_a, shared, other_b);
        } else {
          bad = CGAL::do_intersect(a, b);
        }
        if (bad)
          return Result<ValidatedSections>::error("curve " + std::to_string(i) + " crosses itself near " +
                                                  fmt(s.curves[i].points[j]) + " (edges " + std::to_string(j) +
                                                  " and " + std::to_string(k) + ")");
      }
    }
  }

  // --- Curves on one plane must not cross or touch (rule 3).
  std::vector<Box2> curve_box(s.curves.size());
  for (std::size_t i = 0; i < s.curves.size(); ++i)
    for (const auto& q : poly2[i]) curve_box[i].add(q);
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    for (std::size_t j = i + 1; j < s.curves.size(); ++j) {
      if (s.curves[i].plane != s.curves[j].plane || !curve_box[i].overlaps(curve_box[j])) continue;
      const auto& pi = poly2[i];
      const auto& pj = poly2[j];
      for (std::size_t a = 0; a < pi.size(); ++a) {
        const Box2 ba = seg_box(pi[a], pi[(a + 1) % pi.size()]);
        if (!ba.overlaps(curve_box[j])) continue;
        for (std::size_t b = 0; b < pj.size(); ++b) {
          if (!ba.overlaps(seg_box(pj[b], pj[(b + 1) % pj.size()]))) continue;
          if (CGAL::do_intersect(edge(i, a), edge(j, b)))
            return Result<ValidatedSections>::error("curves " + std::to_string(i) + " and " + std::to_string(j) +
                                                    " on plane " + std::to_string(s.curves[i].plane) +
                                                    " cross near " + fmt(s.curves[i].points[a]) + " (rule 3)");
        }
      }
    }
  }

  // === Nesting (rule 2)
  const std::size_t m = s.curves.size();
  out.depth.assign(m, 0);
  out.parent.assign(m, -1);
  std::vector<std::vector<int>> containers(m);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j)
      if (i != j && s.curves[i].plane == s.curves[j].plane && point_in_polygon_2d(poly2[i][0], poly2[j]))
        containers[i].push_back(static_cast<int>(j));
  for (std::size_t i = 0; i < m; ++i) out.depth[i] = static_cast<int>(containers[i].size());
  for (std::size_t i = 0; i < m; ++i)
    for (int j : containers[i])
      if (out.depth[uz(j)] == out.depth[i] - 1) out.parent[i] = j;
  for (std::size_t i = 0; i < m; ++i) {
    if (out.depth[i] % 2 != 0) continue;
    SectionRegion r;
    r.plane = s.curves[i].plane;
    r.outer = static_cast<int>(i);
    for (std::size_t j = 0; j < m; ++j)
      if (out.parent[j] == static_cast<int>(i)) r.holes.push_back(static_cast<int>(j));
    out.regions.push_back(std::move(r));
  }
  out.sections = std::move(s);
  return out;
}

// === Curve sewing (rule 4)
namespace {

struct Crossing {
  int curve;
  int segment;     // crossing on segment (segment, segment + 1)
  double t;        // parameter along the segment
  double free;     // coordinate along the line
  bool at_vertex = false;  // the crossing is (within the snap distance) an existing vertex
  bool used = false;
};

// Crossings of curve `ci` (on an axis plane) with the plane x_j = b.
void crossings_of(const SectionSet& s, int ci, int j, double b, int free_axis, double snap, std::vector<Crossing>& out) {
  const auto& pts = s.curves[uz(ci)].points;
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = pts[i];
    const Vec3& q = pts[(i + 1) % n];
    if ((p[j] < b) == (q[j] < b)) continue;
    const double t = (b - p[j]) / (q[j] - p[j]);
    const double len = (q - p).norm();
    Crossing c{ci, static_cast<int>(i), t, p[free_axis] + t * (q[free_axis] - p[free_axis])};
    if (t * len <= snap) {
      c.free = p[free_axis];
      c.at_vertex = true;
    } else if ((1.0 - t) * len <= snap) {
      c.free = q[free_axis];
      c.at_vertex = true;
    }
    out.push_back(c);
  }
}

struct Edit {
  int segment;
  double t;
  Vec3 point;
};

// The line where two non-parallel planes meet: origin (the point of the line nearest to the
// coordinate origin) and unit direction.
struct Line3 {
  Vec3 origin, dir;
  Vec3 at(double s) const { return origin + s * dir; }
};
Line3 plane_line(const Plane& a, const Plane& b) {
  const Vec3 d = a.normal.cross(b.normal);
  const double n2 = d.squaredNorm();
  const Vec3 o = (a.offset * b.normal.cross(d) + b.offset * d.cross(a.normal)) / n2;
  return Line3{o, d / std::sqrt(n2)};
}

// Crossings of curve `ci` with plane `other`, parametrised along `line` (any orientation).
void crossings_general(const SectionSet& s, int ci, const Plane& other, const Line3& line, double snap,
                       std::vector<Crossing>& out) {
  const auto& pts = s.curves[uz(ci)].points;
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = pts[i];
    const Vec3& q = pts[(i + 1) % n];
    const double dp = other.signed_distance(p), dq = other.signed_distance(q);
    if ((dp < 0) == (dq < 0)) continue;
    const double t = dp / (dp - dq);
    const double len = (q - p).norm();
    Crossing c{ci, static_cast<int>(i), t, (p + t * (q - p) - line.origin).dot(line.dir)};
    if (t * len <= snap) {
      c.free = (p - line.origin).dot(line.dir);
      c.at_vertex = true;
    } else if ((1.0 - t) * len <= snap) {
      c.free = (q - line.origin).dot(line.dir);
      c.at_vertex = true;
    }
    out.push_back(c);
  }
}

}  // namespace

int sew_crossings(SectionSet& s, double tolerance, std::vector<std::string>* warnings) {
  const Box3 box = bounding_box(s.all_points());
  const double snap = 1e-6 * box.diagonal();
  std::vector<std::vector<Edit>> edits(s.curves.size());
  int shared = 0;
  // Per pair of planes (one on axis k, one on axis j != k): all crossings of the first plane's
  // curves with the second plane, and vice versa, matched as mutual nearest along the line.
  for (std::size_t pa_i = 0; pa_i < s.planes.size(); ++pa_i) {
    for (std::size_t pb_i = pa_i + 1; pb_i < s.planes.size(); ++pb_i) {
      const Plane& pa = s.planes[pa_i];
      const Plane& pb = s.planes[pb_i];
      const int k = pa.axis(), j = pb.axis();
      if (k >= 0 && k == j) continue;
      // Axis pairs keep exact coordinates (the line is x_k = a, x_j = b); other pairs meet along
      // a general line (chapter 6), parallel pairs never.
      const bool axes = k >= 0 && j >= 0;
      if (!axes && pa.normal.cross(pb.normal).norm() < 1e-9) continue;
      const int f = axes ? 3 - k - j : -1;
      const Line3 line = axes ? Line3{} : plane_line(pa, pb);
      std::vector<Crossing> ca, cb;
      for (std::size_t c = 0; c < s.curves.size(); ++c) {
        if (axes) {
          if (uz(s.curves[c].plane) == pa_i) crossings_of(s, static_cast<int>(c), j, pb.offset, f, snap, ca);
          if (uz(s.curves[c].plane) == pb_i) crossings_of(s, static_cast<int>(c), k, pa.offset, f, snap, cb);
        } else {
          if (uz(s.curves[c].plane) == pa_i) crossings_general(s, static_cast<int>(c), pb, line, snap, ca);
          if (uz(s.curves[c].plane) == pb_i) crossings_general(s, static_cast<int>(c), pa, line, snap, cb);
        }
      }
      auto on_line = [&](double free) {
        if (!axes) return line.at(free);
        Vec3 p;
        p[k] = pa.offset;
        p[j] = pb.offset;
        p[f] = free;
        return p;
      };
      if (ca.empty() && cb.empty()) continue;
      auto nearest = [](const std::vector<Crossing>& list, double v) {
        int best = -1;
        for (std::size_t y = 0; y < list.size(); ++y)
          if (best < 0 || std::abs(list[y].free - v) < std::abs(list[uz(best)].free - v)) best = static_cast<int>(y);
        return best;
      };
      for (std::size_t xi = 0; xi < ca.size(); ++xi) {
        Crossing& x = ca[xi];
        const int yi = nearest(cb, x.free);
        if (yi < 0 || nearest(ca, cb[uz(yi)].free) != static_cast<int>(xi)) continue;
        Crossing& y = cb[uz(yi)];
        if (std::abs(y.free - x.free) > tolerance) continue;
        x.used = y.used = true;
        // An existing vertex on the line stays where it is (it is an input point the surface
        // must interpolate); otherwise the two crossings meet half way.
        const Vec3 p = on_line(x.at_vertex ? x.free : y.at_vertex ? y.free : 0.5 * (x.free + y.free));
        edits[uz(x.curve)].push_back(Edit{x.segment, x.t, p});
        edits[uz(y.curve)].push_back(Edit{y.segment, y.t, p});
        ++shared;
      }
      if (warnings) {
        for (const auto* list : {&ca, &cb})
          for (const auto& x : *list)
            if (!x.used) {
              const Vec3 at = on_line(x.free);
              warnings->push_back("a curve crosses the line at " + fmt(at) + " where planes (" +
                                  std::to_string(pa.normal.x()) + ", " + std::to_string(pa.normal.y()) + ", " +
                                  std::to_string(pa.normal.z()) + ") . p = " + std::to_string(pa.offset) + " and (" +
                                  std::to_string(pb.normal.x()) + ", " + std::to_string(pb.normal.y()) + ", " +
                                  std::to_string(pb.normal.z()) + ") . p = " + std::to_string(pb.offset) +
                                  " meet, and no curve of the other plane crosses it nearby (rule 4); not sewn");
            }
      }
    }
  }
  // Apply per curve from the last segment backwards so indices stay valid.
  for (std::size_t c = 0; c < s.curves.size(); ++c) {
    auto& e = edits[c];
    if (e.empty()) continue;
    std::sort(e.begin(), e.end(), [](const Edit& x, const Edit& y) {
      return std::tie(x.segment, x.t) > std::tie(y.segment, y.t);
    });
    auto& pts = s.curves[c].points;
    const std::size_t n = pts.size();
    for (const auto& ed : e) {
      const std::size_t i = uz(ed.segment);
      const std::size_t i1 = (i + 1) % n;
      if ((pts[i] - ed.point).norm() <= snap) {
        pts[i] = ed.point;
      } else if ((pts[i1] - ed.point).norm() <= snap) {
        pts[i1] = ed.point;
      } else {
        pts.insert(pts.begin() + static_cast<std::ptrdiff_t>(i + 1), ed.point);
      }
    }
  }
  return shared;
}

}  // namespace ps
