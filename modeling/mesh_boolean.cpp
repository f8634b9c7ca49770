// Exact Booleans by CGAL corefinement: the per-zone union of the reconstruction (replaces the
// thesis's Carve, Eq. 4.2; zone_union.h) and Booleans of whole solids for sculpting
// (mesh_boolean.h). The only translation unit including CGAL's corefinement.
#include "modeling/mesh_boolean.h"
#include "modeling/zone_union.h"

#include "modeling/coincident_walls.h"
#include "modeling/exact_snap.h"
#include "modeling/snapped_self_intersection.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <string>

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/pair_union_memo.h"
#include "modeling/zone_stitch.h"

namespace ps {

Vec3 exact::rounded_point(const K::Point_3& p) {
  // Round from the exact value: to_double of a lazy number depends on how far it was
  // evaluated, which would make the output depend on evaluation history. An interval
  // approximation that is a single double (every input point) is the exact value already.
  const auto& a = CGAL::approx(p);
  if (a.x().is_point() && a.y().is_point() && a.z().is_point()) return Vec3(a.x().inf(), a.y().inf(), a.z().inf());
  const auto& e = CGAL::exact(p);
  return Vec3(CGAL::to_double(e.x()), CGAL::to_double(e.y()), CGAL::to_double(e.z()));
}

namespace {

// Exact constructions: the sequential unions feed each result into the next one, and rounded
// intersection points (Epick) made CGAL 5.5 crash in the coplanar-face code on zone corners
// where three sections meet.
using K = exact::K;
using SurfaceMesh = exact::SurfaceMesh;
namespace PMP = CGAL::Polygon_mesh_processing;

SurfaceMesh to_surface_mesh(const TriMesh& m) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(m.vertices.size());
  for (const auto& v : m.vertices) vi.push_back(sm.add_vertex(K::Point_3(v.x(), v.y(), v.z())));
  for (const auto& f : m.faces)
    sm.add_face(vi[static_cast<std::size_t>(f[0])], vi[static_cast<std::size_t>(f[1])],
                vi[static_cast<std::size_t>(f[2])]);
  return sm;
}

// Every index stored in the mesh names an existing element. CGAL 5.5's corefinement returned
// `true` on a real data set (CSL Elephant) with a result whose connectivity held a null index;
// the next exact predicate on it read 34 GB past a property array and segfaulted. Checked
// before anything dereferences a union's output; linear in the mesh size.
bool sound_connectivity(const SurfaceMesh& sm) {
  const auto nv = sm.num_vertices(), nh = sm.num_halfedges(), nf = sm.num_faces();
  for (auto h : sm.halfedges()) {
    const auto nx = sm.next(h), op = sm.opposite(h);
    const auto v = sm.target(h);
    const auto f = sm.face(h);
    if (!nx.is_valid() || nx.idx() >= nh || !op.is_valid() || op.idx() >= nh || !v.is_valid() || v.idx() >= nv ||
        sm.is_removed(nx) || sm.is_removed(v))
      return false;
    if (f.is_valid() && (f.idx() >= nf || sm.is_removed(f))) return false;
  }
  for (auto f : sm.faces()) {
    const auto h = sm.halfedge(f);
    if (!h.is_valid() || h.idx() >= nh || sm.is_removed(h) || sm.face(h) != f) return false;
  }
  return CGAL::is_valid_polygon_mesh(sm);
}

TriMesh to_tri_mesh(SurfaceMesh& sm) {
  sm.collect_garbage();
  TriMesh m;
  m.vertices.reserve(sm.number_of_vertices());
  for (auto v : sm.vertices()) m.vertices.push_back(exact::rounded_point(sm.point(v)));
  m.faces.reserve(sm.number_of_faces());
  for (auto f : sm.faces()) {
    Face tri{};
    int i = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (i < 3) tri[static_cast<std::size_t>(i)] = static_cast<int>(v.idx());
      ++i;
    }
    m.faces.push_back(tri);
  }
  return m;
}

}  // namespace

namespace {

// The operand check of union_solids: check_solid without its signed-volume test in absolute
// coordinates (far from the origin that sum cancels to noise; prisms are outward by
// construction), the volume taken relative to the first vertex instead.
Status check_primitive(const TriMesh& m, std::size_t index, bool verified) {
  const std::string which = "primitive " + std::to_string(index);
  if (m.faces.empty() || m.vertices.empty()) return Status::error(which + " is empty");
  for (const auto& v : m.vertices)
    if (!v.allFinite()) return Status::error(which + " has a non-finite coordinate");
  for (const auto& f : m.faces)
    for (int c : f)
      if (c < 0 || static_cast<std::size_t>(c) >= m.vertices.size()) return Status::error(which + " has a face index out of range");
  const MeshTopology t = mesh_topology(m);
  if (!t.closed || !t.manifold() || !t.consistently_oriented)
    return Status::error(which + " is not a closed, oriented 2-manifold (" + t.problem + ")");
  if (!(signed_volume(m, m.vertices.front()) > 0)) return Status::error(which + " is inside out (negative volume)");
  if (!verified && !self_intersecting_pairs(m).empty()) return Status::error(which + " intersects itself");
  return Status::ok();
}

}  // namespace

// Each primitive is checked first (closed, oriented, positive volume, no self-intersection):
// CGAL's preconditions are compiled out, and corefinement fed a self-intersecting prism
// segfaulted or looped forever (stress seeds 281, 845, 104, 293). The union is written to a
// fresh mesh, not in place: CGAL 5.5's in-place path (compute_inplace_operation ->
// append_patches_to_triangle_mesh) looped forever on valid primitives (seeds 353, 605, 722).
Result<TriMesh> union_solids(const std::vector<TriMesh>& solids) { return union_solids(solids, {}); }

Result<TriMesh> union_solids(const std::vector<TriMesh>& solids, const std::vector<bool>& verified) {
  if (solids.empty()) return TriMesh{};
  for (std::size_t i = 0; i < solids.size(); ++i)
    if (Status s = check_primitive(solids[i], i, verified.size() == solids.size() && verified[i]); !s)
      return Result<TriMesh>::error(s.message());
  if (solids.size() == 1) return solids.front();
  SurfaceMesh acc = to_surface_mesh(solids.front());
  for (std::size_t i = 1; i < solids.size(); ++i) {
    SurfaceMesh next = to_surface_mesh(solids[i]);
    SurfaceMesh out;
    bool ok = false;
    try {
      ok = PMP::corefine_and_compute_union(acc, next, out);
    } catch (const std::exception& e) {
      return Result<TriMesh>::error(std::string("union of primitives failed: ") + e.what());
    }
    if (!ok) return Result<TriMesh>::error("union of primitives would not be 2-manifold (primitive " + std::to_string(i) + ")");
    if (!sound_connectivity(out))
      return Result<TriMesh>::error("union of primitives gave a corrupt mesh (primitive " + std::to_string(i) + ")");
    acc = std::move(out);
  }
  return to_tri_mesh(acc);
}

// === Snapped solids (chapter 6): vertices made exact on their planes.
namespace {

using FT = K::FT;

// An exact point on the planes listed in `tags`, next to p (p lies on them up to rounding).
// Hand-written: CGAL projects onto one plane or line, not onto the intersection of up to three
// planes given by double coefficients. The point keeps as many of p's double coordinates as
// the planes leave free and solves for the others (one plane: the coordinate of the normal's
// largest component; two: all but the line direction's largest component; three: the vertex
// by Cramer's rule). Solving rather than projecting keeps the rationals short (denominators
// of one double, or a 2x2 determinant), which is what the union's exact predicates pay for on
// every coplanar test.
K::Point_3 snap_point(const Vec3& p, const std::array<int, 3>& tags, const std::vector<Plane>& planes) {
  std::array<const Plane*, 3> on{};
  int k = 0;
  for (int t : tags)
    if (t >= 0 && static_cast<std::size_t>(t) < planes.size()) on[static_cast<std::size_t>(k++)] = &planes[static_cast<std::size_t>(t)];
  std::array<FT, 3> x{FT(p.x()), FT(p.y()), FT(p.z())};
  auto largest = [](const Vec3& v) {
    int m = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(v[c]) > std::abs(v[m])) m = c;
    return m;
  };
  if (k == 1) {
    const Plane& a = *on[0];
    const int c = largest(a.normal);
    FT r(a.offset);
    for (int j = 0; j < 3; ++j)
      if (j != c) r -= FT(a.normal[j]) * x[static_cast<std::size_t>(j)];
    x[static_cast<std::size_t>(c)] = r / FT(a.normal[c]);
  } else if (k == 2) {
    const Plane &a = *on[0], &b = *on[1];
    const int fixed = largest(a.normal.cross(b.normal));
    const int i = (fixed + 1) % 3, j = (fixed + 2) % 3;
    const FT ra = FT(a.offset) - FT(a.normal[fixed]) * x[static_cast<std::size_t>(fixed)];
    const FT rb = FT(b.offset) - FT(b.normal[fixed]) * x[static_cast<std::size_t>(fixed)];
    const FT ai(a.normal[i]), aj(a.normal[j]), bi(b.normal[i]), bj(b.normal[j]);
    const FT det = ai * bj - aj * bi;
    if (!CGAL::is_zero(det)) {
      x[static_cast<std::size_t>(i)] = (ra * bj - aj * rb) / det;
      x[static_cast<std::size_t>(j)] = (ai * rb - ra * bi) / det;
    }
  } else if (k == 3) {
    std::array<std::array<FT, 3>, 3> m;
    std::array<FT, 3> r;
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 3; ++j) m[i][j] = FT(on[i]->normal[static_cast<int>(j)]);
      r[i] = FT(on[i]->offset);
    }
    auto det3 = [](const std::array<std::array<FT, 3>, 3>& q) {
      return q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
             q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
    };
    const FT det = det3(m);
    if (!CGAL::is_zero(det))
      for (std::size_t c = 0; c < 3; ++c) {
        auto mc = m;
        for (std::size_t i = 0; i < 3; ++i) mc[i][c] = r[i];
        x[c] = det3(mc) / det;
      }
  }
  return K::Point_3(x[0], x[1], x[2]);
}

SurfaceMesh to_surface_mesh(const SnappedSolid& s, const std::vector<Plane>& planes) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(s.mesh.vertices.size());
  for (std::size_t v = 0; v < s.mesh.vertices.size(); ++v) {
    const std::array<int, 3> tags = v < s.tags.size() ? s.tags[v] : std::array<int, 3>{-1, -1, -1};
    vi.push_back(sm.add_vertex(snap_point(s.mesh.vertices[v], tags, planes)));
  }
  for (const auto& f : s.mesh.faces)
    sm.add_face(vi[static_cast<std::size_t>(f[0])], vi[static_cast<std::size_t>(f[1])],
                vi[static_cast<std::size_t>(f[2])]);
  return sm;
}

}  // namespace

namespace {

// Snapping can make three points of a face exactly collinear (corefinement does not check its
// input and crashed on such faces).
bool has_degenerate_face(const SurfaceMesh& sm) {
  for (auto f : sm.faces()) {
    const auto h = sm.halfedge(f);
    if (CGAL::collinear(sm.point(sm.source(h)), sm.point(sm.target(h)), sm.point(sm.target(sm.next(h))))) return true;
  }
  return false;
}

}  // namespace

namespace exact {

SurfaceMesh snapped_surface_mesh(const SnappedSolid& s, const std::vector<Plane>& planes) {
  return to_surface_mesh(s, planes);
}

std::string unusable_operand(const SurfaceMesh& sm) {
  if (sm.is_empty()) return "is empty";
  if (!CGAL::is_valid_polygon_mesh(sm) || !CGAL::is_closed(sm)) return "is not a closed mesh";
  if (has_degenerate_face(sm)) return "has a degenerate face";
  return {};
}

TriMesh rounded(SurfaceMesh& sm) { return to_tri_mesh(sm); }

}  // namespace exact

Result<TriMesh> union_snapped_solids(const std::vector<SnappedSolid>& solids, const std::vector<Plane>& planes) {
  if (solids.empty()) return TriMesh{};
  const std::size_t n = solids.size();
  // Groups of frusta whose boxes overlap (with a margin): frusta of different groups are
  // disjoint, so their union is the plain concatenation, and corefinement (whose exact
  // constructions grow with every union chained onto the last) only runs within a group.
  std::vector<Box3> boxes(n);
  double diag = 0;
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i] = bounding_box(solids[i].mesh.vertices);
    diag = std::max(diag, boxes[i].diagonal());
  }
  const double pad = 1e-9 * diag;
  std::vector<std::size_t> group(n);
  for (std::size_t i = 0; i < n; ++i) group[i] = i;
  auto find = [&](std::size_t i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool overlap = ((boxes[i].min.array() - pad) <= boxes[j].max.array()).all() &&
                           ((boxes[j].min.array() - pad) <= boxes[i].max.array()).all();
      if (!overlap) continue;
      const std::size_t a = find(i), b = find(j);
      if (a != b) group[std::max(a, b)] = std::min(a, b);
    }
  // Walls two frusta share up to rounding made one surface (coincident_walls.h), so the pair
  // glues instead of being refused as a non-manifold contact.
  std::vector<SurfaceMesh> snapped;
  snapped.reserve(n);
  for (std::size_t i = 0; i < n; ++i) snapped.push_back(to_surface_mesh(solids[i], planes));
  std::vector<char> aligned;  // per frustum: changed by the alignment, and checked by it
  exact::align_coincident_walls(snapped, solids, 1e-14 * diag, &aligned);
  // Self-intersection verdicts of frusta as they were given (pair_union_memo.h): the same
  // frusta come back in many unions of one zone. Per thread: zones run in parallel.
  thread_local SolidVerdicts self_intersecting;
  // Every snapped point evaluated exactly now. Lazy exact points tighten their interval
  // approximations when evaluated, and corefinement's box sweep orders its work by those
  // intervals: without this, whether the self-intersection test below ran (or was answered
  // from the memo, or took its 2D path) would change the numbering and triangulation of the
  // union. Evaluated here, the union depends only on the frusta.
  for (auto& sm : snapped)
    for (auto v : sm.vertices()) CGAL::exact(sm.point(v));
  TriMesh out;
  for (std::size_t root = 0; root < n; ++root) {
    if (find(root) != root) continue;
    // The group's frusta in their given order, united pairwise in a balanced tree (shallower
    // chains of exact constructions than one running union).
    std::vector<SurfaceMesh> level;
    std::vector<std::size_t> ids;
    for (std::size_t i = root; i < n; ++i) {
      if (find(i) != root) continue;
      level.push_back(std::move(snapped[i]));
      ids.push_back(i);
      if (level.back().is_empty() || !CGAL::is_valid_polygon_mesh(level.back()) || !CGAL::is_closed(level.back()) ||
          has_degenerate_face(level.back()))
        return Result<TriMesh>::error("frustum " + std::to_string(i) + " is degenerate after snapping");
      // Corefinement's input must not intersect itself (it crashed on a real data set where
      // snapping made a frustum checked in doubles touch itself); exact test, small meshes.
      // A frustum the alignment changed and kept was tested there.
      if (!aligned[i]) {
        int verdict = self_intersecting.find(solids[i], planes);
        if (verdict < 0) {
          verdict = exact::snapped_self_intersects(level.back(), solids[i].tags, planes) ? 1 : 0;
          self_intersecting.add(solids[i], planes, verdict != 0);
        }
        if (verdict != 0)
          return Result<TriMesh>::error("frustum " + std::to_string(i) + " intersects itself after snapping");
      }
    }
    while (level.size() > 1) {
      std::vector<SurfaceMesh> next;
      std::vector<std::size_t> next_ids;
      for (std::size_t k = 0; k + 1 < level.size(); k += 2) {
        bool ok = false;
        // Into a fresh mesh: CGAL 5.5's union written over its first operand looped forever
        // on some inputs (see union_solids).
        SurfaceMesh united;
        try {
          ok = PMP::corefine_and_compute_union(level[k], level[k + 1], united);
        } catch (const std::exception& e) {
          return Result<TriMesh>::error(std::string("union of frusta failed: ") + e.what());
        }
        level[k] = std::move(united);
        if (!ok)
          return Result<TriMesh>::error("union of frusta would not be 2-manifold (frustum " + std::to_string(ids[k + 1]) + ")");
        // CGAL's next union assumes a closed, non-empty operand (it crashed in its orientation
        // test on a real data set otherwise).
        if (!sound_connectivity(level[k]))
          return Result<TriMesh>::error("union of frusta gave a corrupt mesh (frustum " + std::to_string(ids[k + 1]) + ")");
        level[k].collect_garbage();
        if (level[k].is_empty() || !CGAL::is_closed(level[k]) || has_degenerate_face(level[k]))
          return Result<TriMesh>::error("union of frusta is not closed (frustum " + std::to_string(ids[k + 1]) + ")");
        next.push_back(std::move(level[k]));
        next_ids.push_back(ids[k]);
      }
      if (level.size() % 2 == 1) {
        next.push_back(std::move(level.back()));
        next_ids.push_back(ids.back());
      }
      level = std::move(next);
      ids = std::move(next_ids);
    }
    const TriMesh part = to_tri_mesh(level.front());
    const int base = static_cast<int>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const auto& f : part.faces) out.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  return out;
}

// === Booleans of whole solids (sculpting)
namespace {

// A face by its corner coordinates, rotated so that the smallest corner comes first (the same
// oriented triangle gives the same key whatever its vertex numbering).
using FaceKey = std::array<double, 9>;
FaceKey face_key(const TriMesh& m, const Face& f) {
  std::array<std::array<double, 3>, 3> c;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3& p = m.vertices[static_cast<std::size_t>(f[i])];
    c[i] = {p.x(), p.y(), p.z()};
  }
  const std::size_t first = static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin());
  FaceKey k{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) k[3 * i + j] = c[(first + i) % 3][j];
  return k;
}

// Indices of the faces of `result` that are not faces of `a`.
std::vector<int> faces_not_in(const TriMesh& result, const TriMesh& a) {
  std::vector<FaceKey> keys;
  keys.reserve(a.faces.size());
  for (const auto& f : a.faces) keys.push_back(face_key(a, f));
  std::sort(keys.begin(), keys.end());
  std::vector<int> out;
  for (std::size_t i = 0; i < result.faces.size(); ++i)
    if (!std::binary_search(keys.begin(), keys.end(), face_key(result, result.faces[i])))
      out.push_back(static_cast<int>(i));
  return out;
}

// Rounding the exact result to doubles can leave a constructed point within a few 1e-16 of a
// vertex whose fans then cross (sculpt_bench's tunnel centred on the sphere's pole: two vertices
// 1.8e-16 apart). Vertices closer than 1e-9 of the result's diagonal whose faces cross are
// merged (repair_close_vertices), an operand's vertex kept where one of the two is (it does not
// move: the vertices are renumbered so operand vertices come first and the smallest index
// wins), and the whole test is repeated. Returns false, leaving `m` unspecified, when a
// crossing remains or the merge breaks the topology.
bool merge_rounded_neighbours(TriMesh& m, const TriMesh& a, const TriMesh& b) {
  auto key = [](const Vec3& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  std::vector<std::array<double, 3>> inputs;
  inputs.reserve(a.vertices.size() + b.vertices.size());
  for (const auto& p : a.vertices) inputs.push_back(key(p));
  for (const auto& p : b.vertices) inputs.push_back(key(p));
  std::sort(inputs.begin(), inputs.end());
  std::vector<int> order(m.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_partition(order.begin(), order.end(), [&](int v) {
    return std::binary_search(inputs.begin(), inputs.end(), key(m.vertices[static_cast<std::size_t>(v)]));
  });
  TriMesh r;
  r.vertices.reserve(m.vertices.size());
  std::vector<int> index(m.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    index[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
    r.vertices.push_back(m.vertices[static_cast<std::size_t>(order[i])]);
  }
  r.faces.reserve(m.faces.size());
  for (const auto& f : m.faces)
    r.faces.push_back({index[static_cast<std::size_t>(f[0])], index[static_cast<std::size_t>(f[1])],
                       index[static_cast<std::size_t>(f[2])]});
  if (!repair_close_vertices(r, 1e-9 * bounding_box(r.vertices).diagonal())) return false;
  const MeshTopology t = mesh_topology(r);
  if (!t.closed || !t.manifold() || !t.consistently_oriented || t.degenerate_faces > 0) return false;
  if (!intersecting_face_pairs(r.vertices, r.faces, faces_not_in(r, a)).empty()) return false;
  m = std::move(r);
  return true;
}

}  // namespace

Result<TriMesh> mesh_boolean(const TriMesh& a, const TriMesh& b, BooleanOp op, bool checked_a) {
  if (!checked_a)
    if (Status s = check_solid(a, "the model"); !s) return s;
  if (Status s = check_solid(b, "the tool solid"); !s) return s;
  SurfaceMesh ma = to_surface_mesh(a), mb = to_surface_mesh(b), out;
  bool ok = false;
  try {
    switch (op) {
      case BooleanOp::kUnion: ok = PMP::corefine_and_compute_union(ma, mb, out); break;
      case BooleanOp::kDifference: ok = PMP::corefine_and_compute_difference(ma, mb, out); break;
      case BooleanOp::kIntersection: ok = PMP::corefine_and_compute_intersection(ma, mb, out); break;
    }
  } catch (const std::exception& e) {
    return Result<TriMesh>::error(std::string("Boolean operation failed: ") + e.what());
  }
  if (!ok) return Result<TriMesh>::error("Boolean operation refused: the result would not be 2-manifold");
  if (!sound_connectivity(out)) return Result<TriMesh>::error("Boolean operation failed: CGAL returned a corrupt mesh");
  TriMesh m = to_tri_mesh(out);
  // Rounding the exact result to doubles can, in near-degenerate spots, fold a sliver. Faces of
  // `a` that came through unchanged (same corners, bit for bit) were already free of
  // intersections among themselves, so only the other faces need testing, against all faces.
  if (!intersecting_face_pairs(m.vertices, m.faces, faces_not_in(m, a)).empty()) {
    if (!merge_rounded_neighbours(m, a, b))
      return Result<TriMesh>::error("Boolean operation refused: the rounded result intersects itself");
  }
  // CGAL numbers the new vertices in the order it met the intersections, which follows heap
  // addresses (its box intersection breaks ties by box address): the same Boolean gave the same
  // triangles with other vertex numbers when other threads had used the heap (the tunnel replay
  // of tests/app_sculpt_ops_replay_test.sh under load). Canonical order makes it bit-identical.
  canonicalize(m);
  // Free of self-intersections (the faces kept from `a` among themselves, every other face
  // against all): what check_solid asks, once the topology agrees.
  remember_checked_solid(m);
  return m;
}

}  // namespace ps
