// Polyhedral zone partition (thesis 6.2). The clipping of section regions to convex zone faces
// uses CGAL's 2D Boolean set operations on an exact kernel (as zone_partition.cpp does for
// rectangles), so both zones sharing a face get the same piece, computed once.
#include "modeling/polyhedral_partition.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <tuple>

#include "modeling/exact_polygon_2.h"
#include "modeling/zone_arrangement.h"

namespace ps {
namespace {

using namespace exact2;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

using Key2 = std::pair<double, double>;

// Face key shared by the two zones: the plane and the sorted vertex coordinates (both zones'
// polygons are rounded from the same exact points).
using FaceKey = std::pair<int, std::vector<std::array<double, 3>>>;
FaceKey face_key(int plane, const std::vector<Vec3>& poly) {
  FaceKey k{plane, {}};
  for (const auto& p : poly) k.second.push_back({p.x(), p.y(), p.z()});
  std::sort(k.second.begin(), k.second.end());
  return k;
}

}  // namespace

bool PolyZone::contains(const Vec3& p, double margin) const {
  for (const auto& f : faces)
    if (!(f.normal.dot(p) - f.offset <= -margin)) return false;
  return true;
}

int PolyPartition::count(ZoneType t) const {
  return static_cast<int>(std::count_if(zones.begin(), zones.end(), [&](const PolyZone& z) { return z.type == t; }));
}

Result<PolyPartition> partition_polyhedral(const ValidatedSections& vs, const Box3& box) {
  const SectionSet& s = vs.sections;
  PolyPartition part;
  part.box = box;
  part.planes = s.planes;
  part.section_planes = static_cast<int>(s.planes.size());
  for (int k = 0; k < 3; ++k)
    for (double c : {box.min[k], box.max[k]}) part.planes.push_back(Plane{Vec3::Unit(k), c});
  const double diag = box.diagonal();
  const double tol = 1e-10 * diag;

  // === Zones: the arrangement of the planes that hold a curve.
  std::vector<char> used(s.planes.size(), 0);
  for (const auto& c : s.curves) used[uz(c.plane)] = 1;
  std::vector<Plane> cut;
  std::vector<int> cut_id;
  for (std::size_t i = 0; i < s.planes.size(); ++i)
    if (used[i]) {
      for (const auto& p : s.curves)
        if (uz(p.plane) == i)
          for (const auto& q : p.points)
            if (!((q.array() > box.min.array()).all() && (q.array() < box.max.array()).all()))
              return Result<PolyPartition>::error("plane " + std::to_string(i) +
                                                  " has points outside the reconstruction box");
      cut.push_back(s.planes[i]);
      cut_id.push_back(static_cast<int>(i));
    }
  const std::vector<ConvexZone> cz = partition_box_by_planes(box, cut);

  std::map<FaceKey, int> shared_of;
  part.zones.resize(cz.size());
  for (std::size_t zi = 0; zi < cz.size(); ++zi) {
    PolyZone& z = part.zones[zi];
    const ConvexZone& c = cz[zi];
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (std::size_t fi = 0; fi < c.faces.size(); ++fi) {
      PolyFace f;
      f.polygon = c.faces[fi];
      if (c.face_plane[fi] >= 0) {
        f.plane = cut_id[uz(c.face_plane[fi])];
      } else {
        // A box face: the axis whose coordinate all vertices share.
        for (int k = 0; k < 3 && f.plane < 0; ++k)
          for (int side = 0; side < 2; ++side) {
            const double v = side == 0 ? box.min[k] : box.max[k];
            if (std::all_of(f.polygon.begin(), f.polygon.end(), [&](const Vec3& p) { return p[k] == v; })) {
              f.plane = part.section_planes + 2 * k + side;
              break;
            }
          }
        if (f.plane < 0) return Result<PolyPartition>::error("internal: a box face of zone " + std::to_string(zi) + " is not axis-aligned");
      }
      const Plane& pl = part.planes[uz(f.plane)];
      // The side from the split that made the face (exact), not from the rounded polygon.
      const double sign = c.face_outward[fi].dot(pl.normal) >= 0 ? 1.0 : -1.0;
      f.normal = sign * pl.normal;
      f.offset = sign * pl.offset;
      // Planes of the edges (the zone's neighbouring faces).
      for (std::size_t i = 0; i < f.polygon.size(); ++i) {
        const Vec3& a = f.polygon[i];
        const Vec3& b = f.polygon[(i + 1) % f.polygon.size()];
        int best = -1;
        double best_d = 0;
        for (std::size_t pi = 0; pi < part.planes.size(); ++pi) {
          if (static_cast<int>(pi) == f.plane) continue;
          if (pi < s.planes.size() && !used[pi]) continue;
          const double d = std::max(std::abs(part.planes[pi].signed_distance(a)), std::abs(part.planes[pi].signed_distance(b)));
          if (d <= tol && (best < 0 || d < best_d)) {
            best = static_cast<int>(pi);
            best_d = d;
          }
        }
        f.edge_plane.push_back(best);
      }
      const FaceKey key = face_key(f.plane, f.polygon);
      auto [it, fresh] = shared_of.emplace(key, static_cast<int>(part.shared_faces.size()));
      if (fresh) {
        SharedFace sf;
        sf.plane = f.plane;
        part.shared_faces.push_back(sf);
      }
      f.shared = it->second;
      part.shared_faces[uz(f.shared)].zones[sign > 0 ? 0 : 1] = static_cast<int>(zi);
      for (const auto& p : f.polygon) {
        sum += p;
        ++count;
      }
      z.faces.push_back(std::move(f));
    }
    z.centroid = sum / std::max(1, count);
    for (const auto& f : z.faces)
      for (const auto& p : f.polygon)
        for (const auto& g : z.faces)
          for (const auto& q : g.polygon) z.diameter = std::max(z.diameter, (p - q).norm());
  }
  for (std::size_t zi = 0; zi < part.zones.size(); ++zi)
    for (auto& f : part.zones[zi].faces) {
      const auto& zs = part.shared_faces[uz(f.shared)].zones;
      f.neighbour = zs[0] == static_cast<int>(zi) ? zs[1] : zs[0];
      if (f.plane >= part.section_planes) f.neighbour = -1;
    }

  // === Pieces: each region clipped to every face of its plane it overlaps.
  for (const SectionRegion& r : vs.regions) {
    const Plane& pl = s.planes[uz(r.plane)];
    const PlaneFrame fr = plane_frame(pl);
    std::map<Key2, Vec3> input_point;  // 2D image -> the input point (kept bit for bit)
    auto loop2d = [&](int curve) {
      std::vector<Vec2> out;
      for (const auto& p : s.curves[uz(curve)].points) {
        const Vec2 q = fr.to_2d(p);
        input_point.emplace(Key2{q.x(), q.y()}, p);
        out.push_back(q);
      }
      return out;
    };
    const std::vector<Vec2> outer = loop2d(r.outer);
    EPwh region(to_exact(outer, true));
    for (int h : r.holes) region.add_hole(to_exact(loop2d(h), false));
    Vec2 lo = outer.front(), hi = outer.front();
    for (const auto& q : outer) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    for (std::size_t si = 0; si < part.shared_faces.size(); ++si) {
      SharedFace& sf = part.shared_faces[si];
      if (sf.plane != r.plane) continue;
      const int zi = sf.zones[0] >= 0 ? sf.zones[0] : sf.zones[1];
      const PolyFace* face = nullptr;
      for (const auto& f : part.zones[uz(zi)].faces)
        if (f.shared == static_cast<int>(si)) face = &f;
      std::vector<Vec2> poly;
      Vec2 flo(1e300, 1e300), fhi(-1e300, -1e300);
      for (const auto& p : face->polygon) {
        poly.push_back(fr.to_2d(p));
        flo = flo.cwiseMin(poly.back());
        fhi = fhi.cwiseMax(poly.back());
      }
      if ((fhi.array() < lo.array()).any() || (flo.array() > hi.array()).any()) continue;
      // The face is convex, but its vertices are rounded from exact values and projected into
      // the plane's frame, so nearly collinear ones can make a slightly reflex or
      // self-touching polygon, which CGAL's Boolean operations do not accept (it crashed on
      // a real data set). Its exact convex hull is a valid polygon of the same face.
      std::vector<EPoint> fpts, hull;
      for (const auto& q : poly) fpts.emplace_back(q.x(), q.y());
      CGAL::convex_hull_2(fpts.begin(), fpts.end(), std::back_inserter(hull));
      if (hull.size() < 3) continue;
      std::vector<EPwh> clipped;
      CGAL::intersection(region, EPolygon(hull.begin(), hull.end()), std::back_inserter(clipped));
      for (const auto& c : clipped) {
        PolyPiece piece;
        piece.plane = r.plane;
        piece.shared_face = static_cast<int>(si);
        auto add_loop = [&](const EPolygon& e) {
          std::vector<Vec3> pts;
          std::vector<char> is_input;
          for (auto it = e.vertices_begin(); it != e.vertices_end(); ++it) {
            const Key2 k{CGAL::to_double(it->x()), CGAL::to_double(it->y())};
            auto found = input_point.find(k);
            if (found == input_point.end()) {
              // A clip point next to an input point (a sewn crossing lying a rounding error
              // outside the face polygon in 2D) is that input point: both faces meeting at
              // the crossing must use the same point, or the union sees two points 1e-17 apart.
              const Vec2 q(k.first, k.second);
              for (auto it2 = input_point.begin(); it2 != input_point.end(); ++it2)
                if ((Vec2(it2->first.first, it2->first.second) - q).norm() <= 1e3 * tol) {
                  found = it2;
                  break;
                }
            }
            pts.push_back(found != input_point.end() ? found->second : fr.to_3d(Vec2(k.first, k.second)));
            is_input.push_back(found != input_point.end());
          }
          // Points closer than the tolerance (a sewn crossing next to the clip point of the
          // same curve) become one, the input point winning.
          std::vector<Vec3> kept;
          std::vector<char> kept_input;
          for (std::size_t i = 0; i < pts.size(); ++i) {
            if (!kept.empty() && (kept.back() - pts[i]).norm() <= 1e3 * tol) {
              if (is_input[i] && !kept_input.back()) {
                kept.back() = pts[i];
                kept_input.back() = 1;
              }
              continue;
            }
            kept.push_back(pts[i]);
            kept_input.push_back(is_input[i]);
          }
          while (kept.size() > 1 && (kept.back() - kept.front()).norm() <= 1e3 * tol) {
            if (kept_input.back() && !kept_input.front()) {
              kept.front() = kept.back();
              kept_input.front() = 1;
            }
            kept.pop_back();
            kept_input.pop_back();
          }
          if (kept.size() < 3) return false;
          // Tags: the face-edge planes a point lies on. Clip points lie on them by
          // construction (within rounding); an input point only when it is a crossing (sewn
          // to within rounding), not merely close: snapping a curve point that runs near an
          // edge onto it would make it exactly collinear with its neighbours there.
          std::vector<PlaneTags> all_tags;
          for (std::size_t j = 0; j < kept.size(); ++j) {
            const Vec3& p = kept[j];
            const double near = kept_input[j] ? 1e2 * tol : 1e3 * tol;
            PlaneTags t{r.plane, -1, -1};
            int n = 1;
            for (std::size_t i = 0; i < face->polygon.size() && n < 3; ++i) {
              const int ep = face->edge_plane[i];
              if (ep < 0 || std::find(t.begin(), t.end(), ep) != t.end()) continue;
              if (std::abs(part.planes[uz(ep)].signed_distance(p)) <= near) t[uz(n++)] = ep;
            }
            all_tags.push_back(t);
          }
          // Two neighbouring points tagged with the same three planes are one exact point (the
          // clip of a zone a few ulps wide rounds it to two doubles): keep one, or the snapped
          // loop has a zero-length edge (Horsers, zone 658: "no frustum fits").
          {
            auto same_point = [&](std::size_t a, std::size_t b) {
              if (all_tags[a][2] < 0 || all_tags[b][2] < 0) return false;
              PlaneTags x = all_tags[a], y = all_tags[b];
              std::sort(x.begin(), x.end());
              std::sort(y.begin(), y.end());
              return x == y;
            };
            std::vector<std::size_t> keep;
            for (std::size_t j = 0; j < kept.size(); ++j)
              if (keep.empty() || !same_point(keep.back(), j)) keep.push_back(j);
            while (keep.size() > 1 && same_point(keep.back(), keep.front())) keep.pop_back();
            if (keep.size() < kept.size()) {
              std::vector<Vec3> k3;
              std::vector<char> ki;
              std::vector<PlaneTags> kt;
              for (std::size_t j : keep) {
                k3.push_back(kept[j]);
                ki.push_back(kept_input[j]);
                kt.push_back(all_tags[j]);
              }
              kept = std::move(k3);
              kept_input = std::move(ki);
              all_tags = std::move(kt);
            }
            if (kept.size() < 3) return false;
          }
          // A clip point between two points on the same edge line adds nothing but a straight
          // angle (three exactly collinear points after snapping): dropped.
          std::vector<Vec3> pts3;
          std::vector<PlaneTags> tags;
          const std::size_t count = kept.size();
          auto shares_edge = [&](std::size_t a, std::size_t b, int plane) {
            (void)a;
            return std::find(all_tags[b].begin() + 1, all_tags[b].end(), plane) != all_tags[b].end();
          };
          for (std::size_t j = 0; j < count; ++j) {
            const std::size_t prev = (j + count - 1) % count, next = (j + 1) % count;
            bool straight = false;
            if (!kept_input[j])
              for (int s2 = 1; s2 < 3 && !straight; ++s2) {
                const int pl2 = all_tags[j][uz(s2)];
                straight = pl2 >= 0 && shares_edge(j, prev, pl2) && shares_edge(j, next, pl2) &&
                           all_tags[j][2] < 0;
              }
            if (straight) continue;
            pts3.push_back(kept[j]);
            tags.push_back(all_tags[j]);
          }
          if (pts3.size() < 3) return false;
          kept = std::move(pts3);
          std::vector<Vec2> q2;
          for (const auto& p : kept) q2.push_back(fr.to_2d(p));
          piece.loops.push_back(std::move(kept));
          piece.loops2d.push_back(std::move(q2));
          piece.tags.push_back(std::move(tags));
          return true;
        };
        if (!add_loop(c.outer_boundary())) continue;
        for (auto h = c.holes_begin(); h != c.holes_end(); ++h) add_loop(*h);
        sf.pieces.push_back(static_cast<int>(part.pieces.size()));
        part.pieces.push_back(std::move(piece));
      }
    }
  }

  // === Classification by the number of faces holding a piece.
  for (auto& z : part.zones) {
    int faces = 0;
    for (const auto& f : z.faces) faces += part.shared_faces[uz(f.shared)].pieces.empty() ? 0 : 1;
    z.type = faces == 0 ? ZoneType::kEmpty : faces == 1 ? ZoneType::kEnd : ZoneType::kBody;
  }
  return part;
}

}  // namespace ps
