// CGAL translation unit: mesh slicing (CGAL::Polygon_mesh_slicer over an AABB tree of edges)
// and the exact simplicity check of planar polygons.
#include "modeling/mesh_slicer.h"

// Polygon_mesh_slicer's boost::adjacency_list copies default-constructed edge descriptors, which
// GCC 12 flags as maybe-uninitialized (a false positive inside boost, instantiated here).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <CGAL/AABB_halfedge_graph_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_slicer.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "modeling/mesh_topology.h"

namespace ps {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using HGSP = CGAL::AABB_halfedge_graph_segment_primitive<Mesh>;
using AabbTraits = CGAL::AABB_traits<K, HGSP>;
using AabbTree = CGAL::AABB_tree<AabbTraits>;
using Polyline = std::vector<K::Point_3>;

Vec3 to_vec(const K::Point_3& p) { return Vec3(p.x(), p.y(), p.z()); }

// Twice the signed area of a 2D polygon.
double area2(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return a;
}

// === Resampling by arc length with forced stations
// Returns points at arc-length positions along the closed polyline `pts`: every forced
// position is kept, and each stretch between consecutive forced positions gets evenly spaced
// points about `spacing` apart.
std::vector<Vec3> resample(const std::vector<Vec3>& pts, std::vector<double> forced, double spacing) {
  const std::size_t n = pts.size();
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + (pts[(i + 1) % n] - pts[i]).norm();
  const double total = cum[n];
  auto at = [&](double s) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
    const auto it = std::upper_bound(cum.begin(), cum.end(), s);
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - cum.begin()) - 1));
    if (i >= n) i = n - 1;
    const double len = cum[i + 1] - cum[i];
    const double t = len > 0 ? (s - cum[i]) / len : 0.0;
    return Vec3((1 - t) * pts[i] + t * pts[(i + 1) % n]);
  };
  if (forced.empty()) forced.push_back(0.0);
  std::sort(forced.begin(), forced.end());
  // Merge forced stations closer than a tiny fraction of the spacing.
  std::vector<double> st;
  for (double f : forced)
    if (st.empty() || f - st.back() > 1e-6 * spacing) st.push_back(f);
  if (st.size() > 1 && st.front() + total - st.back() <= 1e-6 * spacing) st.pop_back();
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < st.size(); ++k) {
    const double a = st[k];
    const double b = k + 1 < st.size() ? st[k + 1] : st[0] + total;
    const int m = std::max(1, static_cast<int>(std::lround((b - a) / spacing)));
    for (int j = 0; j < m; ++j) out.push_back(at(a + (b - a) * j / m));
  }
  return out;
}

struct Loop {
  std::vector<Vec3> raw;  // exact slice polyline, first point not repeated
  double length = 0;
};

}  // namespace

// === Plane sets
std::vector<Plane> axis_planes(const Box3& box, const std::array<int, 3>& per_axis_counts) {
  std::vector<Plane> out;
  if (box.empty()) return out;
  for (int k = 0; k < 3; ++k) {
    const int c = per_axis_counts[static_cast<std::size_t>(k)];
    for (int i = 0; i < c; ++i) {
      Plane p;
      p.normal = Vec3::Unit(k);
      p.offset = box.min[k] + (box.max[k] - box.min[k]) * (i + 1) / (c + 1);
      out.push_back(p);
    }
  }
  return out;
}

std::vector<Plane> random_planes(const Box3& box, int n, std::uint64_t seed) {
  std::vector<Plane> out;
  if (box.empty()) return out;
  SeededRandom rng(seed);
  for (int i = 0; i < n; ++i) {
    Plane p;
    p.normal = rng.unit_vector();
    Vec3 q;
    for (int k = 0; k < 3; ++k) q[k] = box.min[k] + (box.max[k] - box.min[k]) * rng.uniform(0.2, 0.8);
    p.offset = p.normal.dot(q);
    out.push_back(p);
  }
  return out;
}

// === Simplicity
bool polygons_are_simple(const std::vector<std::vector<Vec2>>& polygons, std::vector<int>* bad) {
  struct Seg {
    K::Point_2 a, b;
    int poly;
    std::size_t idx, n;
    double xmin, xmax, ymin, ymax;
  };
  std::set<int> bad_set;
  std::vector<Seg> segs;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    const auto& poly = polygons[p];
    const std::size_t n = poly.size();
    if (n < 3) {
      bad_set.insert(static_cast<int>(p));
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = poly[i];
      const Vec2& b = poly[(i + 1) % n];
      if (a == b) bad_set.insert(static_cast<int>(p));
      segs.push_back({K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()), static_cast<int>(p), i, n,
                      std::min(a.x(), b.x()), std::max(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.y(), b.y())});
    }
  }
  std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return s.xmin < t.xmin; });
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Seg& s = segs[i];
    for (std::size_t j = i + 1; j < segs.size() && segs[j].xmin <= s.xmax; ++j) {
      const Seg& t = segs[j];
      if (t.ymin > s.ymax || t.ymax < s.ymin) continue;
      if (s.poly == t.poly) {
        const std::size_t n = s.n;
        const bool next = (s.idx + 1) % n == t.idx, prev = (t.idx + 1) % n == s.idx;
        if (next || prev) {
          // Neighbours share one endpoint; they are bad only if they fold back onto each other
          // (or, for a triangle, both are neighbours and nothing else can go wrong).
          const Seg& first = next ? s : t;
          const Seg& second = next ? t : s;
          if (CGAL::orientation(first.a, first.b, second.b) == CGAL::COLLINEAR &&
              (first.b - first.a) * (second.b - second.a) < 0)
            bad_set.insert(s.poly);
          continue;
        }
      }
      if (CGAL::do_intersect(K::Segment_2(s.a, s.b), K::Segment_2(t.a, t.b))) {
        bad_set.insert(s.poly);
        bad_set.insert(t.poly);
      }
    }
  }
  if (bad) bad->assign(bad_set.begin(), bad_set.end());
  return bad_set.empty();
}

// === Slicing
Result<SectionSet> slice_mesh(const TriMesh& mesh, const std::vector<Plane>& planes_in, const SliceOptions& options,
                              std::vector<std::string>* warnings) {
  using R = Result<SectionSet>;
  if (mesh.empty()) return R::error("slice: the mesh has no faces");
  for (const auto& v : mesh.vertices)
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
      return R::error("slice: the mesh has a non-finite vertex coordinate");
  for (const auto& f : mesh.faces)
    for (int i : f)
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size())
        return R::error("slice: a face references a vertex out of range");
  const MeshTopology topo = mesh_topology(mesh);
  if (!topo.closed) return R::error("slice: the mesh is not closed (" + std::to_string(topo.boundary_edges) + " boundary edges)");
  if (!topo.manifold()) return R::error("slice: the mesh is not manifold");

  Mesh sm;
  std::vector<Mesh::Vertex_index> vid;
  vid.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) vid.push_back(sm.add_vertex(K::Point_3(v.x(), v.y(), v.z())));
  for (const auto& f : mesh.faces) {
    const auto fi = sm.add_face(vid[static_cast<std::size_t>(f[0])], vid[static_cast<std::size_t>(f[1])],
                                vid[static_cast<std::size_t>(f[2])]);
    if (fi == Mesh::null_face()) return R::error("slice: the mesh's faces do not form an oriented 2-manifold");
  }
  const Box3 box = bounding_box(mesh.vertices);
  const double diag = box.diagonal();
  if (!(diag > 0)) return R::error("slice: the mesh has zero extent");
  const double spacing = options.spacing > 0 ? options.spacing : diag / 60.0;

  AabbTree tree(edges(sm).first, edges(sm).second, sm);
  CGAL::Polygon_mesh_slicer<Mesh, K> slicer(sm, tree);

  std::vector<std::string> w;
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < planes_in.size(); ++i) {
    Plane p = planes_in[i];
    const double len = p.normal.norm();
    if (!(len > 0) || !std::isfinite(len) || !std::isfinite(p.offset))
      return R::error("slice: plane " + std::to_string(i) + " has a zero or non-finite normal");
    p.normal /= len;
    p.offset /= len;
    for (int attempt = 0; attempt < 8; ++attempt) {
      bool touches = false;
      for (const auto& v : mesh.vertices)
        if (std::abs(p.signed_distance(v)) <= 1e-9 * diag) {
          touches = true;
          break;
        }
      if (!touches) break;
      p.offset += 1e-6 * diag;
      if (attempt == 0)
        w.push_back("slice: plane " + std::to_string(i) + " passes through a mesh vertex; moved by 1e-6 of the diagonal");
    }
    planes.push_back(p);
  }

  SectionSet out;
  int open_dropped = 0, tiny_dropped = 0;
  for (std::size_t pi = 0; pi < planes.size(); ++pi) {
    const Plane& pl = planes[pi];
    std::vector<Polyline> polylines;
    slicer(K::Plane_3(pl.normal.x(), pl.normal.y(), pl.normal.z(), -pl.offset), std::back_inserter(polylines));
    Vec3 u, v;
    pl.basis(u, v);
    std::vector<Loop> loops;
    for (const auto& poly : polylines) {
      if (poly.size() < 4 || poly.front() != poly.back()) {
        ++open_dropped;
        continue;
      }
      Loop loop;
      for (std::size_t k = 0; k + 1 < poly.size(); ++k) {
        const Vec3 q = pl.project(to_vec(poly[k]));
        if (loop.raw.empty() || (q - loop.raw.back()).norm() > 1e-10 * diag) loop.raw.push_back(q);
      }
      while (loop.raw.size() > 1 && (loop.raw.front() - loop.raw.back()).norm() <= 1e-10 * diag) loop.raw.pop_back();
      std::vector<Vec2> flat;
      for (const auto& q : loop.raw) flat.emplace_back(q.dot(u), q.dot(v));
      if (loop.raw.size() < 3 || std::abs(area2(flat)) * 0.5 < options.min_area * diag * diag) {
        ++tiny_dropped;
        continue;
      }
      for (std::size_t k = 0; k < loop.raw.size(); ++k) loop.length += (loop.raw[(k + 1) % loop.raw.size()] - loop.raw[k]).norm();
      loops.push_back(std::move(loop));
    }
    if (loops.empty()) {
      if (options.keep_empty_planes) out.planes.push_back(pl);
      continue;
    }
    // Crossings with the other planes, as arc-length positions on each loop.
    std::vector<std::vector<double>> forced(loops.size());
    for (std::size_t li = 0; li < loops.size(); ++li) {
      const auto& r = loops[li].raw;
      const std::size_t n = r.size();
      double s = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const Vec3& a = r[k];
        const Vec3& b = r[(k + 1) % n];
        const double len = (b - a).norm();
        for (std::size_t pj = 0; pj < planes.size(); ++pj) {
          if (pj == pi) continue;
          const double da = planes[pj].signed_distance(a), db = planes[pj].signed_distance(b);
          if ((da < 0) != (db < 0)) forced[li].push_back(s + len * da / (da - db));
        }
        s += len;
      }
    }
    // Resample, finer on failure; as a last resort keep the raw polylines.
    std::vector<std::vector<Vec3>> curves;
    bool simple = false;
    double h = spacing;
    for (int attempt = 0; attempt < 4 && !simple; ++attempt, h *= 0.5) {
      curves.clear();
      std::vector<std::vector<Vec2>> flat;
      for (std::size_t li = 0; li < loops.size(); ++li) {
        const double hc = std::min(h, loops[li].length / options.min_points);
        auto c = resample(loops[li].raw, forced[li], hc);
        for (auto& q : c) q = pl.project(q);
        std::vector<Vec2> f;
        for (const auto& q : c) f.emplace_back(q.dot(u), q.dot(v));
        flat.push_back(std::move(f));
        curves.push_back(std::move(c));
      }
      simple = polygons_are_simple(flat);
    }
    if (!simple) {
      curves.clear();
      std::vector<std::vector<Vec2>> flat;
      for (const auto& l : loops) {
        curves.push_back(l.raw);
        std::vector<Vec2> f;
        for (const auto& q : l.raw) f.emplace_back(q.dot(u), q.dot(v));
        flat.push_back(std::move(f));
      }
      std::vector<int> bad;
      if (!polygons_are_simple(flat, &bad)) {
        for (auto it = bad.rbegin(); it != bad.rend(); ++it) curves.erase(curves.begin() + *it);
        w.push_back("slice: plane " + std::to_string(pi) + ": dropped " + std::to_string(bad.size()) +
                    " slice loop(s) that touch or cross");
      } else {
        w.push_back("slice: plane " + std::to_string(pi) + ": resampling made curves cross; kept the raw slice polylines");
      }
    }
    if (curves.empty()) continue;
    const int id = static_cast<int>(out.planes.size());
    out.planes.push_back(pl);
    for (auto& c : curves) out.curves.push_back(CrossSection{id, std::move(c)});
  }
  if (open_dropped) w.push_back("slice: dropped " + std::to_string(open_dropped) + " open polyline(s)");
  if (tiny_dropped) w.push_back("slice: dropped " + std::to_string(tiny_dropped) + " degenerate tiny loop(s)");
  if (warnings) warnings->insert(warnings->end(), w.begin(), w.end());
  return out;
}

}  // namespace ps
