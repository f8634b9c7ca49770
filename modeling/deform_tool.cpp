// Deformation tool (thesis 3.2.2, 3.3.3). The only CGAL use is the AABB tree of MeshRayCaster.
#include "modeling/deform_tool.h"

// GCC reports a false -Wmaybe-uninitialized inside CGAL's AABB ray traversal (boost::optional
// returned as boost::none in AABB_traits.h) when building with sanitizers; the header is not ours.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace ps {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 cg(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Closest point on segment [a, b] to p, as the segment parameter in [0, 1].
double closest_param(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 d = b - a;
  const double l2 = d.squaredNorm();
  return l2 > 0.0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
}

std::vector<double> cumulative_lengths(const std::vector<Vec3>& poly) {
  std::vector<double> s(poly.size(), 0.0);
  for (std::size_t i = 1; i < poly.size(); ++i) s[i] = s[i - 1] + (poly[i] - poly[i - 1]).norm();
  return s;
}

std::vector<int> sorted_minus(std::vector<int> v, const std::vector<int>& exclude) {
  std::sort(v.begin(), v.end());
  std::vector<int> ex = exclude;
  std::sort(ex.begin(), ex.end());
  std::vector<int> out;
  std::set_difference(v.begin(), v.end(), ex.begin(), ex.end(), std::back_inserter(out));
  return out;
}

}  // namespace

struct MeshRayCaster::Impl {
  Triangles triangles;
  Tree tree;
};

MeshRayCaster::MeshRayCaster(const TriMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(mesh.faces.size());
  for (const Face& f : mesh.faces)
    impl_->triangles.emplace_back(cg(mesh.vertices[static_cast<std::size_t>(f[0])]),
                                  cg(mesh.vertices[static_cast<std::size_t>(f[1])]),
                                  cg(mesh.vertices[static_cast<std::size_t>(f[2])]));
  impl_->tree.rebuild(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.accelerate_distance_queries();
}
MeshRayCaster::~MeshRayCaster() = default;
MeshRayCaster::MeshRayCaster(MeshRayCaster&&) noexcept = default;
MeshRayCaster& MeshRayCaster::operator=(MeshRayCaster&&) noexcept = default;

std::optional<MeshRayCaster::Hit> MeshRayCaster::first_hit(const Ray& ray) const {
  if (impl_->triangles.empty()) return std::nullopt;
  const K::Ray_3 r(cg(ray.origin), K::Vector_3(ray.direction.x(), ray.direction.y(), ray.direction.z()));
  const auto hit = impl_->tree.first_intersection(r);
  if (!hit) return std::nullopt;
  const K::Point_3* p = boost::get<K::Point_3>(&hit->first);
  Hit out;
  out.face = static_cast<int>(hit->second - impl_->triangles.begin());
  if (p) {
    out.point = Vec3(p->x(), p->y(), p->z());
  } else if (const K::Segment_3* s = boost::get<K::Segment_3>(&hit->first)) {
    // The ray runs inside the triangle's plane: take the segment end nearest the origin.
    const Vec3 a(s->source().x(), s->source().y(), s->source().z());
    const Vec3 b(s->target().x(), s->target().y(), s->target().z());
    out.point = (a - ray.origin).norm() < (b - ray.origin).norm() ? a : b;
  } else {
    return std::nullopt;
  }
  out.distance = (out.point - ray.origin).norm();
  return out;
}

std::vector<Vec3> project_stroke(const MeshRayCaster& caster, const Camera& camera, const std::vector<Vec2>& px) {
  std::vector<Vec3> out;
  for (const Vec2& p : px)
    if (auto h = caster.first_hit(camera.ray(p.x(), p.y()))) out.push_back(h->point);
  return out;
}

Result<HandleCurve> project_handle_stroke(const TriMesh& mesh, const MeshRayCaster& caster, const Camera& camera,
                                          const std::vector<Vec2>& stroke_px, double step_px) {
  if (stroke_px.size() < 2) return Result<HandleCurve>::error("handle stroke: needs at least two points");
  if (!(step_px > 0.0)) step_px = 1.0;
  HandleCurve hc;
  std::vector<char> face_seen(mesh.faces.size(), 0);
  auto sample = [&](const Vec2& p) {
    const auto h = caster.first_hit(camera.ray(p.x(), p.y()));
    if (!h) return;
    if (hc.points.empty() || (hc.points.back() - h->point).norm() > 0.0) hc.points.push_back(h->point);
    if (!face_seen[static_cast<std::size_t>(h->face)]) {
      face_seen[static_cast<std::size_t>(h->face)] = 1;
      hc.faces.push_back(h->face);
    }
  };
  // === Project the stroke densely so every face it crosses is met.
  sample(stroke_px.front());
  for (std::size_t i = 1; i < stroke_px.size(); ++i) {
    const Vec2 a = stroke_px[i - 1], b = stroke_px[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_px)));
    for (int k = 1; k <= n; ++k) sample(a + (b - a) * (static_cast<double>(k) / n));
  }
  if (hc.points.size() < 2)
    return Result<HandleCurve>::error("handle stroke: its projection misses the mesh (fewer than two points hit it)");
  // === Handle vertices: corners of the crossed faces, ordered by arc length of the closest
  // point on the projected curve.
  std::vector<int> verts;
  for (int f : hc.faces)
    for (int v : mesh.faces[static_cast<std::size_t>(f)]) verts.push_back(v);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  const std::vector<double> s = cumulative_lengths(hc.points);
  const double total = s.back();
  struct Item {
    double u;
    int v;
    Vec3 anchor;
  };
  std::vector<Item> items;
  for (int v : verts) {
    const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
    double best = std::numeric_limits<double>::infinity(), best_s = 0.0;
    Vec3 best_q = hc.points.front();
    for (std::size_t i = 1; i < hc.points.size(); ++i) {
      const double t = closest_param(hc.points[i - 1], hc.points[i], p);
      const Vec3 q = hc.points[i - 1] + t * (hc.points[i] - hc.points[i - 1]);
      const double d = (q - p).squaredNorm();
      if (d < best) best = d, best_s = s[i - 1] + t * (s[i] - s[i - 1]), best_q = q;
    }
    items.push_back({total > 0.0 ? best_s / total : 0.0, v, best_q});
  }
  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.u < b.u; });
  for (const auto& it : items) {
    hc.vertices.push_back(it.v);
    hc.parameters.push_back(it.u);
    hc.anchors.push_back(it.anchor);
  }
  return hc;
}

Result<Plane> least_squares_plane(const std::vector<Vec3>& points) {
  if (points.size() < 3) return Result<Plane>::error("plane fit: needs at least three points");
  // Eq. 3.7: the plane passes through the centroid.
  Vec3 c = Vec3::Zero();
  for (const auto& p : points) c += p;
  c /= static_cast<double>(points.size());
  // Eq. 3.8: M holds the centred points; the normal is V's column for the smallest singular value.
  Eigen::MatrixXd m(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = (points[i] - c).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinV);
  const Eigen::Vector3d sv = svd.singularValues();
  if (!(sv(1) > 1e-12 * std::max(sv(0), 1e-300)))
    return Result<Plane>::error("plane fit: the points are collinear (no unique plane)");
  Plane pl;
  pl.normal = svd.matrixV().col(2).normalized();
  pl.offset = pl.normal.dot(c);
  return pl;
}

Result<ReferencePlanes> reference_planes(const std::vector<Vec3>& pts, double rotation) {
  auto fit = least_squares_plane(pts);
  if (!fit) return fit.status();
  ReferencePlanes rp;
  const Vec3 a = fit->project(pts.front()), b = fit->project(pts.back());
  Vec3 dir = b - a;
  if (!(dir.norm() > 0.0)) {
    // Closed or degenerate handle: use the in-plane principal direction instead.
    Vec3 u, v;
    fit->basis(u, v);
    dir = u;
  }
  rp.axis_point = a;
  rp.axis_direction = dir.normalized();
  // Turn the base plane about the axis line through a.
  const Vec3 n = Eigen::AngleAxisd(rotation, rp.axis_direction) * fit->normal;
  rp.base.normal = n.normalized();
  rp.base.offset = rp.base.normal.dot(a);
  // Projection plane: contains the axis, orthogonal to the base plane.
  rp.projection.normal = rp.axis_direction.cross(rp.base.normal).normalized();
  rp.projection.offset = rp.projection.normal.dot(a);
  return rp;
}

Vec3 point_at_arc_length(const std::vector<Vec3>& poly, double u) {
  if (poly.size() == 1) return poly.front();
  const std::vector<double> s = cumulative_lengths(poly);
  const double target = std::clamp(u, 0.0, 1.0) * s.back();
  const auto it = std::lower_bound(s.begin(), s.end(), target);
  if (it == s.begin()) return poly.front();
  if (it == s.end()) return poly.back();
  const auto i = static_cast<std::size_t>(it - s.begin());
  const double seg = s[i] - s[i - 1];
  const double t = seg > 0.0 ? (target - s[i - 1]) / seg : 0.0;
  return poly[i - 1] + t * (poly[i] - poly[i - 1]);
}

std::vector<Vec3> resample_by_arc_length(const std::vector<Vec3>& poly, int n) {
  std::vector<Vec3> out;
  if (poly.empty() || n < 1) return out;
  for (int i = 0; i < n; ++i) out.push_back(point_at_arc_length(poly, n == 1 ? 0.0 : static_cast<double>(i) / (n - 1)));
  return out;
}

Result<std::vector<Vec3>> target_curve(const Camera& camera, const ReferencePlanes& planes,
                                       const std::vector<Vec2>& base_px, const std::vector<Vec2>& shadow_px) {
  return target_curve(camera, base_px, camera, shadow_px, planes);
}

Result<std::vector<Vec3>> target_curve(const Camera& camera, const std::vector<Vec2>& base_px,
                                       const Camera& shadow_camera, const std::vector<Vec2>& shadow_px,
                                       const ReferencePlanes& planes) {
  if (base_px.size() < 2) return Result<std::vector<Vec3>>::error("target stroke: needs at least two points");
  std::vector<Vec3> base;
  for (std::size_t i = 0; i < base_px.size(); ++i) {
    auto p = camera.lift(base_px[i].x(), base_px[i].y(), planes.base);
    if (!p)
      return Result<std::vector<Vec3>>::error("target stroke: point " + std::to_string(i) +
                                              " does not reach the base plane (the view is edge-on)");
    base.push_back(*p);
  }
  if (shadow_px.empty()) return base;
  std::vector<Vec3> shadow;
  for (std::size_t i = 0; i < shadow_px.size(); ++i) {
    auto p = shadow_camera.lift(shadow_px[i].x(), shadow_px[i].y(), planes.projection);
    if (!p)
      return Result<std::vector<Vec3>>::error("shadow stroke: point " + std::to_string(i) +
                                              " does not reach the projection plane");
    shadow.push_back(*p);
  }
  // One-to-one correspondence by arc length, then P_i = P_i^b + V_i.
  shadow = resample_by_arc_length(shadow, static_cast<int>(base.size()));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < base.size(); ++i) out.push_back(base[i] + (shadow[i] - planes.projection.project(base[i])));
  return out;
}

std::vector<Vec3> map_handles_to_target(const TriMesh& mesh, const HandleCurve& handle, const std::vector<Vec3>& target,
                                        bool keep_offsets) {
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < handle.vertices.size(); ++k) {
    Vec3 p = point_at_arc_length(target, handle.parameters[k]);
    if (keep_offsets) p += mesh.vertices[static_cast<std::size_t>(handle.vertices[k])] - handle.anchors[k];
    out.push_back(p);
  }
  return out;
}

std::vector<int> roi_by_radius(const TriMesh& mesh, const std::vector<int>& handles, double radius) {
  std::vector<int> out;
  const double r2 = radius * radius;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (int h : handles)
      if ((mesh.vertices[v] - mesh.vertices[static_cast<std::size_t>(h)]).squaredNorm() < r2) {
        out.push_back(static_cast<int>(v));
        break;
      }
  return sorted_minus(std::move(out), handles);
}

std::vector<int> roi_by_lasso(const TriMesh& mesh, const Camera& camera, const std::vector<Vec2>& lasso,
                              const std::vector<int>& exclude) {
  std::vector<int> out;
  if (lasso.size() < 3) return out;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const auto p = camera.project(mesh.vertices[v]);
    if (!p) continue;
    bool inside = false;  // even-odd crossing test
    for (std::size_t i = 0, j = lasso.size() - 1; i < lasso.size(); j = i++) {
      const Vec2& a = lasso[i];
      const Vec2& b = lasso[j];
      if ((a.y() > p->y()) != (b.y() > p->y()) &&
          p->x() < (b.x() - a.x()) * (p->y() - a.y()) / (b.y() - a.y()) + a.x())
        inside = !inside;
    }
    if (inside) out.push_back(static_cast<int>(v));
  }
  return sorted_minus(std::move(out), exclude);
}

std::vector<int> roi_by_brush(const TriMesh& mesh, const std::vector<Vec3>& brush, double radius,
                              const std::vector<int>& exclude) {
  std::vector<int> out;
  const double r2 = radius * radius;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (const auto& b : brush)
      if ((mesh.vertices[v] - b).squaredNorm() < r2) {
        out.push_back(static_cast<int>(v));
        break;
      }
  return sorted_minus(std::move(out), exclude);
}

}  // namespace ps
