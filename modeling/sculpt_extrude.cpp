// Extrusion by strokes (see sculpt_extrude.h and docs/sculpting.md, "Extrusion").
#include "modeling/sculpt_extrude.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_set>

#include "modeling/deform_tool.h"
#include "modeling/halfedge_mesh.h"
#include "modeling/mesh_boolean.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_smooth.h"
#include "modeling/mesh_topology.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/polyline_crossing.h"
#include "modeling/stroke_preprocess.h"

namespace ps {
namespace {

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// Consecutive duplicates removed (and, for a closed polyline, a last point equal to the first).
template <class V>
std::vector<V> dedup(const std::vector<V>& in, bool closed) {
  std::vector<V> out;
  for (const V& p : in)
    if (out.empty() || (p - out.back()).norm() > 0) out.push_back(p);
  if (closed)
    while (out.size() > 1 && (out.back() - out.front()).norm() == 0) out.pop_back();
  return out;
}

// n points evenly spaced by arc length along a polyline (closed: the closing segment counts and
// the first point is not repeated; open: both ends included, n >= 2).
template <class V>
std::vector<V> resample(const std::vector<V>& poly, int n, bool closed) {
  const std::size_t m = poly.size();
  const std::size_t segs = closed ? m : m - 1;
  std::vector<double> cum(segs + 1, 0.0);
  for (std::size_t i = 0; i < segs; ++i) cum[i + 1] = cum[i] + (poly[(i + 1) % m] - poly[i]).norm();
  const double total = cum.back();
  std::vector<V> out;
  const int steps = closed ? n : n - 1;
  std::size_t seg = 0;
  for (int k = 0; k < n; ++k) {
    const double s = total * static_cast<double>(k) / static_cast<double>(steps);
    while (seg + 1 < segs && cum[seg + 1] < s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double t = len > 0 ? std::clamp((s - cum[seg]) / len, 0.0, 1.0) : 0.0;
    out.push_back(poly[seg] + t * (poly[(seg + 1) % m] - poly[seg]));
  }
  return out;
}

double distance_to_closed_polyline(const Vec3& p, const std::vector<Vec3>& poly) {
  double best = 1e300;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3 d = poly[(i + 1) % poly.size()] - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - p).norm());
  }
  return best;
}

Vec3 face_normal(const TriMesh& m, int f) {
  const Face& t = m.faces[static_cast<std::size_t>(f)];
  const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
  const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
  const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a).normalized();
}

struct VecHash {
  std::size_t operator()(const Vec3& v) const {
    std::size_t h = 1469598103934665603ull;
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits = 0;
      const double x = v[k] == 0.0 ? 0.0 : v[k];  // -0 and +0 hash alike
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ static_cast<std::size_t>(bits)) * 1099511628211ull;
    }
    return h;
  }
};

Result<ExtrudePlane> make_plane(const MeshRayCaster& caster, const TriMesh& model, const std::vector<Vec2>& stroke_in,
                                const Camera& cam, const ExtrudeOptions& o) {
  if (Status s = check_window_points(stroke_in, 3, "the base stroke"); !s) return s;
  if (o.section_points < 8) return Result<ExtrudePlane>::error("extrusion needs at least 8 section points");
  if (Status s = check_plane_rotation(o.spin, o.tilt); !s) return s;
  const std::vector<Vec2> stroke = dedup(stroke_in, /*closed=*/true);
  if (stroke.size() < 3) return Result<ExtrudePlane>::error("the base stroke has fewer than 3 distinct points");
  Vec2 lo = stroke[0], hi = stroke[0];
  for (const auto& p : stroke) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = (hi - lo).maxCoeff();
  const double gap = (stroke.back() - stroke.front()).norm();
  const double max_gap = std::max(12.0, 0.2 * size);
  if (gap > max_gap)
    return Result<ExtrudePlane>::error("the base stroke is not closed: its ends are " + fmt(gap) +
                                       " px apart (at most " + fmt(max_gap) + " px); draw a loop on the model");
  if (auto x = first_self_crossing(stroke))
    return Result<ExtrudePlane>::error("the base stroke crosses itself at " + format_window_point(*x));
  if (std::abs(signed_area_2d(stroke)) < 8.0)
    return Result<ExtrudePlane>::error("the base stroke encloses no area");

  // === Project the loop densely (every 2 px, the closing segment included); every ray must hit.
  std::vector<Vec3> loop;
  for (std::size_t i = 0; i < stroke.size(); ++i) {
    const Vec2 a = stroke[i], b = stroke[(i + 1) % stroke.size()];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 2.0)));
    for (int k = 0; k < n; ++k) {
      const Vec2 p = a + (b - a) * (static_cast<double>(k) / n);
      const auto h = caster.first_hit(cam.ray(p.x(), p.y()));
      if (!h)
        return Result<ExtrudePlane>::error("the base stroke misses the model at " + format_window_point(p) +
                                           "; draw the loop on the surface");
      if (loop.empty() || (h->point - loop.back()).norm() > 0) loop.push_back(h->point);
    }
  }
  loop = dedup(loop, true);
  if (loop.size() < 3) return Result<ExtrudePlane>::error("the base stroke projects to a single point");

  // === The region's mean normal: hit faces of rays on a grid inside the loop and on the loop.
  Vec3 sum = Vec3::Zero();
  const int grid = 16;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const Vec2 p = lo + Vec2((i + 0.5) / grid * (hi.x() - lo.x()), (j + 0.5) / grid * (hi.y() - lo.y()));
      if (!point_in_polygon_2d(p, stroke)) continue;
      if (const auto h = caster.first_hit(cam.ray(p.x(), p.y()))) sum += face_normal(model, h->face);
    }
  for (const Vec2& p : stroke)
    if (const auto h = caster.first_hit(cam.ray(p.x(), p.y()))) sum += face_normal(model, h->face);
  if (!(sum.norm() > 1e-9)) return Result<ExtrudePlane>::error("the region under the base stroke has no mean normal");

  ExtrudePlane out;
  out.base_curve = resample(loop, o.section_points, true);
  out.region_normal = sum.normalized();
  for (const auto& q : out.base_curve) out.centre += q;
  out.centre /= static_cast<double>(out.base_curve.size());
  // Diameter: from the projection of the stroke's first point to the curve point farthest from it.
  const Vec3 first = out.base_curve.front();
  Vec3 farthest = first;
  for (const auto& q : out.base_curve)
    if ((q - first).norm() > (farthest - first).norm()) farthest = q;
  const Vec3 n = out.region_normal;
  const Vec3 diameter = farthest - first;
  Vec3 across = diameter - diameter.dot(n) * n;
  if (!(across.norm() > 1e-12 * std::max(1.0, diameter.norm())))
    return Result<ExtrudePlane>::error("the base curve has no diameter across the region's normal");
  across.normalize();
  across = Eigen::AngleAxisd(o.spin, n) * across;
  out.across = across.normalized();
  out.normal_axis = (Eigen::AngleAxisd(o.tilt, out.across) * n).normalized();
  out.plane.normal = out.across.cross(out.normal_axis).normalized();
  out.plane.offset = out.plane.normal.dot(out.centre);
  return out;
}

// Vertices of the part between two rings, the apex fan and the bottom cap (see build_part).
void add_ring_faces(TriMesh& m, int ring_a, int ring_b, int n) {
  for (int i = 0; i < n; ++i) {
    const int i1 = (i + 1) % n;
    const int a = ring_a * n + i, b = ring_a * n + i1, c = ring_b * n + i1, d = ring_b * n + i;
    m.faces.push_back({a, b, c});
    m.faces.push_back({a, c, d});
  }
}

// Whether smoothing (which moved only the vertices with fixed[v] == 0 of a mesh free of
// self-intersections, connectivity unchanged) made it intersect itself. Exact, and local: every
// moved face lies in the box of the moved faces, so only the faces meeting that box can take
// part in a new intersection; they are tested as one soup (shared vertices keep shared indices,
// so neighbours are still recognised as adjacent).
bool smoothing_self_intersects(const TriMesh& m, const std::vector<std::uint8_t>& fixed) {
  Box3 moved;
  for (const auto& f : m.faces)
    if (!fixed[static_cast<std::size_t>(f[0])] || !fixed[static_cast<std::size_t>(f[1])] ||
        !fixed[static_cast<std::size_t>(f[2])])
      for (int k : f) moved.extend(m.vertices[static_cast<std::size_t>(k)]);
  if (moved.empty()) return false;
  TriMesh local;
  std::vector<int> index(m.vertices.size(), -1);
  for (const auto& f : m.faces) {
    Box3 b;
    for (int k : f) b.extend(m.vertices[static_cast<std::size_t>(k)]);
    if ((b.max.array() < moved.min.array()).any() || (b.min.array() > moved.max.array()).any()) continue;
    Face g{};
    for (int c = 0; c < 3; ++c) {
      int& id = index[static_cast<std::size_t>(f[static_cast<std::size_t>(c)])];
      if (id < 0) {
        id = static_cast<int>(local.vertices.size());
        local.vertices.push_back(m.vertices[static_cast<std::size_t>(f[static_cast<std::size_t>(c)])]);
      }
      g[static_cast<std::size_t>(c)] = id;
    }
    local.faces.push_back(g);
  }
  return does_self_intersect(local);
}

}  // namespace

Status check_plane_rotation(double spin, double tilt) {
  if (!std::isfinite(spin)) return Status::error("the reference plane's spin is not a finite angle");
  if (!(std::abs(tilt) < 0.5 * M_PI))
    return Status::error("the reference plane's tilt must lie strictly between -90 and 90 degrees (found " +
                         fmt(tilt * 180.0 / M_PI) + " degrees): the part must leave the surface");
  return Status::ok();
}

Result<ExtrudePlane> extrusion_reference_plane(const TriMesh& model, const std::vector<Vec2>& base_stroke_px,
                                               const Camera& camera, const ExtrudeOptions& options) {
  if (model.faces.empty()) return Result<ExtrudePlane>::error("the model is empty");
  const MeshRayCaster caster(model);
  return make_plane(caster, model, base_stroke_px, camera, options);
}

Result<TriMesh> extrude_by_strokes(const TriMesh& model, const std::vector<Vec2>& base_stroke_px,
                                   const std::vector<Vec2>& silhouette_px, const Camera& camera,
                                   const ExtrudeOptions& o, ExtrudeReport* report) {
  if (model.faces.empty()) return Result<TriMesh>::error("the model is empty");
  if (o.stations < 4) return Result<TriMesh>::error("extrusion needs at least 4 stations");
  if (Status s = check_window_points(silhouette_px, 3, "the silhouette stroke"); !s) return s;
  const MeshRayCaster caster(model);
  auto planed = make_plane(caster, model, base_stroke_px, camera, o);
  if (!planed) return planed.status();
  const ExtrudePlane& P = *planed;
  const Vec3 c = P.centre, U = P.across, N = P.normal_axis, W = P.plane.normal;

  // === Base section: the base curve flattened along N (coordinates x along U, y along W).
  const std::vector<Vec3>& base = P.base_curve;
  std::vector<Vec2> section;
  double hmin = 1e300, hmax = -1e300;
  for (const auto& q : base) {
    section.emplace_back((q - c).dot(U), (q - c).dot(W));
    hmin = std::min(hmin, (q - c).dot(N));
    hmax = std::max(hmax, (q - c).dot(N));
  }
  if (first_self_crossing(section))
    return Result<TriMesh>::error("the base curve folds over itself seen along the region's normal; draw a rounder loop");
  double xmin = 1e300, xmax = -1e300;
  for (const auto& s : section) {
    xmin = std::min(xmin, s.x());
    xmax = std::max(xmax, s.x());
  }
  const double wb = xmax - xmin, xc = 0.5 * (xmin + xmax);
  if (!(wb > 0)) return Result<TriMesh>::error("the base curve has no width in the reference plane");

  // === Silhouette on the plane, in plane coordinates (u along U, v along N).
  const Camera& scam = o.silhouette_camera ? *o.silhouette_camera : camera;
  std::vector<Vec2> sil;
  for (std::size_t i = 0; i < silhouette_px.size(); ++i) {
    const Ray ray = scam.ray(silhouette_px[i].x(), silhouette_px[i].y());
    if (std::abs(ray.direction.dot(P.plane.normal)) < std::sin(2.0 * M_PI / 180.0))
      return Result<TriMesh>::error("the reference plane is seen edge-on at silhouette point " + std::to_string(i) +
                                    "; turn the view to face the plane");
    const auto p = scam.lift(silhouette_px[i].x(), silhouette_px[i].y(), P.plane);
    if (!p)
      return Result<TriMesh>::error("silhouette point " + std::to_string(i) +
                                    " cannot be lifted onto the reference plane (seen edge-on or behind the eye); turn the view");
    sil.emplace_back((*p - c).dot(U), (*p - c).dot(N));
  }
  sil = dedup(sil, false);
  if (sil.size() < 3) return Result<TriMesh>::error("the silhouette stroke is degenerate (fewer than 3 distinct points)");
  const auto to3 = [&](const Vec2& s) { return Vec3(c + s.x() * U + s.y() * N); };
  const double end_tol = o.end_tolerance * wb;
  const double d_start = distance_to_closed_polyline(to3(sil.front()), base);
  const double d_end = distance_to_closed_polyline(to3(sil.back()), base);
  if (d_start > end_tol || d_end > end_tol)
    return Result<TriMesh>::error(std::string("the silhouette must ") + (d_start > end_tol ? "start" : "end") +
                                  " near the base curve (it is " + fmt(std::max(d_start, d_end)) + " away, at most " +
                                  fmt(end_tol) + "): draw it from one side of the loop to the other");
  if (std::abs(sil.back().x() - sil.front().x()) < 0.2 * wb)
    return Result<TriMesh>::error("the silhouette's ends are too close together across the base: draw it from one side of the loop to the other");
  if (first_self_crossing_open(sil))
    return Result<TriMesh>::error("the silhouette stroke crosses itself");
  // Tip: the point farthest from the midpoint of the ends.
  const Vec2 mid = 0.5 * (sil.front() + sil.back());
  std::size_t tip = 0;
  for (std::size_t i = 0; i < sil.size(); ++i)
    if ((sil[i] - mid).norm() > (sil[tip] - mid).norm()) tip = i;
  if (tip == 0 || tip + 1 == sil.size() || (sil[tip] - mid).norm() < 0.05 * wb)
    return Result<TriMesh>::error("the silhouette stroke is degenerate: it does not rise from the base");
  // Outward: extrusion. Inward: digging (thesis 3.2.2: "extrude or dig"), a tunnel when the dug
  // part comes out at the back. Along the surface: neither.
  const bool dig = sil[tip].y() - mid.y() < -0.05 * wb;
  if (!dig && !(sil[tip].y() - mid.y() > 0.05 * wb))
    return Result<TriMesh>::error("the silhouette runs along the surface: draw it outward (extrude) or inward (dig)");
  const double out_sign = dig ? -1.0 : 1.0;  // the part's direction along N

  // === Skeleton: both sides from the base to the tip, paired by normalised arc length.
  const int K = o.stations;
  std::vector<Vec2> side_a(sil.begin(), sil.begin() + static_cast<std::ptrdiff_t>(tip) + 1);
  std::vector<Vec2> side_b(sil.begin() + static_cast<std::ptrdiff_t>(tip), sil.end());
  std::reverse(side_b.begin(), side_b.end());
  if (side_a.front().x() > side_b.front().x()) std::swap(side_a, side_b);  // a: the -U side
  const std::vector<Vec2> L = resample(side_a, K + 1, false), R = resample(side_b, K + 1, false);

  // === The part: ring -1 (sunk into the model), rings 0..K-1 on the rungs, the tip as apex.
  const int n = static_cast<int>(section.size());
  TriMesh part;
  std::vector<Vec3> ring0;
  double w0 = 0;
  for (int k = 0; k < K; ++k) {
    const Vec3 l = to3(L[static_cast<std::size_t>(k)]), r = to3(R[static_cast<std::size_t>(k)]);
    const double wk = (r - l).norm();
    if (!(wk > 1e-3 * wb))
      return Result<TriMesh>::error("the silhouette pinches to zero width before its tip");
    const Vec3 a = (r - l) / wk, m = 0.5 * (l + r);
    const double s = wk / wb;
    std::vector<Vec3> ring;
    for (const auto& q : section) ring.push_back(m + s * (q.x() - xc) * a + s * q.y() * W);
    if (k == 0) {
      ring0 = ring;
      w0 = wk;
      // Sink (extrusion): below the lowest point of the base curve by a quarter of the base
      // width, into the model. Digging: as far above its highest point, out of the model, so
      // the difference opens the surface cleanly.
      const double depth = dig ? std::max(0.0, hmax - std::min(L[0].y(), R[0].y())) + 0.25 * wk
                               : std::max(0.0, std::max(L[0].y(), R[0].y()) - hmin) + 0.25 * wk;
      for (const auto& p : ring) part.vertices.push_back(p - out_sign * depth * N);
    }
    part.vertices.insert(part.vertices.end(), ring.begin(), ring.end());
  }
  const int apex = static_cast<int>(part.vertices.size());
  part.vertices.push_back(to3(sil[tip]));
  for (int k = 0; k < K; ++k) add_ring_faces(part, k, k + 1, n);
  for (int i = 0; i < n; ++i) part.faces.push_back({K * n + i, K * n + (i + 1) % n, apex});
  // Orientation: a wall triangle of ring 0 must face away from the ring's centre.
  Vec3 m0 = Vec3::Zero();
  for (const auto& p : ring0) m0 += p;
  m0 /= n;
  {
    const Face& f = part.faces[static_cast<std::size_t>(2 * n)];  // first wall face above ring 0
    const Vec3& a = part.vertices[static_cast<std::size_t>(f[0])];
    const Vec3 nf = (part.vertices[static_cast<std::size_t>(f[1])] - a).cross(part.vertices[static_cast<std::size_t>(f[2])] - a);
    if (nf.dot(a - m0) < 0)
      for (auto& t : part.faces) std::swap(t[1], t[2]);
  }
  // Cap on ring -1 (vertices 0..n-1), facing away from the tip: -N for an extrusion, +N when
  // digging. Its triangles turn like the section in (x, y); the ring's axes are (a, W) with
  // a = alpha U + beta N, alpha > 0 (the sides are sorted along U), and (a x W) . N = -alpha: a
  // counter-clockwise section faces -N.
  const bool ccw = signed_area_2d(section) > 0;
  for (const auto& t : triangulate_polygon_2d(section)) {
    Face f = t;
    if (ccw == dig) std::swap(f[1], f[2]);
    part.faces.push_back(f);
  }
  if (Status s = check_solid(part, "the extruded part"); !s) {
    const char* what = dig ? "dug part" : "extruded part";
    if (s.message().find("intersects itself") != std::string::npos)
      return Result<TriMesh>::error(std::string("the ") + what +
                                    " would intersect itself: the silhouette bends too sharply for the base");
    return Result<TriMesh>::error(std::string("cannot build the ") + what + ": " + s.message());
  }
  if (Status s = check_solid(model, "the model"); !s) return s;

  // === Exact union; nudge the part by a fixed tiny offset when rounding folds a sliver.
  Result<TriMesh> joined = Result<TriMesh>::error("");
  TriMesh used = part;
  int attempts = 0;
  for (int attempt = 0; attempt < 5; ++attempt) {
    ++attempts;
    used = part;
    const Vec3 shift = static_cast<double>(attempt) * 1e-4 * wb * Vec3(0.31, 0.17, 0.23);
    for (auto& p : used.vertices) p += shift;
    joined = mesh_boolean(model, used, dig ? BooleanOp::kDifference : BooleanOp::kUnion, /*checked_a=*/true);
    if (joined || joined.message().find("rounded result") == std::string::npos) break;
  }
  if (!joined) return Result<TriMesh>::error(std::string(dig ? "digging" : "extrusion") + " failed: " + joined.message());
  const MeshTopology before = mesh_topology(model), after = mesh_topology(*joined);
  if (dig) {
    // A pocket keeps the genus; a part that comes out at the back digs a tunnel (genus + 1).
    if (after.components != before.components)
      return Result<TriMesh>::error("digging would split the model (" + std::to_string(after.components) +
                                    " components instead of " + std::to_string(before.components) +
                                    "): the dug part cuts a piece off");
    if (after.genus != before.genus && after.genus != before.genus + 1)
      return Result<TriMesh>::error("digging would change the genus from " + std::to_string(before.genus) + " to " +
                                    std::to_string(after.genus) + " (a pocket keeps it, a tunnel adds one)");
    if (!(after.signed_volume < before.signed_volume))
      return Result<TriMesh>::error("the dug part does not meet the model");
  } else {
    if (after.components != before.components)
      return Result<TriMesh>::error("the new part does not join the model (" + std::to_string(after.components) +
                                    " components instead of " + std::to_string(before.components) + ")");
    if (after.genus != before.genus)
      return Result<TriMesh>::error("the new part would pass through the model (genus " +
                                    std::to_string(before.genus) + " -> " + std::to_string(after.genus) + ")");
  }

  // === Smooth the join: vertices near the intersection curve (new vertices of the union).
  std::unordered_set<Vec3, VecHash> inputs;
  for (const auto& p : model.vertices) inputs.insert(p);
  for (const auto& p : used.vertices) inputs.insert(p);
  const TriMesh& J = *joined;
  std::vector<Vec3> join;
  for (const auto& p : J.vertices)
    if (!inputs.count(p)) join.push_back(p);
  // The region within `radius` of the join, smoothed by `steps`, halved while the result
  // intersects itself; when even one step does at the full radius, once more at half the radius
  // (fewer faces move near a grazing join, e.g. where a bent tunnel comes out at the back: the
  // unit test's bent tunnel folds at the full radius and smooths at half of it).
  const double radius0 = o.smooth_radius > 0 ? o.smooth_radius : 0.25 * w0;
  const Box3 jbox = bounding_box(join);
  TriMesh result = J;
  int steps_done = 0, region = 0;
  auto built = o.smooth_steps > 0 && !join.empty() ? HalfedgeMesh::build(J)
                                                   : Result<HalfedgeMesh>::error("the join is not smoothed");
  for (const double radius : {radius0, 0.5 * radius0}) {
    if (o.smooth_steps <= 0 || join.empty() || !built) break;
    std::vector<std::uint8_t> fixed(J.vertices.size(), 1);
    region = 0;
    for (std::size_t v = 0; v < J.vertices.size(); ++v) {
      const Vec3& p = J.vertices[v];
      if ((p.array() < jbox.min.array() - radius).any() || (p.array() > jbox.max.array() + radius).any()) continue;
      for (const auto& q : join)
        if ((p - q).squaredNorm() <= radius * radius) {
          fixed[v] = 0;
          ++region;
          break;
        }
    }
    if (region == 0) break;
    SmoothOptions so;
    so.flow = NormalFlow::kMeanCurvature;
    so.normal_step = 0.5;
    so.tangential_step = 0.5;
    for (int steps = o.smooth_steps; steps >= 1 && steps_done == 0; steps /= 2) {
      HalfedgeMesh m = *built;
      Smoother smoother(m, fixed, so);
      for (int k = 0; k < steps; ++k) smoother.step(m);
      TriMesh out = m.to_trimesh();
      if (!smoothing_self_intersects(out, fixed)) {
        result = std::move(out);
        steps_done = steps;
      }
    }
    if (steps_done > 0) break;
  }
  // The smoothed result is free of self-intersections: the union J was (mesh_boolean checked
  // it), and the smoothing kept J's connectivity and moved only vertices whose faces were tested
  // against all others. Remembered, so the next operation does not check it again.
  if (steps_done > 0) remember_checked_solid(result);
  if (report) {
    report->plane = P;
    report->part = used;
    report->join_vertices = static_cast<int>(join.size());
    report->smoothed_vertices = steps_done > 0 ? region : 0;
    report->smooth_steps = steps_done;
    report->boolean_attempts = attempts;
    // About a point of the mesh, as mesh_topology sums `before`: about the origin a model far
    // from it loses the volume to rounding.
    report->added_volume =
        (result.vertices.empty() ? 0.0 : signed_volume(result, result.vertices.front())) - before.signed_volume;
    report->dug = dig;
    report->genus_change = after.genus - before.genus;
  }
  return result;
}

}  // namespace ps
