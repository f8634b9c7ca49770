// The reconstruction pipeline (thesis 4.2-4.5): validate, partition, cylinders, per-zone union
// (parallel over zones with TBB, cached), stitch, curve flags, improvement hook.
#include "modeling/progressive_reconstructor.h"

#include "modeling/mesh_improve.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>
#include <tuple>
#include <unordered_map>

#include "modeling/aligned_frame.h"
#include "modeling/cavity_fill.h"
#include "modeling/content_cache.h"
#include "modeling/cylinder_builder.h"
#include "modeling/face_intersections.h"
#include "modeling/frustum_builder.h"
#include "modeling/frustum_connectors.h"
#include "modeling/frustum_nudge.h"
#include "modeling/pair_union_memo.h"
#include "modeling/polyhedral_partition.h"
#include "modeling/mesh_topology.h"
#include "modeling/nef_union.h"
#include "modeling/gap_fill.h"
#include "modeling/parallel_over.h"
#include "modeling/pinch_separate.h"
#include "modeling/reconstruction_limits.h"
#include "modeling/section_validate.h"
#include "modeling/sliver_repair.h"
#include "modeling/zone_partition.h"
#include "modeling/zone_stitch.h"
#include "modeling/zone_box_union.h"
#include "modeling/zone_stacked_union.h"
#include "modeling/zone_union.h"

namespace ps {
namespace {

// A point by its bits (the frame's points map back to the input's exactly).
struct PointKey {
  std::array<double, 3> c;
  explicit PointKey(const Vec3& p) : c{p.x(), p.y(), p.z()} {}
  bool operator==(const PointKey& o) const { return std::memcmp(c.data(), o.c.data(), sizeof c) == 0; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    ContentHash h;
    h.bytes(k.c.data(), sizeof k.c);
    return static_cast<std::size_t>(h.h);
  }
};

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

ImproveHook g_improve_hook = &improve_mesh;  // thesis 4.5.1, modeling/mesh_improve.h

// A closed surface that touches itself along edges or at vertices (material in diagonally
// opposite zones around a grid line): its sheets are separated by `gap` (pinch_separate.h) when
// that leaves no self-intersection among the faces around the moved vertices. Returns the
// number of vertices split (mesh replaced) or 0 (mesh unchanged). The gap is 1e-10 of the
// diagonal: a tenth of the tolerance by which curve vertices are recognised (curve_flags,
// 1e-9), so a moved curve vertex stays fixed in the improvement, and 1e-4 of the guarantee
// that curve points lie on the surface within 1e-6.
int separate_touching_sheets(TriMesh& mesh, double gap, PinchMode mode, PinchDirection direction) {
  TriMesh separated = mesh;
  std::vector<int> moved;
  const int split = separate_pinches(separated, gap, &moved, mode, direction);
  if (split <= 0) return 0;
  std::vector<char> mark(separated.vertices.size(), 0);
  for (int v : moved) mark[uz(v)] = 1;
  if (!intersecting_face_pairs(separated.vertices, separated.faces, faces_touching(separated, mark)).empty()) return 0;
  const MeshTopology t = mesh_topology(separated);
  if (!t.closed || !t.manifold() || !t.consistently_oriented) return 0;
  canonicalize(separated);
  mesh = std::move(separated);
  return split;
}

// Planar gaps left by the stitching (gap_fill.h) closed, when the added faces cross nothing and
// the surface is then closed and consistently oriented (it may still be pinched: see below).
// Returns the warning for the report, or empty (mesh unchanged).
std::string fill_stitch_gaps(TriMesh& mesh, double plane_tol) {
  TriMesh filled = mesh;
  std::vector<int> added;
  const int loops = fill_planar_gaps(filled, plane_tol, &added);
  if (loops <= 0) return {};
  if (!intersecting_face_pairs(filled.vertices, filled.faces, added).empty()) return {};
  const MeshTopology t = mesh_topology(filled);
  if (!t.closed || !t.consistently_oriented) return {};
  canonicalize(filled);
  mesh = std::move(filled);
  return "the stitching of zone faces left " + std::to_string(loops) +
         " planar gap(s); each was closed by its plane's region inside it";
}

// Separated first; joined by a sliver where separating splits no vertex or leaves a crossing.
// Both with the copies moved along their fans' normals, then, where that leaves a crossing
// (thin wedges and bladed fans, pinch_separate.h), along directions inside their fans.
// Returns the warning for the report, or empty (mesh unchanged).
std::string resolve_touching_sheets(TriMesh& mesh, double gap) {
  for (const PinchDirection direction : {PinchDirection::kFanNormal, PinchDirection::kInsideFan}) {
    const std::string along = direction == PinchDirection::kFanNormal ? "" : " (the copies moved inside their fans)";
    if (const int split = separate_touching_sheets(mesh, gap, PinchMode::kSeparate, direction); split > 0)
      return "the surface touched itself at " + std::to_string(split) +
             " vertices (material in diagonally opposite zones); the touching sheets were separated by 1e-10 of "
             "the bounding-box diagonal" + along;
    if (const int split = separate_touching_sheets(mesh, gap, PinchMode::kJoin, direction); split > 0)
      return "the surface touched itself at " + std::to_string(split) +
             " vertices (material in diagonally opposite zones); the touching solids were joined there by a sliver "
             "1e-10 of the bounding-box diagonal wide" + along;
  }
  return {};
}

// Flat slivers of the exact zone unions that rounding turned over (sliver_repair.h), given the
// surface's crossing face pairs: removed and the seam zipped (vertices a rounding step apart at
// its ends merged), kept when the surface is then closed, manifold, consistently oriented and
// free of crossings. Returns the warning for the report, or empty (mesh unchanged).
std::string zip_folded_slivers(TriMesh& mesh, const std::vector<std::array<int, 2>>& crossing, double tol) {
  if (crossing.empty()) return {};
  TriMesh zipped = mesh;
  const int removed = remove_folded_slivers(zipped, crossing, tol);
  if (removed <= 0) return {};
  const MeshTopology zt = mesh_topology(zipped);
  if (!zt.closed || !zt.manifold() || !zt.consistently_oriented || !self_intersecting_pairs(zipped).empty()) return {};
  canonicalize(zipped);
  mesh = std::move(zipped);
  return "rounding had folded " + std::to_string(removed) +
         " flat sliver face(s) of the exact zone unions; they were removed and the seam closed (no vertex moved by "
         "more than 1e-10 of the diagonal)";
}

// The repairs of a stitched surface given its topology `t`, for both kinds of zones: planar
// gaps filled (1e-9 of the diagonal `diag` as plane tolerance), then touching sheets resolved
// (a gap of 1e-10 of it), each reported in `warnings`. Returns whether the mesh changed (the
// caller then checks it again).
bool repair_stitched_surface(TriMesh& mesh, const MeshTopology& t, double diag, std::vector<std::string>& warnings) {
  bool changed = false;
  int boundary_edges = t.boundary_edges;
  bool manifold = t.manifold();
  if (boundary_edges > 0) {
    if (std::string w = fill_stitch_gaps(mesh, 1e-9 * diag); !w.empty()) {
      warnings.push_back(std::move(w));
      const MeshTopology filled = mesh_topology(mesh);
      boundary_edges = filled.boundary_edges;
      manifold = filled.manifold();
      changed = true;
    }
  }
  if (!manifold && boundary_edges == 0) {
    if (std::string w = resolve_touching_sheets(mesh, 1e-10 * diag); !w.empty()) {
      warnings.push_back(std::move(w));
      changed = true;
    }
  }
  return changed;
}

// === Canonical order of planes and curves (order independence, thesis 4.1 requirement 3).
SectionSet canonical_sections(const SectionSet& s) {
  auto plane_key = [](const Plane& p) { return std::make_tuple(p.normal.x(), p.normal.y(), p.normal.z(), p.offset); };
  std::vector<int> used_planes;
  for (const auto& c : s.curves)
    if (std::find(used_planes.begin(), used_planes.end(), c.plane) == used_planes.end()) used_planes.push_back(c.plane);
  std::sort(used_planes.begin(), used_planes.end(), [&](int a, int b) {
    return plane_key(s.planes[uz(a)]) < plane_key(s.planes[uz(b)]);
  });
  SectionSet out;
  out.units = s.units;
  std::vector<int> new_index(s.planes.size(), -1);
  for (int p : used_planes) {
    new_index[uz(p)] = static_cast<int>(out.planes.size());
    out.planes.push_back(s.planes[uz(p)]);
  }
  out.curves = s.curves;
  for (auto& c : out.curves) c.plane = new_index[uz(c.plane)];
  auto less_points = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), [](const Vec3& p, const Vec3& q) {
      return std::make_tuple(p.x(), p.y(), p.z()) < std::make_tuple(q.x(), q.y(), q.z());
    });
  };
  std::sort(out.curves.begin(), out.curves.end(), [&](const CrossSection& a, const CrossSection& b) {
    if (a.plane != b.plane) return a.plane < b.plane;
    return less_points(a.points, b.points);
  });
  return out;
}

std::uint64_t hash_meshes(const std::vector<TriMesh>& ms) {
  ContentHash h;
  for (const auto& m : ms) {
    for (const auto& v : m.vertices) h.bytes(v.data(), sizeof(double) * 3);
    for (const auto& f : m.faces) h.bytes(f.data(), sizeof(int) * 3);
    h.size(m.faces.size());
  }
  return h.h;
}

bool same_meshes(const std::vector<TriMesh>& a, const std::vector<TriMesh>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].vertices != b[i].vertices || a[i].faces != b[i].faces) return false;
  return true;
}

// === Curve vertices and edges (for the improvement step)
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

void curve_flags(const TriMesh& m, const SectionSet& s, double tol, std::vector<bool>& on_curve,
                 std::vector<std::array<int, 2>>& edges) {
  // Both outputs are replaced: the checks run again after a repair renumbers the vertices, and
  // edges appended to the first run's list named vertices of the unrepaired mesh (the
  // improvement then refused the result: "fixed edge ... is not an edge of the mesh").
  on_curve.assign(m.vertices.size(), false);
  edges.clear();
  std::vector<std::vector<int>> curves_of(m.vertices.size());
  for (std::size_t ci = 0; ci < s.curves.size(); ++ci) {
    const auto& c = s.curves[ci];
    const Plane& pl = s.planes[uz(c.plane)];
    Box3 b = bounding_box(c.points);
    b.min -= Vec3::Constant(tol);
    b.max += Vec3::Constant(tol);
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      const Vec3& p = m.vertices[v];
      if ((p.array() < b.min.array()).any() || (p.array() > b.max.array()).any()) continue;
      if (std::abs(pl.signed_distance(p)) > tol) continue;
      for (std::size_t j = 0; j < c.points.size(); ++j)
        if (segment_distance(p, c.points[j], c.points[(j + 1) % c.points.size()]) <= tol) {
          on_curve[v] = true;
          curves_of[v].push_back(static_cast<int>(ci));
          break;
        }
    }
  }
  std::vector<std::array<int, 2>> all;
  for (const auto& f : m.faces)
    for (int i = 0; i < 3; ++i) {
      int a = f[uz(i)], b = f[uz((i + 1) % 3)];
      if (a > b) std::swap(a, b);
      if (on_curve[uz(a)] && on_curve[uz(b)]) all.push_back({a, b});
    }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  for (const auto& e : all) {
    const Vec3 mid = 0.5 * (m.vertices[uz(e[0])] + m.vertices[uz(e[1])]);
    bool along = false;
    for (int ci : curves_of[uz(e[0])]) {
      if (std::find(curves_of[uz(e[1])].begin(), curves_of[uz(e[1])].end(), ci) == curves_of[uz(e[1])].end()) continue;
      const auto& c = s.curves[uz(ci)];
      for (std::size_t j = 0; j < c.points.size() && !along; ++j)
        along = segment_distance(mid, c.points[j], c.points[(j + 1) % c.points.size()]) <= tol;
      if (along) break;
    }
    if (along) edges.push_back(e);
  }
}

// === Scale normalisation helpers (powers of two: exact)
int scale_exponent(const Box3& box) {
  const double d = box.diagonal();
  if (!std::isfinite(d) || d <= 0) return 0;
  return -std::ilogb(d);
}

Box3 scaled_box(const Box3& b, int k) {
  Box3 out;
  for (int c = 0; c < 3; ++c) {
    out.min[c] = std::ldexp(b.min[c], k);
    out.max[c] = std::ldexp(b.max[c], k);
  }
  return out;
}

ValidatedSections scaled_sections(const ValidatedSections& in, int k) {
  ValidatedSections out = in;
  if (k == 0) return out;
  for (auto& pl : out.sections.planes) pl.offset = std::ldexp(pl.offset, k);
  for (auto& c : out.sections.curves)
    for (auto& p : c.points)
      for (int i = 0; i < 3; ++i) p[i] = std::ldexp(p[i], k);
  out.diagonal = std::ldexp(out.diagonal, k);
  return out;
}

// === Canonical axes (the grid path). A signed permutation of the axes is exact in doubles, and
// the grid path gives the same surface under one (tests/recon_axis_permutation_test.cpp), but not
// the same triangulation (the zone unions meet their operands in another order), and the mesh
// improvement follows the triangulation: a mirror of the input moved the improved surface by up
// to 0.13 of the diagonal (docs/mesh-improvement.md). So the grid runs in a frame chosen from the
// box alone: axes by decreasing extent (ties in axis order), each pointing away from the origin
// as the box's centre does (a centre on 0 keeps its sign). Moving the input by a signed
// permutation moves its box the same way, so the frame, and every bit of the result in it, is
// the same; the mesh is mapped back exactly. A function of the box, it stays while the box is
// kept, and with it the progressive caches.
struct SignedAxes {
  std::array<int, 3> axis{0, 1, 2};  // frame axis i is world axis axis[i] times sign[i]
  std::array<double, 3> sign{1.0, 1.0, 1.0};
  bool identity() const {
    return axis == std::array<int, 3>{0, 1, 2} && sign == std::array<double, 3>{1.0, 1.0, 1.0};
  }
  // A mirror (odd permutation times the signs' product negative): mapping back turns the
  // faces inside out.
  bool mirrors() const {
    const bool odd = (axis[0] > axis[1]) != ((axis[0] > axis[2]) != (axis[1] > axis[2]));
    return (sign[0] * sign[1] * sign[2] < 0.0) != odd;
  }
  Vec3 to_frame(const Vec3& p) const {
    return Vec3(sign[0] * p[axis[0]], sign[1] * p[axis[1]], sign[2] * p[axis[2]]);
  }
  Vec3 to_world(const Vec3& q) const {
    Vec3 p;
    for (int i = 0; i < 3; ++i) p[axis[uz(i)]] = sign[uz(i)] * q[i];
    return p;
  }
  Box3 to_frame(const Box3& b) const {
    Box3 out;
    for (int i = 0; i < 3; ++i) {
      const int a = axis[uz(i)];
      out.min[i] = sign[uz(i)] > 0 ? b.min[a] : -b.max[a];
      out.max[i] = sign[uz(i)] > 0 ? b.max[a] : -b.min[a];
    }
    return out;
  }
};

SignedAxes canonical_axes(const Box3& box) {
  SignedAxes f;
  const Vec3 ext = box.max - box.min;
  std::stable_sort(f.axis.begin(), f.axis.end(), [&](int x, int y) { return ext[x] > ext[y]; });
  for (int i = 0; i < 3; ++i) {
    const int a = f.axis[uz(i)];
    f.sign[uz(i)] = box.min[a] + box.max[a] < 0.0 ? -1.0 : 1.0;
  }
  return f;
}

SectionSet to_frame(const SectionSet& s, const SignedAxes& f) {
  SectionSet out = s;
  for (auto& pl : out.planes) pl.normal = f.to_frame(pl.normal);  // the offset is unchanged
  for (auto& c : out.curves)
    for (auto& p : c.points) p = f.to_frame(p);
  return out;
}

// Zone counts of either partition (grid or convex zones) into the report.
template <class Part>
void count_zones(const Part& part, ReconstructReport& rep) {
  rep.zones = static_cast<int>(part.zones.size());
  rep.empty_zones = part.count(ZoneType::kEmpty);
  rep.end_zones = part.count(ZoneType::kEnd);
  rep.body_zones = part.count(ZoneType::kBody);
}

// === Chapter 6: convex zones, frusta, unions of snapped frusta, stitching. The stage timings
// and zone counts go into `rep`; the stitched (unimproved) mesh is returned.
Result<TriMesh> reconstruct_polyhedral(const ValidatedSections& vs, const Box3& box, ReconstructReport& rep,
                                       const std::function<void(const char*, double)>& progress,
                                       int threads = 0) {
  auto t = Clock::now();
  auto part = partition_polyhedral(vs, box);
  if (!part) return part.status();
  count_zones(*part, rep);
  rep.timings.partition_ms = ms_since(t);
  progress("partition", 1.0);

  // Frusta, then the unions of each zone. A refused union (a non-manifold contact between
  // frusta) is retried with the frusta rebuilt under other margins and heights: the contacts
  // are coincidences of the construction, not of the input (same idea as the perturbation of
  // 4.3). Every attempt is deterministic. Only the zones whose union was refused are redone
  // (zones meet on faces whose contents the stitch XORs, so neighbours need not come from the
  // same attempt); a stitched surface that fails its checks sends every zone to the next
  // attempt.
  FrustumOptions wide;
  wide.face_margin = 0.045;
  wide.height_margin = 0.12;
  FrustumOptions narrow;
  narrow.face_margin = 0.009;
  narrow.height_margin = 0.03;
  const FrustumOptions attempts[] = {FrustumOptions{}, wide, narrow};
  std::vector<TriMesh> solids;
  TriMesh mesh;
  std::string failure;
  std::size_t todo_count = 0;
  std::vector<char> redo;  // per zone: its union must be (re)computed in this attempt
  for (std::size_t attempt = 0; attempt < 3; ++attempt) {
    t = Clock::now();
    FrustumReport fr;
    auto frusta = build_frusta(*part, attempts[attempt], &fr);
    if (!frusta) return frusta.status();
    rep.primitives = fr.frusta;
    rep.timings.primitives_ms += ms_since(t);
    progress("primitives", 1.0);

    t = Clock::now();
    if (attempt == 0) {
      redo.assign(frusta->size(), 1);
      solids.assign(frusta->size(), TriMesh{});
      todo_count = 0;
      for (const auto& f : *frusta) todo_count += f.solids.empty() ? 0u : 1u;
    }
    std::vector<int> todo;
    for (std::size_t z = 0; z < frusta->size(); ++z)
      if (!(*frusta)[z].solids.empty() && redo[z]) todo.push_back(static_cast<int>(z));
    std::vector<std::string> errors(todo.size()), notes(todo.size());
    // Progress per zone for long runs (the callback is called under a lock, from the worker
    // threads).
    std::atomic<std::size_t> zones_done{0};
    std::mutex progress_lock;
    parallel_over(todo.size(), threads, [&](std::size_t i) {
      struct Report {
        std::atomic<std::size_t>& done;
        std::mutex& lock;
        const std::function<void(const char*, double)>& progress;
        std::size_t total;
        ~Report() {
          const std::size_t d = ++done;
          const std::lock_guard<std::mutex> hold(lock);
          progress("union", static_cast<double>(d) / static_cast<double>(total));
        }
      } report_done{zones_done, progress_lock, progress, todo.size()};
      const std::size_t z = uz(todo[i]);
      // An intermediate union can be non-manifold (two frusta touching along an edge or at a
      // point) when the whole union is not: retry from each other starting frustum, then
      // reversed (fixed orders: deterministic).
      const auto& fz = (*frusta)[z].solids;
      auto u = union_snapped_solids(fz, part->planes);
      // Connectors and nudges both ask about the unions of the same pairs of frusta.
      PairUnionMemo pair_unions(part->planes);
      // Frusta meeting on a zone edge may bound an empty wedge there (frustum_connectors.h):
      // fill it, then try the other orders.
      if (!u && fz.size() > 1) {
        int connectors = 0;
        const std::vector<SnappedSolid> with = with_frustum_connectors(fz, part->planes, &connectors, &pair_unions);
        if (connectors > 0)
          if (auto c = union_snapped_solids(with, part->planes)) u = std::move(c);
      }
      // Frusta whose walls coincide to rounding along shared points (frustum_nudge.h): lean
      // the walls into each other.
      if (!u && fz.size() > 1) {
        int nudged = 0;
        const std::vector<SnappedSolid> leaned = with_overlap_nudges(fz, part->planes, &nudged, &pair_unions);
        if (nudged > 0)
          if (auto c = union_snapped_solids(leaned, part->planes)) u = std::move(c);
      }
      // Every single order met a non-manifold or corrupt intermediate: all frusta at once,
      // exactly (nef_union.h), where a third frustum may cover a pair's contact. It runs before
      // the other orders because it decides whether they can succeed at all: corefinement
      // refuses a union that is not a 2-manifold, and every order ends with the union of all
      // frusta, so when that union is not a 2-manifold (frusta touching without overlapping)
      // every order fails in its last step (stress seed 218: 14 such zones spent 11 of 28 s
      // in orders that could not succeed). Such a union is taken as it is only in the last
      // attempt (its contacts are then left to the pinch resolution of the stitched surface);
      // before that, the zone is rebuilt with other margins first. A 2-manifold union at once
      // is kept for when no order succeeds (orders first: their corefined result is the one
      // the earlier landings gave).
      if (!u && fz.size() > 1) {
        const bool last = attempt + 1 == std::size(attempts);
        bool manifold = true;
        auto c = union_snapped_solids_at_once(fz, part->planes, /*allow_non_manifold=*/last, &manifold);
        if (manifold)
          for (std::size_t rot = 1; !u && rot < fz.size() + 1; ++rot) {
            std::vector<SnappedSolid> order(fz);
            if (rot < fz.size())
              std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(rot), order.end());
            else
              std::reverse(order.begin(), order.end());
            u = union_snapped_solids(order, part->planes);
          }
        if (!u) {
          if (c && !manifold)
            notes[i] = "zone " + std::to_string(z) + ": frusta touch without overlapping; their exact union was kept with "
                       "the contact, for the stitch to separate or join";
          if (c) u = std::move(c);
          else u = Result<TriMesh>::error(u.message() + "; united at once: " + c.message());
        }
      }
      if (u) {
        solids[z] = std::move(*u);
        canonicalize(solids[z]);
        redo[z] = 0;
      } else {
        errors[i] = "zone " + std::to_string(z) + ": " + u.message();
      }
    });
    rep.timings.union_ms += ms_since(t);
    failure.clear();
    for (const auto& e : errors)
      if (!e.empty() && failure.empty()) failure = e;
    for (auto& note : notes)
      if (!note.empty()) rep.warnings.push_back(std::move(note));
    if (failure.empty()) {
      // Stitch, and check what the rounding of exact unions may have broken: a closed
      // manifold (checked again by the caller) without self-intersections (two nearly
      // coincident exact points rounded onto each other can fold a fan).
      t = Clock::now();
      mesh = stitch_polyhedral_zones(*part, solids, 1e-10 * box.diagonal());
      MeshTopology topo = mesh_topology(mesh);
      if (repair_stitched_surface(mesh, topo, box.diagonal(), rep.warnings)) topo = mesh_topology(mesh);
      if (!topo.closed || !topo.manifold() || !topo.consistently_oriented) {
        // Vertices that rounding left within the weld tolerance of each other inside a closed
        // part (the weld only merges along open seams) can leave a doubled face or an edge
        // with four faces (stress seed 37: two exact points 1.6e-17 apart): merged where
        // their fans cross, kept when the surface is then a closed, oriented manifold.
        TriMesh merged = mesh;
        if (repair_close_vertices(merged, 1e-10 * box.diagonal()) && merged.vertices.size() < mesh.vertices.size()) {
          const MeshTopology mt = mesh_topology(merged);
          if (mt.closed && mt.manifold() && mt.consistently_oriented) {
            rep.warnings.push_back("rounding had left " + std::to_string(mesh.vertices.size() - merged.vertices.size()) +
                                   " vertex(es) within 1e-10 of the diagonal of another one; they were merged");
            mesh = std::move(merged);
            topo = mt;
          }
        }
      }
      if (!topo.closed || !topo.manifold() || !topo.consistently_oriented) {
        failure = "the stitched surface is not a closed, oriented 2-manifold (" + topo.problem + ")";
      } else {
        auto crossing = self_intersecting_pairs(mesh);
        // Flat slivers that rounding turned over (sliver_repair.h): removed and the seam
        // zipped (vertices a rounding step apart at its ends merged), kept when the surface
        // is then closed, manifold and free of crossings.
        if (std::string w = zip_folded_slivers(mesh, crossing, 1e-10 * box.diagonal()); !w.empty()) {
          crossing.clear();
          rep.warnings.push_back(std::move(w));
        }
        if (!crossing.empty()) failure = "the stitched surface intersects itself";
      }
      rep.timings.stitch_ms += ms_since(t);
    }
    if (failure.empty()) {
      if (attempt > 0)
        rep.warnings.push_back("frusta rebuilt with other margins (attempt " + std::to_string(attempt + 1) + ")");
      break;
    }
    rep.warnings.push_back("attempt " + std::to_string(attempt + 1) + " failed: " + failure);
    if (std::none_of(redo.begin(), redo.end(), [](char c) { return c != 0; }))
      std::fill(redo.begin(), redo.end(), 1);  // every union held: the stitched surface failed
  }
  if (!failure.empty()) return Result<TriMesh>::error("reconstruction failed: " + failure);
  rep.zones_recomputed = static_cast<int>(todo_count);
  progress("union", 1.0);
  return mesh;
}

}  // namespace

void set_improve_hook(ImproveHook hook) { g_improve_hook = hook; }
ImproveHook improve_hook() { return g_improve_hook; }

ProgressiveReconstructor::ProgressiveReconstructor(ReconstructOptions options) : options_(std::move(options)) {}

void ProgressiveReconstructor::set_box(const Box3& box) {
  box_ = box;
  box_fixed_ = !box.empty();
  frame_ = AlignedFrame{};
  cache_.clear();
}

void ProgressiveReconstructor::clear() {
  sections_ = SectionSet{};
  mesh_ = TriMesh{};
  box_ = Box3{};
  box_fixed_ = false;
  frame_ = AlignedFrame{};
  cache_.clear();
  edits_.clear();
}

Result<TriMesh> ProgressiveReconstructor::add(const Plane& plane, const std::vector<Vec3>& curve,
                                              ReconstructReport* report) {
  SectionSet s = sections_;
  s.planes.push_back(plane);
  s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1, curve});
  return update(s, report);
}

Result<TriMesh> ProgressiveReconstructor::replace(int curve, const std::vector<Vec3>& points,
                                                  ReconstructReport* report) {
  if (curve < 0 || uz(curve) >= sections_.curves.size())
    return Result<TriMesh>::error("curve " + std::to_string(curve) + " does not exist");
  SectionSet s = sections_;
  s.curves[uz(curve)].points = points;
  return update(s, report);
}

Result<TriMesh> ProgressiveReconstructor::remove(int curve, ReconstructReport* report) {
  if (curve < 0 || uz(curve) >= sections_.curves.size())
    return Result<TriMesh>::error("curve " + std::to_string(curve) + " does not exist");
  SectionSet s = sections_;
  s.curves.erase(s.curves.begin() + curve);
  if (s.curves.empty()) {
    sections_ = s;
    mesh_ = TriMesh{};
    return mesh_;
  }
  return update(s, report);
}

// === Chapter 4: axis planes, cuboid zones of the grid, per-zone unions cached by primitives.
// `next_cache` receives every zone's entry (the caller commits it with the rest of the state).
Result<TriMesh> ProgressiveReconstructor::reconstruct_grid(const ValidatedSections& scaled, const Box3& box,
                                                           double tol, int scale_exponent,
                                                           const std::vector<TopologyEdit>& edits,
                                                           std::size_t strict_from, ReconstructReport& rep,
                                                           const std::function<void(const char*, double)>& progress,
                                                           Caches& next_cache) const {
  auto t = Clock::now();
  auto part = partition_zones(scaled, box, &cache_.clips, &next_cache.clips);
  if (!part) return part.status();
  count_zones(*part, rep);
  rep.timings.partition_ms = ms_since(t);
  progress("partition", 1.0);

  // === Primitives
  t = Clock::now();
  std::vector<ZonePrimitives> prims = build_cylinders(*part, {}, &cache_.cylinders, &next_cache.cylinders);
  // === Topology edits (6.4), in the scaled coordinates; they change a few zones' primitives,
  // so only those zones miss the cache below.
  for (std::size_t i = 0; i < edits.size(); ++i) {
    TopologyEdit e = edits[i];
    for (auto& p : e.stroke)
      for (int c = 0; c < 3; ++c) p[c] = std::ldexp(p[c], scale_exponent);
    if (Status st = apply_topology_edit(*part, prims, e); !st) {
      if (i >= strict_from) return st;
      rep.warnings.push_back("topology edit " + std::to_string(i) + " (" + topology_edit_name(e.kind) +
                             ") no longer applies and was skipped: " + st.message());
    }
  }
  for (const auto& z : prims) rep.primitives += static_cast<int>(z.solids.size());
  rep.timings.primitives_ms = ms_since(t);
  progress("primitives", 1.0);

  // === Per-zone unions: cached, the rest in parallel; merged in zone order.
  t = Clock::now();
  std::vector<TriMesh> solids(prims.size());
  std::vector<std::uint64_t> keys(prims.size(), 0);
  std::vector<int> todo;
  for (std::size_t z = 0; z < prims.size(); ++z) {
    if (prims[z].solids.empty()) continue;
    keys[z] = hash_meshes(prims[z].solids);
    bool hit = false;
    for (auto [it, end] = cache_.zones.equal_range(keys[z]); it != end; ++it)
      if (same_meshes(it->second.primitives, prims[z].solids)) {
        solids[z] = it->second.solid;
        hit = true;
        break;
      }
    if (!hit) todo.push_back(static_cast<int>(z));
  }
  std::vector<std::string> errors(todo.size());
  std::atomic<int> done{0}, filled_zones{0}, stacked_zones{0};
  parallel_over(todo.size(), options_.threads, [&](std::size_t i) {
    const std::size_t z = uz(todo[i]);
    // A zone its six whole-face prisms fill is its box (zone_box_union.h): no exact union.
    if (auto filled = filled_zone_union(part->zones[z], prims[z])) {
      solids[z] = std::move(*filled);
      canonicalize(solids[z]);
      ++filled_zones;
      ++done;
      return;
    }
    // Straight prisms stacked along one axis (parallel sections): a 2D arrangement instead of
    // the 3D corefinement (zone_stacked_union.h).
    if (auto stacked = stacked_zone_union(*part, part->zones[z], prims[z])) {
      solids[z] = std::move(*stacked);
      canonicalize(solids[z]);
      ++stacked_zones;
      ++done;
      return;
    }
    // An intermediate union can be non-manifold (two primitives touching along an edge)
    // even when the whole union is not; retry in other fixed orders (deterministic).
    std::vector<bool> verified(prims[z].solids.size(), false);
    if (prims[z].info.size() == verified.size())
      for (std::size_t p = 0; p < verified.size(); ++p) verified[p] = prims[z].info[p].verified;
    auto u = union_solids(prims[z].solids, verified);
    const std::size_t count = prims[z].solids.size();
    // At most two retries (one rotation, then reversed): a refusal must stay quick.
    for (std::size_t rot = 1; !u && rot <= 2 && count > 2; ++rot) {
      std::vector<TriMesh> order(prims[z].solids);
      std::vector<bool> order_verified(verified);
      if (rot == 1) {
        std::rotate(order.begin(), order.begin() + 1, order.end());
        std::rotate(order_verified.begin(), order_verified.begin() + 1, order_verified.end());
      } else {
        std::reverse(order.begin(), order.end());
        std::reverse(order_verified.begin(), order_verified.end());
      }
      u = union_solids(order, order_verified);
    }
    if (u) {
      solids[z] = std::move(*u);
      canonicalize(solids[z]);
    }
    else
      errors[i] = "zone " + std::to_string(z) + ": " + u.message();
    ++done;
  });
  for (const auto& e : errors)
    if (!e.empty()) return Result<TriMesh>::error("reconstruction failed: " + e);
  rep.zones_recomputed = static_cast<int>(todo.size());
  rep.zones_filled = filled_zones.load();
  rep.zones_stacked = stacked_zones.load();
  rep.timings.union_ms = ms_since(t);
  progress("union", 1.0);

  // === Stitch
  t = Clock::now();
  TriMesh mesh = stitch_zones(*part, solids, tol);
  // (The close-vertex repair of the stitched mesh runs in update_with, next to its topology.)
  for (std::size_t z = 0; z < prims.size(); ++z)
    if (!prims[z].solids.empty()) next_cache.zones.emplace(keys[z], CacheEntry{prims[z].solids, solids[z]});
  rep.timings.stitch_ms += ms_since(t);
  return mesh;
}

Result<TriMesh> ProgressiveReconstructor::update(const SectionSet& input, ReconstructReport* report) {
  return update_with(input, edits_, edits_.size(), report);
}

Result<TriMesh> ProgressiveReconstructor::join(const std::vector<Vec3>& stroke, ReconstructReport* report) {
  std::vector<TopologyEdit> edits = edits_;
  edits.push_back({TopologyEditKind::kJoin, stroke});
  return update_with(sections_, edits, edits.size() - 1, report);
}

Result<TriMesh> ProgressiveReconstructor::split(const std::vector<Vec3>& stroke, ReconstructReport* report) {
  std::vector<TopologyEdit> edits = edits_;
  edits.push_back({TopologyEditKind::kSplit, stroke});
  return update_with(sections_, edits, edits.size() - 1, report);
}

Result<TriMesh> ProgressiveReconstructor::undo_edit(ReconstructReport* report) {
  if (edits_.empty()) return Result<TriMesh>::error("there is no topology edit to undo");
  std::vector<TopologyEdit> edits(edits_.begin(), edits_.end() - 1);
  return update_with(sections_, edits, edits.size(), report);
}

Result<TriMesh> ProgressiveReconstructor::update(const SectionSet& sections, const std::vector<TopologyEdit>& edits,
                                                 ReconstructReport* report) {
  return update_with(sections, edits, 0, report);
}

Result<TriMesh> ProgressiveReconstructor::update_with(const SectionSet& input, const std::vector<TopologyEdit>& edits,
                                                      std::size_t strict_from, ReconstructReport* report) {
  bool used_frame = false;
  auto r = update_in_frame(input, edits, strict_from, report, options_.rotate_to_planes, &used_frame);
  if (r || !used_frame) return r;
  // The grid in the planes' frame failed where the world frame may not (rounding of the rotated
  // points; never seen on the data sets): chapter 6 decides, and its verdict stands.
  return update_in_frame(input, edits, strict_from, report, false, &used_frame);
}

Result<TriMesh> ProgressiveReconstructor::update_in_frame(const SectionSet& input,
                                                          const std::vector<TopologyEdit>& input_edits,
                                                          std::size_t strict_from, ReconstructReport* report,
                                                          bool allow_frame, bool* used_frame) {
  const auto t_total = Clock::now();
  ReconstructReport rep;
  auto progress = [&](const char* stage, double f) {
    if (options_.progress) options_.progress(stage, f);
  };

  // === Validate (messages name the caller's curve indices), then canonicalise.
  auto t = Clock::now();
  if (Status size = check_reconstruction_size(input); !size) return size;
  auto checked = validate_sections(input);
  if (!checked) return checked.status();
  SectionSet canonical = canonical_sections(checked->sections);
  // === Planes in at most three orthogonal directions other than the axes (a tilted stack):
  // the grid of chapter 4 in their frame (aligned_frame.h). The frame's points map back to the
  // caller's exactly at the end, the rest of the mesh by the inverse rotation.
  std::optional<AlignedFrame> frame = allow_frame ? aligned_frame(canonical) : std::nullopt;
  std::unordered_map<PointKey, Vec3, PointKeyHash> world_of;  // frame point -> input point
  std::vector<TopologyEdit> edits = input_edits;
  if (frame) {
    *used_frame = true;
    SectionSet framed = to_aligned_frame(canonical, *frame);
    for (std::size_t c = 0; c < framed.curves.size(); ++c)
      for (std::size_t j = 0; j < framed.curves[c].points.size(); ++j) {
        const Vec3& w = canonical.curves[c].points[j];
        auto [it, fresh] = world_of.emplace(PointKey(framed.curves[c].points[j]), w);
        // Two input points on one frame point (within rounding of each other): the smaller, so
        // that the choice does not depend on the order of the input.
        if (!fresh && std::make_tuple(w.x(), w.y(), w.z()) < std::make_tuple(it->second.x(), it->second.y(), it->second.z()))
          it->second = w;
      }
    canonical = canonical_sections(framed);
    for (auto& e : edits)
      for (auto& p : e.stroke) p = frame->to_frame(p);
  }
  // Rule 4: crossing points of curves on perpendicular planes closer than 2% of the diagonal
  // become one shared vertex (the stitching of zones needs them to agree exactly).
  rep.warnings = checked->warnings;
  sew_crossings(canonical, kSewTolerance * checked->diagonal, &rep.warnings);
  auto valid = validate_sections(canonical);
  if (!valid) return Result<TriMesh>::error("after sewing crossing points (rule 4): " + valid.message());
  const SectionSet& s = valid->sections;
  // Planes of any orientation go through the convex-zone pipeline of chapter 6; axis planes
  // only through the grid of chapter 4 (faster, and cached per zone).
  bool orthogonal = true;
  {
    std::vector<char> used(s.planes.size(), 0);
    for (const auto& c : s.curves) used[uz(c.plane)] = 1;
    for (std::size_t i = 0; i < s.planes.size(); ++i)
      if (used[i] && s.planes[i].axis() < 0) orthogonal = false;
  }
  rep.timings.validate_ms = ms_since(t);
  progress("validate", 1.0);

  // === Box (fixed while sketching unless a point leaves it) and partition.
  t = Clock::now();
  const std::vector<Vec3> points = s.all_points();
  Box3 box = box_;
  bool inside = box_fixed_;
  if (inside) {
    for (const auto& p : points)
      if ((p.array() <= box.min.array()).any() || (p.array() >= box.max.array()).any()) {
        inside = false;
        break;
      }
  }
  // The kept box is in the previous update's frame; another frame sets it anew.
  const AlignedFrame this_frame = frame ? *frame : AlignedFrame{};
  if (inside && this_frame.rotation != frame_.rotation) inside = false;
  if (!inside) box = default_reconstruction_box(points);
  // The box as kept, in the aligned frame; below, the grid path turns it to its canonical axes.
  const Box3 frame_box = box;
  const SignedAxes axes = orthogonal && options_.canonical_axes ? canonical_axes(box) : SignedAxes{};
  std::optional<ValidatedSections> turned;
  if (!axes.identity()) {
    auto v = validate_sections(canonical_sections(to_frame(s, axes)));
    if (!v) return Result<TriMesh>::error("after turning to the canonical axes: " + v.message());
    turned = std::move(*v);
    box = axes.to_frame(box);
    for (auto& e : edits)
      for (auto& p : e.stroke) p = axes.to_frame(p);
  }
  const ValidatedSections& vsec = turned ? *turned : *valid;
  // === Scale normalisation. Everything below runs on the input scaled by 2^k so that the box
  // diagonal lies in [1, 2): CGAL's static filters give up far from unit scale (coordinates of
  // 1e-30 sent every predicate to exact arithmetic: minutes instead of milliseconds), and a few
  // guards downstream are absolute. Multiplying by a power of two is exact, so the curve points
  // come back bit-identical and k is a function of the box alone (the cache stays valid while
  // the box is kept).
  const int k = scale_exponent(box);
  const ValidatedSections scaled = scaled_sections(vsec, k);
  box = scaled_box(box, k);
  const double diag = box.diagonal();
  const double tol = 1e-10 * diag;
  Caches cache;
  TriMesh mesh;
  if (!orthogonal && strict_from < edits.size())
    return Result<TriMesh>::error(std::string(topology_edit_name(edits[strict_from].kind)) +
                                  ": topology edits apply to sections on planes of at most three orthogonal directions only");
  if (!orthogonal && !edits.empty())
    rep.warnings.push_back("topology edits were skipped: they apply to sections on planes of at most three orthogonal directions only");
  if (!orthogonal) {
    auto built = reconstruct_polyhedral(scaled, box, rep, progress, options_.threads);
    t = Clock::now();
    if (!built) return built.status();
    mesh = std::move(*built);
  } else {
    auto built = reconstruct_grid(scaled, box, tol, k, edits, strict_from, rep, progress, cache);
    t = Clock::now();
    if (!built) return built.status();
    mesh = std::move(*built);
  }
  // === Checks: topology and curve flags; on the grid path, in parallel with the close-vertex
  // repair. Rounding can leave two distinct vertices almost on top of each other; their fans
  // are where a result made of valid zone solids can cross itself. Merged when that removes
  // the crossing, refused otherwise. A merge always removes a vertex, so an unchanged vertex
  // count means nothing was merged and the checks of the unrepaired mesh stand (the common
  // case); otherwise they are redone on the repaired mesh.
  MeshTopology topo;
  auto check = [&](const TriMesh& m) {
    topo = mesh_topology(m);
    curve_flags(m, scaled.sections, 1e-9 * diag, rep.curve_vertex, rep.curve_edges);
  };
  if (orthogonal) {
    TriMesh repaired = mesh;
    bool clean = true;
    parallel_over(2, options_.threads, [&](std::size_t i) {
      if (i == 0)
        clean = repair_close_vertices(repaired, 1e-9 * diag);
      else
        check(mesh);
    });
    if (!clean) {
      // What merging leaves crossing: flat slivers folded by rounding, as on the polyhedral path
      // (CGAL's spool sliced 2x2x3: 176 crossing pairs, 277 sliver faces of 1e-10 of the
      // diagonal or less; closed and free of crossings without them).
      std::string w = zip_folded_slivers(mesh, self_intersecting_pairs(mesh), tol);
      if (w.empty())
        return Result<TriMesh>::error(
            "reconstruction failed: the stitched surface intersects itself where two vertices almost coincide");
      rep.warnings.push_back(std::move(w));
      repaired = mesh;
      check(mesh);
    }
    if (repaired.vertices.size() != mesh.vertices.size()) {
      mesh = std::move(repaired);
      check(mesh);
    }
  } else {
    check(mesh);
  }
  // (The polyhedral path repaired its surface before its own self-intersection test.)
  if (orthogonal && repair_stitched_surface(mesh, topo, diag, rep.warnings)) check(mesh);
  if (!topo.closed || !topo.manifold())
    return Result<TriMesh>::error("reconstruction failed: the stitched surface is not a closed 2-manifold (" +
                                  topo.problem + ")");
  if (!(topo.signed_volume > 0.0))
    return Result<TriMesh>::error("reconstruction failed: the stitched surface is inside out");
  if (double cavity_volume = 0.0; topo.components > 1) {
    if (const int filled = fill_curveless_cavities(mesh, rep.curve_vertex, cavity_volume); filled > 0) {
      char share[32];
      std::snprintf(share, sizeof share, "%.2g", 100.0 * cavity_volume / topo.signed_volume);
      rep.warnings.push_back(std::to_string(filled) + " empty pocket(s) enclosed between primitives, with no input curve on "
                             "them (" + share + "% of the volume), were filled");
      check(mesh);
    }
  }
  rep.components = topo.components;
  if (topo.components > 1)
    rep.warnings.push_back("result has " + std::to_string(topo.components) +
                           " components; a new section near the separate parts may join them");
  rep.timings.stitch_ms += ms_since(t);
  progress("stitch", 1.0);

  // === Improvement (4.5.1), through the hook.
  if (options_.improve) {
    t = Clock::now();
    if (g_improve_hook) {
      ImproveOptions io;
      io.iterations = options_.improve_iterations;
      // The coarse-to-fine ramp of alpha takes 8 of the thesis's 10 rounds; other counts keep
      // that share, so fewer rounds still reach the full density (docs/mesh-improvement.md).
      io.ramp_rounds = (8 * io.iterations + 5) / 10;
      ImproveReport irep;
      auto improved = g_improve_hook(mesh, rep.curve_vertex, rep.curve_edges, io, &irep);
      rep.timings.improve_refine_ms = irep.refine_ms;
      rep.timings.improve_smooth_ms = irep.smooth_ms;
      rep.timings.improve_check_ms = irep.check_ms;
      if (improved && irep.kept_input) {
        char figures[160];
        std::snprintf(figures, sizeof figures,
                      "mean smallest angle %.1f -> %.1f deg, RMS dihedral %.1f -> %.1f deg",
                      irep.quality_in.mean_min_angle_deg, irep.quality_out.mean_min_angle_deg,
                      irep.quality_in.rms_dihedral_deg, irep.quality_out.rms_dihedral_deg);
        const std::string when = irep.gave_up_after_round >= 0
                                     ? ", given up after round " + std::to_string(irep.gave_up_after_round + 1) +
                                           " of " + std::to_string(io.iterations)
                                     : std::string();
        rep.warnings.push_back(std::string("mesh improvement made the surface worse (") + figures + when +
                               "); the unimproved surface was kept");
      } else if (improved) {
        mesh = std::move(*improved);
        rep.improved = true;
        if (mesh.vertices.size() != rep.curve_vertex.size()) {
          rep.curve_vertex.clear();
          rep.curve_edges.clear();
          curve_flags(mesh, scaled.sections, 1e-9 * diag, rep.curve_vertex, rep.curve_edges);
        }
      } else {
        rep.warnings.push_back("mesh improvement failed, initial mesh kept: " + improved.message());
      }
    } else {
      rep.warnings.push_back("mesh improvement unavailable");
    }
    rep.timings.improve_ms = ms_since(t);
    progress("improve", 1.0);
  }

  // Back to the caller's units: exact, and curve vertices are the input points themselves.
  for (auto& v : mesh.vertices)
    for (int c = 0; c < 3; ++c) v[c] = std::ldexp(v[c], -k);
  // Back from the canonical axes: exact.
  if (!axes.identity())
    for (auto& v : mesh.vertices) v = axes.to_world(v);
  if (axes.mirrors())
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);
  // Back to the world frame: each input point exactly, every other vertex rotated. Rotating
  // rounds (a few ulps), and two faces closer than that could cross: the result is checked,
  // and the caller falls back to chapter 6 in the world frame if they do.
  if (frame) {
    t = Clock::now();
    for (auto& v : mesh.vertices) {
      const auto it = world_of.find(PointKey(v));
      v = it != world_of.end() ? it->second : frame->to_world(v);
    }
    if (const auto pairs = self_intersecting_pairs(mesh); !pairs.empty())
      return Result<TriMesh>::error("reconstruction failed: rotating the result back to the world frame made faces " +
                                    std::to_string(pairs[0][0]) + " and " + std::to_string(pairs[0][1]) + " intersect");
    rep.rotated_frame = true;
    rep.timings.stitch_ms += ms_since(t);
  }

  // === Commit state
  cache_ = std::move(cache);
  box_ = frame_box;
  box_fixed_ = true;
  frame_ = this_frame;
  sections_ = input;
  edits_ = input_edits;
  mesh_ = mesh;
  rep.timings.total_ms = ms_since(t_total);
  if (report) *report = std::move(rep);
  return mesh;
}

// === One-shot
Result<TriMesh> reconstruct(const SectionSet& sections, const ReconstructOptions& options, ReconstructReport* report) {
  ProgressiveReconstructor r(options);
  return r.update(sections, report);
}

}  // namespace ps
