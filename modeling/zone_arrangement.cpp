// Convex zones from an arrangement of planes (thesis 6.2), with exact predicates and exact
// intersection points (CGAL Epeck). Each split is a convex-polygon clip per face (hand-written:
// convex polygons against one plane need no general Boolean machinery) plus the cap polygon.
#include "modeling/zone_arrangement.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace ps {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using EPoint = EK::Point_3;
using EPlane = EK::Plane_3;

struct EZone {
  std::vector<EPlane> half_spaces;  // the zone is on the negative side (or on) of each
  std::vector<std::vector<EPoint>> faces;
  std::vector<int> face_plane;
  std::vector<Vec3> face_outward;
};

Vec3 to_vec(const EPoint& p) { return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())); }

EZone box_zone(const Box3& b) {
  EZone z;
  const EPoint c[8] = {{b.min.x(), b.min.y(), b.min.z()}, {b.max.x(), b.min.y(), b.min.z()},
                       {b.max.x(), b.max.y(), b.min.z()}, {b.min.x(), b.max.y(), b.min.z()},
                       {b.min.x(), b.min.y(), b.max.z()}, {b.max.x(), b.min.y(), b.max.z()},
                       {b.max.x(), b.max.y(), b.max.z()}, {b.min.x(), b.max.y(), b.max.z()}};
  // Counter-clockwise seen from outside.
  const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  const Vec3 out[6] = {-Vec3::UnitZ(), Vec3::UnitZ(), -Vec3::UnitY(), Vec3::UnitY(), -Vec3::UnitX(), Vec3::UnitX()};
  for (int k = 0; k < 6; ++k) {
    const auto& q = f[k];
    z.faces.push_back({c[q[0]], c[q[1]], c[q[2]], c[q[3]]});
    z.face_plane.push_back(-1);
    z.face_outward.push_back(out[k]);
  }
  z.half_spaces = {EPlane(-1, 0, 0, b.min.x()), EPlane(1, 0, 0, -b.max.x()), EPlane(0, -1, 0, b.min.y()),
                   EPlane(0, 1, 0, -b.max.y()), EPlane(0, 0, -1, b.min.z()), EPlane(0, 0, 1, -b.max.z())};
  return z;
}

// Orders the cap points (all on `plane`, the vertices of a convex polygon) counter-clockwise
// seen from the side `normal` points to.
std::vector<EPoint> order_cap(std::vector<EPoint> pts, const Vec3& normal) {
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return {};
  Vec3 c = Vec3::Zero();
  for (const auto& p : pts) c += to_vec(p);
  c /= static_cast<double>(pts.size());
  const Vec3 helper = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = normal.cross(helper).normalized();
  const Vec3 v = normal.cross(u);
  std::vector<std::pair<double, std::size_t>> key;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3 d = to_vec(pts[i]) - c;
    key.emplace_back(std::atan2(d.dot(v), d.dot(u)), i);
  }
  std::sort(key.begin(), key.end());
  std::vector<EPoint> out;
  for (const auto& k : key) out.push_back(pts[k.second]);
  return out;
}

// Splits z by the plane; returns false when the plane does not cut it (z untouched).
bool split(const EZone& z, const EPlane& plane, int plane_id, const Vec3& normal, EZone& neg, EZone& pos) {
  bool has_neg = false, has_pos = false;
  for (const auto& f : z.faces)
    for (const auto& p : f) {
      const auto s = plane.oriented_side(p);
      has_neg = has_neg || s == CGAL::ON_NEGATIVE_SIDE;
      has_pos = has_pos || s == CGAL::ON_POSITIVE_SIDE;
    }
  if (!has_neg || !has_pos) return false;
  neg = EZone{};
  pos = EZone{};
  std::vector<EPoint> cap;
  for (std::size_t fi = 0; fi < z.faces.size(); ++fi) {
    const auto& f = z.faces[fi];
    std::vector<EPoint> fn, fp;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const EPoint& a = f[i];
      const EPoint& b = f[(i + 1) % f.size()];
      const auto sa = plane.oriented_side(a), sb = plane.oriented_side(b);
      if (sa != CGAL::ON_POSITIVE_SIDE) fn.push_back(a);
      if (sa != CGAL::ON_NEGATIVE_SIDE) fp.push_back(a);
      if (sa == CGAL::ON_ORIENTED_BOUNDARY) cap.push_back(a);
      if ((sa == CGAL::ON_NEGATIVE_SIDE && sb == CGAL::ON_POSITIVE_SIDE) ||
          (sa == CGAL::ON_POSITIVE_SIDE && sb == CGAL::ON_NEGATIVE_SIDE)) {
        const auto x = CGAL::intersection(plane, EK::Segment_3(a, b));
        const EPoint* q = x ? boost::get<EPoint>(&*x) : nullptr;
        if (q) {
          fn.push_back(*q);
          fp.push_back(*q);
          cap.push_back(*q);
        }
      }
    }
    if (fn.size() >= 3) {
      neg.faces.push_back(std::move(fn));
      neg.face_plane.push_back(z.face_plane[fi]);
      neg.face_outward.push_back(z.face_outward[fi]);
    }
    if (fp.size() >= 3) {
      pos.faces.push_back(std::move(fp));
      pos.face_plane.push_back(z.face_plane[fi]);
      pos.face_outward.push_back(z.face_outward[fi]);
    }
  }
  std::vector<EPoint> cap_neg = order_cap(cap, normal);
  if (cap_neg.size() < 3) return false;
  std::vector<EPoint> cap_pos(cap_neg.rbegin(), cap_neg.rend());
  neg.faces.push_back(std::move(cap_neg));
  neg.face_plane.push_back(plane_id);
  neg.face_outward.push_back(normal);
  pos.faces.push_back(std::move(cap_pos));
  pos.face_plane.push_back(plane_id);
  pos.face_outward.push_back(-normal);
  neg.half_spaces = z.half_spaces;
  neg.half_spaces.push_back(plane);
  pos.half_spaces = z.half_spaces;
  pos.half_spaces.push_back(plane.opposite());
  return true;
}

}  // namespace

std::vector<ConvexZone> partition_box_by_planes(const Box3& box, const std::vector<Plane>& planes) {
  std::vector<EZone> zones{box_zone(box)};
  for (std::size_t pi = 0; pi < planes.size(); ++pi) {
    const Plane& p = planes[pi];
    const EPlane plane(p.normal.x(), p.normal.y(), p.normal.z(), -p.offset);
    std::vector<EZone> next;
    next.reserve(zones.size() * 2);
    for (const auto& z : zones) {
      EZone neg, pos;
      if (split(z, plane, static_cast<int>(pi), p.normal, neg, pos)) {
        next.push_back(std::move(neg));
        next.push_back(std::move(pos));
      } else {
        next.push_back(z);
      }
    }
    zones = std::move(next);
  }
  std::vector<ConvexZone> out;
  out.reserve(zones.size());
  for (const auto& z : zones) {
    ConvexZone c;
    for (const auto& h : z.half_spaces) {
      const Vec3 n(CGAL::to_double(h.a()), CGAL::to_double(h.b()), CGAL::to_double(h.c()));
      c.half_spaces.push_back(HalfSpace{n, -CGAL::to_double(h.d())});
    }
    for (const auto& f : z.faces) {
      std::vector<Vec3> poly;
      for (const auto& p : f) poly.push_back(to_vec(p));
      c.faces.push_back(std::move(poly));
    }
    c.face_plane = z.face_plane;
    c.face_outward = z.face_outward;
    out.push_back(std::move(c));
  }
  return out;
}

double zone_volume(const ConvexZone& z) {
  double v = 0.0;
  for (const auto& f : z.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) v += f[0].dot(f[i].cross(f[i + 1]));
  return v / 6.0;
}

}  // namespace ps
