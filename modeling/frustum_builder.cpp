// Frusta per convex zone, thesis 6.3.1 (Eq. 6.1) and 6.3.2. Caps are CGAL constrained Delaunay
// triangulations of the pieces (triangulate_piece, cylinder_builder.h); the frusta are checked
// with check_solid (mesh_boolean.h): closed, oriented, no self-intersection.
#include "modeling/frustum_builder.h"

#include <algorithm>
#include <cmath>

#include "modeling/cylinder_builder.h"
#include "modeling/mesh_boolean.h"
#include "modeling/mesh_topology.h"
#include "modeling/polygon_triangulate.h"

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

constexpr PlaneTags kNoTags{-1, -1, -1};

// A frustum bottom: a (real or virtual) section piece on face `face` of zone `zone`.
struct Base {
  int zone = -1, face = -1;
  PlaneFrame frame;                         // of the face's plane
  std::vector<Vec3> pts;                    // loops concatenated
  std::vector<Vec2> pts2d;                  // the same in `frame`
  std::vector<std::array<int, 2>> loops;    // [begin, end) per loop; outer ccw, holes cw in frame
  std::vector<PlaneTags> tags;
  std::vector<std::array<int, 3>> tris;     // cap, ccw in frame
  bool is_virtual = false;
};

// Area centroid; a result outside the loop's bounding box (a near-zero area, where the cross
// products cancel) falls back to the vertex mean, which lies in the loop's convex hull.
Vec2 polygon_centroid(const std::vector<Vec2>& p) {
  double a = 0;
  Vec2 c = Vec2::Zero(), lo = p.front(), hi = p.front(), mean = Vec2::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    const double w = u.x() * v.y() - v.x() * u.y();
    a += w;
    c += w * (u + v);
    lo = lo.cwiseMin(u);
    hi = hi.cwiseMax(u);
    mean += u;
  }
  mean /= static_cast<double>(p.size());
  if (std::abs(a) < 1e-300) return mean;
  c /= 3.0 * a;
  if (!((c.array() >= lo.array()).all() && (c.array() <= hi.array()).all())) return mean;
  return c;
}

Vec3 vertex_mean(const std::vector<Vec3>& poly) {
  Vec3 m = Vec3::Zero();
  for (const auto& p : poly) m += p;
  return m / static_cast<double>(poly.size());
}

double polygon_diameter(const std::vector<Vec3>& poly) {
  double d = 0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    for (std::size_t j = i + 1; j < poly.size(); ++j) d = std::max(d, (poly[i] - poly[j]).norm());
  return d;
}

void finish_base(Base& b) {
  SectionPiece sp;
  for (const auto& r : b.loops)
    sp.loops.emplace_back(b.pts2d.begin() + r[0], b.pts2d.begin() + r[1]);
  b.tris = triangulate_piece(sp);
}

// Outer loop counter-clockwise, holes clockwise in the frame (the wall rule needs it).
void orient_loops(Base& b) {
  for (std::size_t li = 0; li < b.loops.size(); ++li) {
    const auto r = b.loops[li];
    std::vector<Vec2> q(b.pts2d.begin() + r[0], b.pts2d.begin() + r[1]);
    const bool ccw = signed_area_2d(q) > 0;
    if (ccw != (li == 0)) {
      std::reverse(b.pts.begin() + r[0], b.pts.begin() + r[1]);
      std::reverse(b.pts2d.begin() + r[0], b.pts2d.begin() + r[1]);
      std::reverse(b.tags.begin() + r[0], b.tags.begin() + r[1]);
    }
  }
}

// Bottom cap, walls and top cap. Bottom cap faces are ccw in the frame; walls run along each
// loop so the cap's boundary half-edge i -> i+1 meets the wall's i+1 -> i. Flipped at the end
// when the frustum lies on the frame normal's side.
SnappedSolid assemble(const Base& b, const std::vector<Vec3>& top, const std::vector<PlaneTags>& top_tags) {
  SnappedSolid s;
  const int n = static_cast<int>(b.pts.size());
  s.mesh.vertices = b.pts;
  s.mesh.vertices.insert(s.mesh.vertices.end(), top.begin(), top.end());
  s.tags = b.tags;
  s.tags.insert(s.tags.end(), top_tags.begin(), top_tags.end());
  for (const auto& t : b.tris) {
    s.mesh.faces.push_back({t[0], t[1], t[2]});
    s.mesh.faces.push_back({n + t[0], n + t[2], n + t[1]});
  }
  for (const auto& r : b.loops)
    for (int i = r[0]; i < r[1]; ++i) {
      const int j = i + 1 < r[1] ? i + 1 : r[0];
      s.mesh.faces.push_back({j, i, n + i});
      s.mesh.faces.push_back({j, n + i, n + j});
    }
  if (signed_volume(s.mesh, s.mesh.vertices.front()) < 0)  // near the mesh: no cancellation far from the origin
    for (auto& f : s.mesh.faces) std::swap(f[1], f[2]);
  return s;
}

bool caps_keep_orientation(const Base& b, const std::vector<Vec3>& top) {
  for (const auto& t : b.tris) {
    const Vec2 a = b.frame.to_2d(top[uz(t[0])]), c = b.frame.to_2d(top[uz(t[1])]), d = b.frame.to_2d(top[uz(t[2])]);
    const Vec2 a0 = b.pts2d[uz(t[0])], c0 = b.pts2d[uz(t[1])], d0 = b.pts2d[uz(t[2])];
    const double s = (c.x() - a.x()) * (d.y() - a.y()) - (c.y() - a.y()) * (d.x() - a.x());
    const double s0 = (c0.x() - a0.x()) * (d0.y() - a0.y()) - (c0.y() - a0.y()) * (d0.x() - a0.x());
    if (!(s * s0 > 0) || std::abs(s) < 1e-6 * std::abs(s0)) return false;
  }
  return true;
}

// Nearest point to p on the given planes (1 or 2), in doubles (the exact value is made by the
// union from the tags).
Vec3 project_on(const Vec3& p, const std::vector<const Plane*>& on) {
  if (on.size() == 1) return on[0]->project(p);
  const Vec3 &n1 = on[0]->normal, &n2 = on[1]->normal;
  const double a = n1.dot(n1), b = n1.dot(n2), c = n2.dot(n2);
  const double r1 = on[0]->offset - n1.dot(p), r2 = on[1]->offset - n2.dot(p);
  const double det = a * c - b * b;
  if (std::abs(det) < 1e-12) return on[0]->project(p);
  return p + ((r1 * c - b * r2) / det) * n1 + ((a * r2 - b * r1) / det) * n2;
}

class Builder {
 public:
  Builder(const PolyPartition& part, const FrustumOptions& opt) : part_(part), opt_(opt) {
    tol_ = 1e-7 * part.box.diagonal();
  }

  Result<std::vector<ZoneFrusta>> run(FrustumReport* report) {
    out_.assign(part_.zones.size(), ZoneFrusta{});
    for (std::size_t zi = 0; zi < part_.zones.size(); ++zi) {
      const PolyZone& z = part_.zones[zi];
      if (z.type == ZoneType::kEmpty) continue;
      for (std::size_t fi = 0; fi < z.faces.size(); ++fi) {
        const SharedFace& sf = part_.shared_faces[uz(z.faces[fi].shared)];
        for (int pid : sf.pieces) {
          Base b = real_base(static_cast<int>(zi), static_cast<int>(fi), part_.pieces[uz(pid)]);
          const bool clipped = std::any_of(b.tags.begin(), b.tags.end(), [](const PlaneTags& t) { return t[1] >= 0; });
          Status st = z.type == ZoneType::kEnd && opt_.extend_end_zones && !clipped ? extend(std::move(b))
                                                                                    : body_frustum(b);
          if (!st) return st;
        }
      }
    }
    if (report) *report = rep_;
    return out_;
  }

 private:
  const PolyZone& zone(int z) const { return part_.zones[uz(z)]; }
  const PolyFace& face(const Base& b) const { return zone(b.zone).faces[uz(b.face)]; }

  Base real_base(int zi, int fi, const PolyPiece& piece) const {
    Base b;
    b.zone = zi;
    b.face = fi;
    b.frame = plane_frame(part_.planes[uz(piece.plane)]);
    for (std::size_t li = 0; li < piece.loops.size(); ++li) {
      const int begin = static_cast<int>(b.pts.size());
      b.pts.insert(b.pts.end(), piece.loops[li].begin(), piece.loops[li].end());
      b.pts2d.insert(b.pts2d.end(), piece.loops2d[li].begin(), piece.loops2d[li].end());
      b.tags.insert(b.tags.end(), piece.tags[li].begin(), piece.tags[li].end());
      b.loops.push_back({begin, static_cast<int>(b.pts.size())});
    }
    finish_base(b);
    return b;
  }

  Vec3 centre(const Base& b) const {
    const std::vector<Vec2> outer(b.pts2d.begin() + b.loops[0][0], b.pts2d.begin() + b.loops[0][1]);
    return b.frame.to_3d(polygon_centroid(outer));
  }

  // Depth of the zone from c along d (the nearest other face hit by the ray).
  double depth(const PolyZone& z, int skip, const Vec3& c, const Vec3& d) const {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < z.faces.size(); ++k) {
      if (static_cast<int>(k) == skip) continue;
      const PolyFace& f = z.faces[k];
      const double nd = f.normal.dot(d);
      if (nd <= 1e-12) continue;
      best = std::min(best, (f.offset - f.normal.dot(c)) / nd);
    }
    return best;
  }

  // Does a real piece on face `k` of zone z cover point p (inside or on its boundary)?
  bool material_at(const PolyZone& z, int k, const Vec3& p) const {
    const PolyFace& f = z.faces[uz(k)];
    const SharedFace& sf = part_.shared_faces[uz(f.shared)];
    if (sf.pieces.empty()) return false;
    const PlaneFrame fr = plane_frame(part_.planes[uz(f.plane)]);
    const Vec2 q = fr.to_2d(p);
    for (int pid : sf.pieces) {
      const PolyPiece& piece = part_.pieces[uz(pid)];
      int inside = 0;
      for (const auto& loop : piece.loops2d) {
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const Vec2& a = loop[i];
          const Vec2& b = loop[(i + 1) % loop.size()];
          const Vec2 e = b - a;
          const double t = std::clamp((q - a).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
          if ((a + t * e - q).norm() <= tol_) return true;
        }
        if (point_in_polygon_2d(q, loop)) ++inside;
      }
      if (inside % 2 == 1) return true;
    }
    return false;
  }

  // === Body zone (6.3.1): translate by h (Eq. 6.1), shrink uniformly by s, clamp the points
  // still outside towards the top's centre; keep unsupported edge points on their faces.
  Status body_frustum(const Base& b) {
    const PolyZone& z = zone(b.zone);
    const PolyFace& f = face(b);
    const Vec3 d = -f.normal;
    const Vec3 c = centre(b);
    const double dp = depth(z, b.face, c, d);
    if (!std::isfinite(dp) || !(dp > 0))
      return Status::error("reconstruction failed: zone " + std::to_string(b.zone) + " has no depth behind face " +
                           std::to_string(b.face));
    // The margin differs per face of the zone: frusta of two faces clamped against a third face
    // by the same margin would meet there in coincident edges, which the union refuses as a
    // non-manifold contact (the orthogonal perturbation had the same problem; 4.3).
    const double margin = opt_.face_margin * dp * (1.0 + 0.173 * b.face + 0.0291 * b.face * b.face);
    // Faces each bottom point must stay on (no section there), by plane.
    std::vector<std::vector<const Plane*>> stay(b.pts.size());
    std::vector<std::vector<int>> stay_face(b.pts.size());
    std::vector<char> pulled(b.pts.size(), 0);  // PT_f: on an edge whose other face has a section there
    for (std::size_t i = 0; i < b.pts.size(); ++i)
      for (int s = 1; s < 3; ++s) {
        const int q = b.tags[i][uz(s)];
        if (q < 0) continue;
        int k = -1;
        for (std::size_t j = 0; j < z.faces.size(); ++j)
          if (z.faces[j].plane == q && static_cast<int>(j) != b.face) k = static_cast<int>(j);
        if (k < 0) continue;
        if (material_at(z, k, b.pts[i])) {
          pulled[i] = 1;
          continue;
        }
        // A face a few ulps wide (four planes almost through one point) holds no wall: a top
        // kept on it could only sit at the zone vertex it rounds to, often on this piece's own
        // plane. The sub-ulp mismatch with the neighbour's wall is within the stitch's weld.
        if (polygon_diameter(z.faces[uz(k)].polygon) <= 1e-2 * tol_) continue;
        stay[i].push_back(&part_.planes[uz(q)]);
        stay_face[i].push_back(k);
      }
    std::vector<Vec3> top(b.pts.size());
    std::vector<PlaneTags> top_tags(b.pts.size(), kNoTags);
    for (std::size_t i = 0; i < b.pts.size(); ++i)
      for (std::size_t s = 0; s < stay_face[i].size(); ++s) top_tags[i][s] = z.faces[uz(stay_face[i][s])].plane;
    const int steps = std::max(1, opt_.height_steps);
    for (int hi = 0; hi < steps; ++hi) {
      const double h = (1.0 - opt_.height_margin) * dp * static_cast<double>(steps - hi) / steps;
      const Vec3 ct = c + h * d;
      if (!z.contains(ct, std::min(margin, 0.5 * h))) continue;
      const double m = std::min(margin, 0.5 * h);
      // Radial clamp: towards the top's centre until just inside (Case 2, "translate them
      // towards the center of fr_p^t until they just get inside").
      auto clamp_in = [&](const Vec3& p) {
        if (z.contains(p, m)) return p;
        double lambda = 1.0;
        const Vec3 e = p - ct;
        for (const auto& g : z.faces) {
          const double ne = g.normal.dot(e);
          if (ne <= 0) continue;
          lambda = std::min(lambda, (g.offset - m - g.normal.dot(ct)) / ne);
        }
        return Vec3(ct + std::max(lambda, 0.0) * e);
      };
      // PT_f points are translated, not shrunk, and pulled straight off the faces they would
      // cross by the margin, so they stay near the face whose section they meet and the two
      // frusta overlap beyond their common segment (no over-shrinkage, thesis Fig. 6.5c).
      std::vector<Vec3> fixed(b.pts.size());
      for (std::size_t i = 0; i < b.pts.size(); ++i) {
        if (!pulled[i] || !stay[i].empty()) continue;
        Vec3 t = b.pts[i] + h * d;
        for (int pass = 0; pass < 4; ++pass)
          for (const auto& g : z.faces) {
            const double over = g.normal.dot(t) - g.offset + m;
            if (over > 0) t -= over * g.normal;
          }
        fixed[i] = clamp_in(t);
      }
      for (double s = 1.0; s >= opt_.min_scale - 1e-9; s -= 0.1) {
        // Free points near PT_f points follow them (their displacement fades out linearly
        // over a quarter of the loop's length), standing in for the Laplacian top deformation
        // of Eq. 6.2 with PT_f fixed.
        std::vector<Vec3> shift(b.pts.size(), Vec3::Zero());
        for (const auto& r : b.loops) {
          const int n = r[1] - r[0];
          std::vector<double> arc(static_cast<std::size_t>(n) + 1, 0.0);
          for (int j = 0; j < n; ++j)
            arc[uz(j + 1)] = arc[uz(j)] + (b.pts[uz(r[0] + (j + 1) % n)] - b.pts[uz(r[0] + j)]).norm();
          const double len = arc[uz(n)], band = 0.25 * len;
          for (int j = 0; j < n; ++j) {
            const std::size_t i = uz(r[0] + j);
            if (pulled[i] && stay[i].empty()) continue;
            double best = band;
            Vec3 u = Vec3::Zero();
            for (int q = 0; q < n; ++q) {
              const std::size_t fi = uz(r[0] + q);
              if (!pulled[fi] || !stay[fi].empty()) continue;
              const double da = std::abs(arc[uz(j)] - arc[uz(q)]);
              const double dist = std::min(da, len - da);
              if (dist < best) {
                best = dist;
                u = fixed[fi] - (ct + s * (b.pts[fi] - c));
              }
            }
            if (band > 0) shift[i] = (1.0 - best / band) * u;
          }
        }
        bool ok = true;
        for (std::size_t i = 0; i < b.pts.size() && ok; ++i) {
          Vec3 t = ct + s * (b.pts[i] - c);
          if (pulled[i] && stay[i].empty()) {
            t = fixed[i];
          } else if (!stay[i].empty()) {
            t = project_on(t, stay[i]);
            for (std::size_t k = 0; k < z.faces.size() && ok; ++k) {
              if (std::find(stay_face[i].begin(), stay_face[i].end(), static_cast<int>(k)) != stay_face[i].end()) continue;
              ok = z.faces[k].normal.dot(t) - z.faces[k].offset <= -m;
            }
          } else {
            t = clamp_in(t + shift[i]);
          }
          top[i] = t;
        }
        if (!ok) continue;
        if (!caps_keep_orientation(b, top)) continue;
        SnappedSolid solid = assemble(b, top, top_tags);
        if (!check_solid(solid.mesh, "frustum")) continue;
        out_[uz(b.zone)].solids.push_back(std::move(solid));
        ++rep_.frusta;
        return Status::ok();
      }
    }
    // A fallback top is taken when its caps keep their orientation and the frustum is a valid
    // solid.
    auto accept_fallback = [&]() {
      if (!caps_keep_orientation(b, top)) return false;
      SnappedSolid solid = assemble(b, top, top_tags);
      if (!check_solid(solid.mesh, "frustum")) return false;
      out_[uz(b.zone)].solids.push_back(std::move(solid));
      ++rep_.frusta;
      ++rep_.fallback_frusta;
      return true;
    };
    // === Fallback 1: one homothety of the bottom about a centre c* (ratio s < 1). Every slice
    // of such a frustum is a scaled copy of the bottom in a parallel plane, so the frustum never
    // intersects itself and its top cap keeps the bottom's orientation; it lies in the cone from
    // c* over the bottom, hence in the (convex) zone when c* does. c* is the zone's centroid
    // when no point must stay on a face, the centroid of that face when all such points stay on
    // one face, and the midpoint of the zone edge two such faces share: a homothety about a
    // point of a plane maps the plane to itself, so the walls kept on those faces stay there,
    // and c* lies strictly inside every other face, so the top leaves them by (1 - s) times
    // c*'s distance.
    {
      std::vector<int> kept;
      for (const auto& sf : stay_face)
        for (int k : sf)
          if (std::find(kept.begin(), kept.end(), k) == kept.end()) kept.push_back(k);
      std::sort(kept.begin(), kept.end());
      // Candidates, first valid one wins; the last is the mean of the zone's vertices on every
      // kept plane (three kept faces meeting at a zone vertex, two sharing only a vertex).
      std::vector<Vec3> candidates;
      if (kept.empty()) candidates.push_back(z.centroid);
      if (kept.size() == 1) candidates.push_back(vertex_mean(z.faces[uz(kept[0])].polygon));
      if (kept.size() == 2) {
        const PolyFace& g = z.faces[uz(kept[0])];
        const int other = z.faces[uz(kept[1])].plane;
        for (std::size_t e = 0; e < g.polygon.size() && e < g.edge_plane.size(); ++e)
          if (g.edge_plane[e] == other) candidates.push_back(0.5 * (g.polygon[e] + g.polygon[(e + 1) % g.polygon.size()]));
      }
      if (!kept.empty()) {
        Vec3 m = Vec3::Zero();
        int count = 0;
        for (const auto& g : z.faces)
          for (const auto& p : g.polygon) {
            bool on_all = true;
            for (int k : kept) on_all = on_all && std::abs(z.faces[uz(k)].normal.dot(p) - z.faces[uz(k)].offset) <= 1e-3 * tol_;
            if (on_all) {
              m += p;
              ++count;
            }
          }
        if (count > 0) candidates.push_back(m / count);
      }
      // c* must lie strictly inside every face it is not meant to be on (a degenerate kept
      // face rounds to a zone vertex, which can be on this piece's own plane).
      bool have_centre = false;
      Vec3 cs = z.centroid;
      for (const Vec3& cand : candidates) {
        bool inside = true;
        for (std::size_t k = 0; k < z.faces.size() && inside; ++k)
          if (!std::binary_search(kept.begin(), kept.end(), static_cast<int>(k)))
            inside = z.faces[k].normal.dot(cand) - z.faces[k].offset < -1e-3 * tol_;
        if (inside) {
          cs = cand;
          have_centre = true;
          break;
        }
      }
      if (have_centre)
        for (const double s : {0.9, 0.75, 0.6, 0.45, 0.3, 0.2, 0.1, 0.05}) {
          for (std::size_t i = 0; i < b.pts.size(); ++i) top[i] = cs + s * (b.pts[i] - cs);
          if (accept_fallback()) return Status::ok();
        }
    }
    // === Fallback 2 (points kept on more than two faces, or on two that share no edge): free
    // points move towards the zone's centroid, points kept on a face towards that face's
    // centroid (or the midpoint of the zone edge shared by the two faces they are kept on).
    {
      std::vector<Vec3> target(b.pts.size(), z.centroid);
      for (std::size_t i = 0; i < b.pts.size(); ++i) {
        if (stay_face[i].size() == 1) {
          target[i] = vertex_mean(z.faces[uz(stay_face[i][0])].polygon);
        } else if (stay_face[i].size() == 2) {
          const auto& poly = z.faces[uz(stay_face[i][0])].polygon;
          const Plane& other = part_.planes[uz(z.faces[uz(stay_face[i][1])].plane)];
          Vec3 m = Vec3::Zero();
          int n = 0;
          for (const auto& p : poly)
            if (std::abs(other.signed_distance(p)) <= 1e3 * tol_) {
              m += p;
              ++n;
            }
          if (n > 0) target[i] = m / n;
        }
      }
      for (double s = 0.9; s > 0.25; s -= 0.1) {
        for (std::size_t i = 0; i < b.pts.size(); ++i) top[i] = target[i] + s * (b.pts[i] - target[i]);
        if (accept_fallback()) return Status::ok();
      }
    }
    return Status::error("reconstruction failed: no frustum fits the section piece on face " + std::to_string(b.face) +
                         " of zone " + std::to_string(b.zone));
  }

  // === End zone (6.3.2): extend by virtual sections while possible, else a body frustum.
  Status extend(Base b) {
    std::vector<int> visited;
    for (std::size_t step = 0; step <= part_.zones.size(); ++step) {
      visited.push_back(b.zone);
      const PolyZone& z = zone(b.zone);
      const PolyFace& f = face(b);
      const Vec3 d = -f.normal;
      const Vec3 c = centre(b);
      // Projected area of the outer loop along d on every face ahead, clipped to the face.
      int best = -1;
      double best_area = 0;
      const std::vector<Vec3> outer(b.pts.begin() + b.loops[0][0], b.pts.begin() + b.loops[0][1]);
      for (std::size_t k = 0; k < z.faces.size(); ++k) {
        if (static_cast<int>(k) == b.face) continue;
        const PolyFace& g = z.faces[k];
        const double nd = g.normal.dot(d);
        if (nd <= 1e-9) continue;
        std::vector<Vec3> poly;
        for (const auto& p : outer) poly.push_back(p + ((g.offset - g.normal.dot(p)) / nd) * d);
        // Sutherland-Hodgman against the zone's other half-spaces (the face is the plane's
        // part inside them).
        for (std::size_t j = 0; j < z.faces.size() && poly.size() >= 3; ++j) {
          if (j == k) continue;
          const PolyFace& h = z.faces[j];
          std::vector<Vec3> next;
          for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec3& p = poly[i];
            const Vec3& q = poly[(i + 1) % poly.size()];
            const double sp = h.normal.dot(p) - h.offset, sq = h.normal.dot(q) - h.offset;
            if (sp <= 0) next.push_back(p);
            if ((sp < 0) != (sq < 0) && sp != sq) next.push_back(p + (sp / (sp - sq)) * (q - p));
          }
          poly = std::move(next);
        }
        if (poly.size() < 3) continue;
        Vec3 nw = Vec3::Zero();
        for (std::size_t i = 0; i < poly.size(); ++i) nw += poly[i].cross(poly[(i + 1) % poly.size()]);
        const double area = 0.5 * nw.norm();
        if (area > best_area) {
          best_area = area;
          best = static_cast<int>(k);
        }
      }
      if (best < 0 || z.faces[uz(best)].on_box()) {
        if (best >= 0) ++rep_.extensions_to_box;
        return body_frustum(b);
      }
      const PolyFace& g = z.faces[uz(best)];
      const int next_zone = g.neighbour;
      if (next_zone < 0 || std::find(visited.begin(), visited.end(), next_zone) != visited.end()) return body_frustum(b);
      // Virtual section: the projection along d, shrunk towards its centre into the face.
      const double nd = g.normal.dot(d);
      const Vec3 cv = c + ((g.offset - g.normal.dot(c)) / nd) * d;
      const double margin = opt_.face_margin * std::max((cv - c).norm(), tol_);
      auto inside_face = [&](const Vec3& p) {
        for (std::size_t j = 0; j < z.faces.size(); ++j)
          if (static_cast<int>(j) != best && z.faces[j].normal.dot(p) - z.faces[j].offset > -margin) return false;
        return true;
      };
      std::vector<Vec3> proj;
      for (const auto& p : b.pts) proj.push_back(p + ((g.offset - g.normal.dot(p)) / nd) * d);
      std::vector<Vec3> top;
      bool placed = false;
      if (inside_face(cv)) {
        for (double s = 1.0; s > 0.05 && !placed; s -= 0.1) {
          top.clear();
          placed = true;
          for (const auto& p : proj) {
            top.push_back(cv + s * (p - cv));
            if (!inside_face(top.back())) {
              placed = false;
              break;
            }
          }
        }
      }
      if (!placed) return body_frustum(b);
      const std::vector<PlaneTags> top_tags(top.size(), PlaneTags{g.plane, -1, -1});
      if (!caps_keep_orientation(b, top)) return body_frustum(b);
      SnappedSolid solid = assemble(b, top, top_tags);
      if (!check_solid(solid.mesh, "frustum")) return body_frustum(b);
      out_[uz(b.zone)].solids.push_back(std::move(solid));
      ++rep_.frusta;
      ++rep_.virtual_sections;
      // The virtual section is the next zone's bottom.
      Base nb;
      nb.zone = next_zone;
      for (std::size_t j = 0; j < zone(next_zone).faces.size(); ++j)
        if (zone(next_zone).faces[j].shared == g.shared) nb.face = static_cast<int>(j);
      if (nb.face < 0) return Status::error("reconstruction failed: zones " + std::to_string(b.zone) + " and " +
                                            std::to_string(next_zone) + " do not share a face");
      nb.frame = plane_frame(part_.planes[uz(g.plane)]);
      nb.pts = top;
      for (const auto& p : top) nb.pts2d.push_back(nb.frame.to_2d(p));
      nb.loops = b.loops;
      nb.tags = top_tags;
      nb.is_virtual = true;
      orient_loops(nb);
      finish_base(nb);
      if (zone(next_zone).type != ZoneType::kEmpty) return body_frustum(nb);
      b = std::move(nb);
    }
    return body_frustum(b);
  }

  const PolyPartition& part_;
  FrustumOptions opt_;
  double tol_ = 0;
  std::vector<ZoneFrusta> out_;
  FrustumReport rep_;
};

}  // namespace

Result<std::vector<ZoneFrusta>> build_frusta(const PolyPartition& partition, const FrustumOptions& options,
                                             FrustumReport* report) {
  return Builder(partition, options).run(report);
}

}  // namespace ps
