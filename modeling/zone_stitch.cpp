// Stitching of zone solids: cap XOR per internal face (CGAL constrained Delaunay triangulation
// with exact predicates), welding and T-junction removal (hand-written: plain index bookkeeping
// on a soup, which no CGAL function does on a soup with tolerance).
#include "modeling/zone_stitch.h"

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/radix_sort.h"
#include "modeling/section_validate.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <tuple>
#include <unordered_map>

namespace ps {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Default, CGAL::Exact_predicates_tag>;

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

using Tri2 = std::array<Vec2, 3>;

struct FaceBucket {
  PlaneFrame frame;                // of the face's plane (an axis frame in the grid case)
  std::vector<Tri2> below, above;  // caps of the zone below (normal +frame.normal) and above
  std::map<std::pair<double, double>, Vec3> lift;  // 2D image -> the 3D point it came from
};

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool in_triangle(const Tri2& t, const Vec2& p) {
  const double s = orient(t[0], t[1], t[2]);
  const double a = orient(t[0], t[1], p), b = orient(t[1], t[2], p), c = orient(t[2], t[0], p);
  if (s > 0) return a > 0 && b > 0 && c > 0;
  return a < 0 && b < 0 && c < 0;
}

// A CDT point back in 3D: the cap point it came from when there is one (exact for axis frames
// anyway; for other planes it keeps the union's rounded points bit for bit), else the frame's.
Vec3 lift(const FaceBucket& b, const Vec2& q) {
  const auto it = b.lift.find({q.x(), q.y()});
  return it != b.lift.end() ? it->second : b.frame.to_3d(q);
}

std::vector<std::array<double, 6>> canonical(const std::vector<Tri2>& tris) {
  std::vector<std::array<double, 6>> out;
  out.reserve(tris.size());
  for (const auto& t : tris) {
    std::array<std::pair<double, double>, 3> v{{{t[0].x(), t[0].y()}, {t[1].x(), t[1].y()}, {t[2].x(), t[2].y()}}};
    std::sort(v.begin(), v.end());
    out.push_back({v[0].first, v[0].second, v[1].first, v[1].second, v[2].first, v[2].second});
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The constraint segments of a bucket: every triangle edge once, split at the points of the
// bucket that lie within tol of its interior without being on it exactly. Two caps whose
// boundaries meet in a chain of points rounding left a few 1e-20 either side of the other
// cap's edge (stress seed 466: two points 1e-17 off an edge 0.008 long) otherwise give the CDT
// constraints that cross at a grazing angle; their intersection points, constructed in doubles,
// left a triangulation whose faces covered the region between the chains twice, and the stitch
// an edge with three faces. A point exactly on an edge is unchanged: the CDT splits there
// anyway. Written here because CGAL's snap rounding (Snap_rounding_2) moves every vertex to a
// grid centre, including the curve points the surface must interpolate.
std::vector<std::array<Vec2, 2>> snapped_segments(const FaceBucket& b, double tol) {
  std::vector<std::pair<double, double>> points;
  for (const auto* side : {&b.below, &b.above})
    for (const auto& t : *side)
      for (const auto& p : t) points.emplace_back(p.x(), p.y());
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  // Edges in the order the triangles list them (the order of insertion decides between
  // cocircular triangulations, so it stays what it was before this split existed).
  std::vector<std::array<Vec2, 2>> out;
  std::vector<std::pair<double, Vec2>> on;
  for (const auto* side : {&b.below, &b.above})
    for (const auto& tri : *side)
      for (int i = 0; i < 3; ++i) {
        const Vec2& pa = tri[uz(i)];
        const Vec2& pc = tri[uz((i + 1) % 3)];
        const Vec2 d = pc - pa;
        const double len2 = d.squaredNorm();
        on.clear();
        if (len2 > 0) {
          // Points sorted by x: only those with x in the edge's range (widened by tol).
          const double x0 = std::min(pa.x(), pc.x()) - tol, x1 = std::max(pa.x(), pc.x()) + tol;
          const double y0 = std::min(pa.y(), pc.y()) - tol, y1 = std::max(pa.y(), pc.y()) + tol;
          for (auto it = std::lower_bound(points.begin(), points.end(), std::make_pair(x0, -HUGE_VAL));
               it != points.end() && it->first <= x1; ++it) {
            const Vec2 p(it->first, it->second);
            if (p.y() < y0 || p.y() > y1) continue;
            const double t = (p - pa).dot(d) / len2;
            if (!(t > 0.0 && t < 1.0)) continue;
            if ((pa + t * d - p).norm() > tol || (p - pa).norm() <= tol || (p - pc).norm() <= tol) continue;
            // Exactly on the edge: the CDT splits there itself.
            if (CGAL::orientation(K::Point_2(pa.x(), pa.y()), K::Point_2(pc.x(), pc.y()), K::Point_2(p.x(), p.y())) ==
                CGAL::COLLINEAR)
              continue;
            on.emplace_back(t, p);
          }
        }
        if (on.empty()) {
          out.push_back({pa, pc});
          continue;
        }
        std::sort(on.begin(), on.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        Vec2 prev = pa;
        for (const auto& [t, p] : on) {
          out.push_back({prev, p});
          prev = p;
        }
        out.push_back({prev, pc});
      }
  return out;
}

// Triangles of (below XOR above), oriented outward, appended to `out` as 3D triangles.
int cap_xor(const FaceBucket& b, double tol, std::vector<std::array<Vec3, 3>>& out) {
  if (canonical(b.below) == canonical(b.above)) return 0;
  CDT cdt;
  for (const auto& [p, q] : snapped_segments(b, tol))
    cdt.insert_constraint(CDT::Point(p.x(), p.y()), CDT::Point(q.x(), q.y()));
  int kept = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    Tri2 t;
    for (int i = 0; i < 3; ++i) t[uz(i)] = Vec2(f->vertex(i)->point().x(), f->vertex(i)->point().y());
    const Vec2 c = (t[0] + t[1] + t[2]) / 3.0;
    bool in_below = false, in_above = false;
    for (const auto& q : b.below)
      if (in_triangle(q, c)) {
        in_below = true;
        break;
      }
    for (const auto& q : b.above)
      if (in_triangle(q, c)) {
        in_above = true;
        break;
      }
    if (in_below == in_above) continue;
    // CDT faces are counter-clockwise in (u, v), i.e. normal +frame.normal: right for the zone
    // below.
    std::array<Vec3, 3> tri{lift(b, t[0]), lift(b, t[1]), lift(b, t[2])};
    if (in_above) std::swap(tri[1], tri[2]);
    out.push_back(tri);
    ++kept;
  }
  return kept;
}

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
// Unsigned arithmetic: cell indices far from the origin (a model 1e12 of its size away) made
// the signed products overflow (undefined behaviour); unsigned ones wrap to the same bits.
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return static_cast<std::size_t>(static_cast<std::uint64_t>(k.x) * 73856093ULL ^
                                    static_cast<std::uint64_t>(k.y) * 19349663ULL ^
                                    static_cast<std::uint64_t>(k.z) * 83492791ULL);
  }
};
// Cell indices are clamped to +-2^62 before the conversion (a double beyond the int64 range
// converts with undefined behaviour); clamped points share a cell, which only adds candidates.
CellKey cell_of(const Vec3& p, double h) {
  constexpr double kLimit = 4611686018427387904.0;  // 2^62
  auto index = [&](double c) { return static_cast<std::int64_t>(std::clamp(std::floor(c / h), -kLimit, kLimit)); };
  return {index(p.x()), index(p.y()), index(p.z())};
}

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

}  // namespace

int split_t_junctions(TriMesh& m, double tol) {
  int total = 0;
  for (int pass = 0; pass < 4; ++pass) {
    // Edges used once: sorted (key, 3 * face + corner) pairs, runs of length one.
    std::vector<std::pair<std::uint64_t, std::size_t>> half;
    half.reserve(m.faces.size() * 3);
    for (std::size_t fi = 0; fi < m.faces.size(); ++fi)
      for (int i = 0; i < 3; ++i)
        half.emplace_back(edge_key(m.faces[fi][uz(i)], m.faces[fi][uz((i + 1) % 3)]), 3 * fi + uz(i));
    std::sort(half.begin(), half.end());
    std::vector<char> boundary_vertex(m.vertices.size(), 0);
    std::vector<std::array<int, 3>> bedges;  // face, corner i (edge i -> i+1), in face order
    for (std::size_t i = 0; i < half.size();) {
      std::size_t j = i + 1;
      while (j < half.size() && half[j].first == half[i].first) ++j;
      if (j - i == 1) {
        const std::size_t fi = half[i].second / 3;
        const int c = static_cast<int>(half[i].second % 3);
        bedges.push_back({static_cast<int>(fi), c, 0});
        boundary_vertex[uz(m.faces[fi][uz(c)])] = boundary_vertex[uz(m.faces[fi][uz((c + 1) % 3)])] = 1;
      }
      i = j;
    }
    if (bedges.empty()) break;
    std::sort(bedges.begin(), bedges.end());
    double mean = 0.0;
    for (const auto& e : bedges) {
      const auto& f = m.faces[uz(e[0])];
      mean += (m.vertices[uz(f[uz(e[1])])] - m.vertices[uz(f[uz((e[1] + 1) % 3)])]).norm();
    }
    const double h = std::max(mean / static_cast<double>(bedges.size()), 100.0 * tol);
    std::unordered_map<CellKey, std::vector<int>, CellHash> grid;
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (boundary_vertex[v]) grid[cell_of(m.vertices[v], h)].push_back(static_cast<int>(v));
    std::map<int, std::vector<std::pair<int, std::vector<std::pair<double, int>>>>> splits;  // face -> (edge, points)
    int found = 0;
    for (const auto& e : bedges) {
      const auto& f = m.faces[uz(e[0])];
      const int a = f[uz(e[1])], b = f[uz((e[1] + 1) % 3)];
      const Vec3 pa = m.vertices[uz(a)], pb = m.vertices[uz(b)];
      const Vec3 d = pb - pa;
      const double len2 = d.squaredNorm();
      if (!(len2 > 0)) continue;
      const CellKey lo = cell_of(pa.cwiseMin(pb) - Vec3::Constant(tol), h);
      const CellKey hi = cell_of(pa.cwiseMax(pb) + Vec3::Constant(tol), h);
      std::vector<std::pair<double, int>> on;
      for (std::int64_t x = lo.x; x <= hi.x; ++x)
        for (std::int64_t y = lo.y; y <= hi.y; ++y)
          for (std::int64_t z = lo.z; z <= hi.z; ++z) {
            const auto it = grid.find({x, y, z});
            if (it == grid.end()) continue;
            for (int v : it->second) {
              if (v == a || v == b) continue;
              const Vec3 p = m.vertices[uz(v)];
              const double t = (p - pa).dot(d) / len2;
              if (!(t > 0.0 && t < 1.0)) continue;
              if ((pa + t * d - p).norm() > tol) continue;
              if ((p - pa).norm() <= tol || (p - pb).norm() <= tol) continue;
              on.emplace_back(t, v);
            }
          }
      if (on.empty()) continue;
      std::sort(on.begin(), on.end());
      splits[e[0]].push_back({e[1], std::move(on)});
      ++found;
    }
    if (found == 0) break;
    total += found;
    std::vector<Face> faces;
    faces.reserve(m.faces.size() + static_cast<std::size_t>(found) * 2);
    for (std::size_t fi = 0; fi < m.faces.size(); ++fi) {
      const auto it = splits.find(static_cast<int>(fi));
      if (it == splits.end()) {
        faces.push_back(m.faces[fi]);
        continue;
      }
      // Split along the first listed edge only; later passes handle the others.
      const auto& [corner, pts] = it->second.front();
      const Face f = m.faces[fi];
      const int a = f[uz(corner)], b = f[uz((corner + 1) % 3)], c = f[uz((corner + 2) % 3)];
      // A face whose own apex c lies on the split edge (a flat sliver, stress seed 250) would
      // give faces with a repeated corner; those are left out, which removes the sliver.
      auto keep = [&](int p0, int p1) {
        if (p0 != p1 && p0 != c && p1 != c) faces.push_back({p0, p1, c});
      };
      int prev = a;
      for (const auto& [t, v] : pts) {
        keep(prev, v);
        prev = v;
      }
      keep(prev, b);
    }
    m.faces = std::move(faces);
  }
  return total;
}

namespace {

// Merges the vertices of `m` given by `parent` (union-find forest, roots are smallest indices).
TriMesh apply_merge(const TriMesh& mesh, std::vector<int>& parent) {
  const std::size_t n = mesh.vertices.size();
  auto find = [&](int v) {
    while (parent[uz(v)] != v) v = parent[uz(v)] = parent[uz(parent[uz(v)])];
    return v;
  };
  std::vector<int> map(n, -1);
  TriMesh out;
  for (std::size_t v = 0; v < n; ++v) {
    const int r = find(static_cast<int>(v));
    if (map[uz(r)] < 0) {
      map[uz(r)] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(mesh.vertices[uz(r)]);
    }
    map[v] = map[uz(r)];
  }
  for (const auto& f : mesh.faces) {
    const Face g{map[uz(f[0])], map[uz(f[1])], map[uz(f[2])]};
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) continue;
    out.faces.push_back(g);
  }
  return out;
}

}  // namespace

namespace {

// Merges bit-identical positions while a mesh is built (-0 counts as +0, which compares
// equal): vertices are numbered in order of first appearance and faces that collapse are
// dropped, which is what merging a finished soup with the smallest index as root gives.
class ExactWelder {
 public:
  explicit ExactWelder(std::size_t vertices) { index_.reserve(vertices); }
  int vertex(const Vec3& p) {
    std::array<std::uint64_t, 3> bits{};
    for (int c = 0; c < 3; ++c) {
      const double x = p[c] + 0.0;
      std::memcpy(&bits[uz(c)], &x, sizeof x);
    }
    const auto [it, inserted] = index_.emplace(bits, static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(p);
    return it->second;
  }
  void face(int a, int b, int c) {
    if (a != b && b != c && a != c) mesh.faces.push_back({a, b, c});
  }
  void triangle(const std::array<Vec3, 3>& t) { face(vertex(t[0]), vertex(t[1]), vertex(t[2])); }
  TriMesh mesh;

 private:
  struct PointHash {
    std::size_t operator()(const std::array<std::uint64_t, 3>& b) const {
      std::uint64_t h = 1469598103934665603ULL;
      for (std::uint64_t w : b) h = (h ^ w) * 1099511628211ULL ^ (w >> 29);
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<std::array<std::uint64_t, 3>, int, PointHash> index_;
};

// `closed` (optional) is set when `exact` has no boundary edge (nothing to merge or split).
TriMesh weld_near(TriMesh exact, double tol, bool* closed = nullptr);

}  // namespace

TriMesh weld_vertices(const TriMesh& mesh, double tol) {
  // 1. Identical positions (most of them: shared points are rounded from the same exact value).
  ExactWelder welder(mesh.vertices.size());
  std::vector<int> index(mesh.vertices.size());
  for (std::size_t v = 0; v < index.size(); ++v) index[v] = welder.vertex(mesh.vertices[v]);
  for (const auto& f : mesh.faces) welder.face(index[uz(f[0])], index[uz(f[1])], index[uz(f[2])]);
  return weld_near(std::move(welder.mesh), tol);
}

namespace {

TriMesh weld_near(TriMesh exact, double tol, bool* closed) {
  // 2. Near positions, only among vertices of boundary edges (where sides failed to meet):
  //    sort-and-sweep along x with union-find, smallest index wins.
  //    Undirected edges as min * n + max, radix-sorted: an edge seen once is a boundary edge.
  const auto n = static_cast<std::uint64_t>(exact.vertices.size());
  std::vector<std::uint64_t> edges;
  edges.reserve(exact.faces.size() * 3);
  for (const auto& f : exact.faces)
    for (int i = 0; i < 3; ++i) {
      const auto a = static_cast<std::uint64_t>(f[uz(i)]), b = static_cast<std::uint64_t>(f[uz((i + 1) % 3)]);
      edges.push_back(std::min(a, b) * n + std::max(a, b));
    }
  radix_sort(edges, bits_for(n * n));
  std::vector<int> cand;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) {
      cand.push_back(static_cast<int>(edges[i] / n));
      cand.push_back(static_cast<int>(edges[i] % n));
    }
    i = j;
  }
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  if (closed) *closed = cand.empty();
  if (cand.empty()) return exact;
  std::vector<int> par2(exact.vertices.size());
  for (std::size_t i = 0; i < par2.size(); ++i) par2[i] = static_cast<int>(i);
  auto find = [&](int v) {
    while (par2[uz(v)] != v) v = par2[uz(v)] = par2[uz(par2[uz(v)])];
    return v;
  };
  std::sort(cand.begin(), cand.end(), [&](int a, int b) {
    return exact.vertices[uz(a)].x() < exact.vertices[uz(b)].x() ||
           (exact.vertices[uz(a)].x() == exact.vertices[uz(b)].x() && a < b);
  });
  for (std::size_t a = 0; a < cand.size(); ++a) {
    const Vec3& p = exact.vertices[uz(cand[a])];
    for (std::size_t b = a + 1; b < cand.size(); ++b) {
      const Vec3& q = exact.vertices[uz(cand[b])];
      if (q.x() - p.x() > tol) break;
      if ((q - p).norm() > tol) continue;
      const int ra = find(cand[a]), rb = find(cand[b]);
      if (ra != rb) par2[uz(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  return apply_merge(exact, par2);
}

}  // namespace

bool repair_close_vertices(TriMesh& m, double tol) {
  const std::size_t n = m.vertices.size();
  std::vector<int> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int v) {
    while (parent[uz(v)] != v) v = parent[uz(v)] = parent[uz(parent[uz(v)])];
    return v;
  };
  // Grid hash with cells of size tol: a vertex within tol of another lies in a neighbouring
  // cell. (A sweep along one axis is quadratic here: thousands of vertices share the
  // coordinate of a zone face.)
  //    Cells sorted lexicographically; the neighbours of a cell are found by binary search on
  //    its 9 neighbouring (x, y) columns (no hash map of 20k small vectors).
  if (!(tol > 0)) return true;
  std::vector<std::pair<std::array<std::int64_t, 3>, int>> cells(n);
  for (std::size_t v = 0; v < n; ++v) {
    const CellKey c = cell_of(m.vertices[v], tol);
    cells[v] = {{c.x, c.y, c.z}, static_cast<int>(v)};
  }
  std::sort(cells.begin(), cells.end());
  std::vector<char> close(n, 0);
  bool any = false;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3& p = m.vertices[v];
    const CellKey c = cell_of(p, tol);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const std::pair<std::array<std::int64_t, 3>, int> lo{{c.x + dx, c.y + dy, c.z - 1}, -1};
        const std::array<std::int64_t, 3> hi{c.x + dx, c.y + dy, c.z + 1};
        for (auto it = std::lower_bound(cells.begin(), cells.end(), lo); it != cells.end() && it->first <= hi; ++it) {
          const int w = it->second;
          if (uz(w) <= v || (m.vertices[uz(w)] - p).norm() > tol) continue;
          close[v] = close[uz(w)] = 1;
          const int ra = find(static_cast<int>(v)), rb = find(w);
          if (ra != rb) parent[uz(std::max(ra, rb))] = std::min(ra, rb);
          any = true;
        }
      }
  }
  if (!any) return true;
  if (intersecting_face_pairs(m.vertices, m.faces, faces_touching(m, close)).empty()) return true;
  TriMesh merged = apply_merge(m, parent);
  // apply_merge numbers the roots in index order; mark the images of the merged vertices.
  std::vector<int> image(n, -1);
  int next = 0;
  for (std::size_t v = 0; v < n; ++v)
    if (find(static_cast<int>(v)) == static_cast<int>(v)) image[v] = next++;
  std::vector<char> mark(merged.vertices.size(), 0);
  for (std::size_t v = 0; v < n; ++v)
    if (close[v]) mark[uz(image[uz(find(static_cast<int>(v)))])] = 1;
  const bool clean = intersecting_face_pairs(merged.vertices, merged.faces, faces_touching(merged, mark)).empty();
  m = std::move(merged);
  canonicalize(m);
  return clean;
}

void canonicalize(TriMesh& m) {
  std::vector<int> order(m.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  auto key = [&](int i) {
    const Vec3& p = m.vertices[uz(i)];
    return std::make_tuple(p.x(), p.y(), p.z());
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::vector<int> rank(order.size());
  std::vector<Vec3> vertices(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[uz(order[i])] = static_cast<int>(i);
    vertices[i] = m.vertices[uz(order[i])];
  }
  for (auto& f : m.faces) {
    Face g{rank[uz(f[0])], rank[uz(f[1])], rank[uz(f[2])]};
    while (g[0] > g[1] || g[0] > g[2]) g = Face{g[1], g[2], g[0]};
    f = g;
  }
  std::sort(m.faces.begin(), m.faces.end());
  m.vertices = std::move(vertices);
}

namespace {
TriMesh finish_weld(TriMesh exact, double tol, StitchReport& rep);
}  // namespace

TriMesh stitch_zones(const Partition& part, const std::vector<TriMesh>& solids, double tol, StitchReport* report) {
  StitchReport rep;
  std::map<std::array<int, 4>, FaceBucket> buckets;  // (axis, layer, cell_u, cell_v)
  // The kept triangles go straight into the welder (each zone vertex hashed once), in the order
  // of the soup they form: zones in order, then the caps.
  std::size_t total = 0;
  for (std::size_t zi = 0; zi < part.zones.size() && zi < solids.size(); ++zi) total += solids[zi].vertices.size();
  ExactWelder welder(total);
  std::vector<int> index;
  for (std::size_t zi = 0; zi < part.zones.size() && zi < solids.size(); ++zi) {
    const Zone& z = part.zones[zi];
    const TriMesh& s = solids[zi];
    index.assign(s.vertices.size(), -1);
    for (const auto& f : s.faces) {
      const std::array<Vec3, 3> t{s.vertices[uz(f[0])], s.vertices[uz(f[1])], s.vertices[uz(f[2])]};
      int face = -1;
      for (int a = 0; a < 3 && face < 0; ++a) {
        for (int side = 0; side < 2; ++side) {
          const double c = side == 0 ? z.min[a] : z.max[a];
          if (std::abs(t[0][a] - c) <= tol && std::abs(t[1][a] - c) <= tol && std::abs(t[2][a] - c) <= tol) {
            face = 2 * a + side;
            break;
          }
        }
      }
      if (face < 0 || z.on_box[uz(face)]) {
        std::array<int, 3> g{};
        for (std::size_t i = 0; i < 3; ++i) {
          int& v = index[uz(f[i])];
          if (v < 0) v = welder.vertex(t[i]);
          g[i] = v;
        }
        welder.face(g[0], g[1], g[2]);
        continue;
      }
      const int a = face / 2, side = face % 2;
      const int layer = z.cell[uz(a)] + side;
      FaceBucket& b = buckets[{a, layer, z.cell[uz((a + 1) % 3)], z.cell[uz((a + 2) % 3)]}];
      b.frame = plane_frame(Plane{Vec3::Unit(a), part.grid.coords[uz(a)][uz(layer)]});
      Tri2 t2{Vec2(t[0][(a + 1) % 3], t[0][(a + 2) % 3]), Vec2(t[1][(a + 1) % 3], t[1][(a + 2) % 3]),
              Vec2(t[2][(a + 1) % 3], t[2][(a + 2) % 3])};
      (side == 1 ? b.below : b.above).push_back(t2);
      ++rep.face_triangles_removed;
    }
  }
  std::vector<std::array<Vec3, 3>> caps;
  for (const auto& [key, b] : buckets) rep.cap_triangles_kept += cap_xor(b, tol, caps);
  for (const auto& t : caps) welder.triangle(t);
  TriMesh m = finish_weld(std::move(welder.mesh), tol, rep);
  if (report) *report = rep;
  return m;
}

TriMesh stitch_polyhedral_zones(const PolyPartition& part, const std::vector<TriMesh>& solids, double tol,
                                StitchReport* report) {
  StitchReport rep;
  std::map<int, FaceBucket> buckets;  // by shared face
  std::vector<std::array<Vec3, 3>> soup;
  for (std::size_t zi = 0; zi < part.zones.size() && zi < solids.size(); ++zi) {
    const PolyZone& z = part.zones[zi];
    const TriMesh& s = solids[zi];
    for (const auto& f : s.faces) {
      const std::array<Vec3, 3> t{s.vertices[uz(f[0])], s.vertices[uz(f[1])], s.vertices[uz(f[2])]};
      int face = -1;
      for (std::size_t k = 0; k < z.faces.size() && face < 0; ++k) {
        const Plane& pl = part.planes[uz(z.faces[k].plane)];
        if (std::abs(pl.signed_distance(t[0])) <= tol && std::abs(pl.signed_distance(t[1])) <= tol &&
            std::abs(pl.signed_distance(t[2])) <= tol)
          face = static_cast<int>(k);
      }
      if (face < 0 || z.faces[uz(face)].on_box()) {
        soup.push_back(t);
        continue;
      }
      const PolyFace& pf = z.faces[uz(face)];
      FaceBucket& b = buckets[pf.shared];
      const Plane& pl = part.planes[uz(pf.plane)];
      b.frame = plane_frame(pl);
      Tri2 t2;
      for (std::size_t i = 0; i < 3; ++i) {
        t2[i] = b.frame.to_2d(t[i]);
        b.lift.emplace(std::make_pair(t2[i].x(), t2[i].y()), t[i]);
      }
      // The zone on the plane's negative side has outward normal +normal: "below".
      (pf.normal.dot(pl.normal) > 0 ? b.below : b.above).push_back(t2);
      ++rep.face_triangles_removed;
    }
  }
  for (const auto& [key, b] : buckets) rep.cap_triangles_kept += cap_xor(b, tol, soup);
  ExactWelder welder(soup.size() * 3);
  for (const auto& t : soup) welder.triangle(t);
  TriMesh m = finish_weld(std::move(welder.mesh), tol, rep);
  if (report) *report = rep;
  return m;
}

namespace {

// Near merges, T-junctions and canonical order of a mesh whose identical points are merged.
TriMesh finish_weld(TriMesh exact, double tol, StitchReport& rep) {
  // A closed mesh has no boundary edge for a T-junction to lie on.
  bool closed = false;
  TriMesh m = weld_near(std::move(exact), tol, &closed);
  rep.t_junctions_split = closed ? 0 : split_t_junctions(m, tol);
  canonicalize(m);
  return m;
}

}  // namespace
}  // namespace ps
