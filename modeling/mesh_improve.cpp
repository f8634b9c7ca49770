#include "modeling/mesh_improve.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "modeling/content_cache.h"
#include "modeling/face_intersections.h"
#include "modeling/halfedge_mesh.h"
#include "modeling/mesh_refine.h"
#include "modeling/mesh_smooth.h"
#include "modeling/smoothing_clearance.h"

namespace ps {
namespace {

// A refinement redone after a crossing locks flips in the box of each crossing pair grown by the
// pair's size, but by at most this many length floors (RefineOptions::min_length), when there
// is a floor. 1 and 2 were measured (docs/mesh-improvement.md, "Smaller flip locks"); 2 was as
// good or better on both figures on every input that changed.
constexpr double kLockGrowthFloors = 2.0;

// Why our own refinement and smoothing rather than CGAL's PMP::isotropic_remeshing and
// PMP::tangential_relaxation / angle_and_area_smoothing: the thesis's target length is not one
// number but the length attribute spread from the curves (sigma); isotropic remeshing projects
// onto the input, so the union's creases stay (measured on the 3k-triangle staircase: max
// dihedral still 90 degrees, and 7x the CPU time of this whole function, see
// docs/mesh-improvement.md); it collapses edges, which renumbers vertices, and it was seen to
// create self-intersections on these union meshes; and neither PMP smoother moves vertices along
// the normal, which is what removes the creases. CGAL still provides the exact predicates and the
// box intersection of the self-intersection checks (face_intersections.h).

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

using Clock = std::chrono::steady_clock;

// A face as its three points, sorted (whether two triangles cross does not depend on their
// orientation). Two faces with equal keys are the same triangle.
using FaceKey = std::array<Vec3, 3>;
bool point_less(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}
FaceKey face_key(const HalfedgeMesh& m, int f) {
  FaceKey k = {m.position(m.faces[idx(f)][0]), m.position(m.faces[idx(f)][1]), m.position(m.faces[idx(f)][2])};
  std::sort(k.begin(), k.end(), point_less);
  return k;
}
// A set of face keys: open addressing with linear probing over indices into one array of keys.
// It replaced std::unordered_set, whose node allocations and byte-wise hashing of 72-byte keys
// were about 3% of stress seed 737's CPU time (perf).
class FaceKeySet {
 public:
  explicit FaceKeySet(std::size_t capacity) {
    while ((std::size_t{1} << bits_) < 2 * capacity + 2) ++bits_;
    slots_.assign(std::size_t{1} << bits_, 0);
    keys_.reserve(capacity);
  }
  void insert(const FaceKey& k) {
    std::size_t s = home(k);
    for (; slots_[s] != 0; s = (s + 1) & mask()) {
      if (keys_[slots_[s] - 1] == k) return;
    }
    keys_.push_back(k);
    slots_[s] = static_cast<std::uint32_t>(keys_.size());
    if (2 * keys_.size() + 2 > slots_.size()) grow();
  }
  bool contains(const FaceKey& k) const {
    for (std::size_t s = home(k); slots_[s] != 0; s = (s + 1) & mask())
      if (keys_[slots_[s] - 1] == k) return true;
    return false;
  }

 private:
  std::size_t mask() const { return slots_.size() - 1; }
  std::size_t home(const FaceKey& k) const {
    ContentHash h;
    for (const Vec3& p : k)
      for (int c = 0; c < 3; ++c) {
        const double x = p[c] == 0.0 ? 0.0 : p[c];  // -0 and +0 alike, as == has them
        h.word(std::bit_cast<std::uint64_t>(x));
      }
    return static_cast<std::size_t>((h.h * 0x9E3779B97F4A7C15ULL) >> (64 - bits_));
  }
  void grow() {
    ++bits_;
    slots_.assign(std::size_t{1} << bits_, 0);
    for (std::size_t i = 0; i < keys_.size(); ++i) {
      std::size_t s = home(keys_[i]);
      while (slots_[s] != 0) s = (s + 1) & mask();
      slots_[s] = static_cast<std::uint32_t>(i + 1);
    }
  }
  int bits_ = 4;
  std::vector<std::uint32_t> slots_;  // key index + 1; 0: empty
  std::vector<FaceKey> keys_;
};

// The kept-input test (improve_mesh) and the early give-up (ImproveOptions) ask the same: a
// smaller mean smallest angle and a larger RMS dihedral than the input's.
bool worse_on_both(const MeshQuality& q, const MeshQuality& in) {
  return q.mean_min_angle_deg < in.mean_min_angle_deg && q.rms_dihedral_deg > in.rms_dihedral_deg;
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

namespace {
Result<TriMesh> improve_unit_scale(const TriMesh& mesh, const std::vector<bool>& fixed_vertex,
                                   const std::vector<std::array<int, 2>>& fixed_edges,
                                   const ImproveOptions& options, ImproveReport* report);
}  // namespace

// === Scale normalisation
// The exact predicates' static filters give up on coordinates far from 1 (a model of size 1e-30
// sent every test to exact arithmetic: minutes instead of milliseconds), and some guards are
// absolute. The mesh is therefore scaled by a power of two so that its diagonal lies in [1, 2):
// multiplying by 2^k is exact in floating point, so fixed vertices come back bit-identical.
Result<TriMesh> improve_mesh(const TriMesh& mesh, const std::vector<bool>& fixed_vertex,
                             const std::vector<std::array<int, 2>>& fixed_edges,
                             const ImproveOptions& options, ImproveReport* report) {
  const auto t_start = Clock::now();
  ImproveReport rep;
  auto out = [&]() -> Result<TriMesh> {
    const double diag = bounding_box(mesh.vertices).diagonal();
    if (!std::isfinite(diag) || diag <= 0 || (diag >= 1 && diag < 2))
      return improve_unit_scale(mesh, fixed_vertex, fixed_edges, options, &rep);
    const int k = -std::ilogb(diag);
    TriMesh scaled = mesh;
    for (auto& v : scaled.vertices)
      for (int c = 0; c < 3; ++c) v[c] = std::ldexp(v[c], k);
    auto improved = improve_unit_scale(scaled, fixed_vertex, fixed_edges, options, &rep);
    if (!improved) return improved;
    for (auto& v : improved->vertices)
      for (int c = 0; c < 3; ++c) v[c] = std::ldexp(v[c], -k);
    // Fixed vertices never move; restoring them also covers coordinates so far below the
    // model's size that scaling them made subnormal numbers and lost bits.
    for (std::size_t v = 0; v < mesh.vertices.size() && v < improved->vertices.size(); ++v)
      if (fixed_vertex[v]) improved->vertices[v] = mesh.vertices[v];
    return improved;
  }();
  if (!out) return out;
  // === Worse on both figures: keep the input (the caller's own, not a rescaled copy). The RMS
  // dihedral alone would not do: rounding a 90-degree crease over several faces raises it before
  // refinement brings it down, and a union is mostly flat pieces (Skull-20 ends higher than it
  // starts, and is much better triangulated); nor the angle alone (a smoothed surface can need
  // thinner triangles). Both figures are scale-invariant.
  rep.quality_out = mesh_quality(*out);  // (rep.quality_in: the input's, from improve_unit_scale)
  if (worse_on_both(rep.quality_out, rep.quality_in)) {
    rep.kept_input = true;
    *out = mesh;
  }
  rep.ms = ms_since(t_start);
  if (report) *report = rep;
  return out;
}

namespace {
Result<TriMesh> improve_unit_scale(const TriMesh& mesh, const std::vector<bool>& fixed_vertex,
                                   const std::vector<std::array<int, 2>>& fixed_edges,
                                   const ImproveOptions& options, ImproveReport* report) {
  ImproveReport rep;

  // === Validate the input
  const int nv = static_cast<int>(mesh.vertices.size());
  if (fixed_vertex.size() != mesh.vertices.size())
    return Result<TriMesh>::error("fixed_vertex has " + std::to_string(fixed_vertex.size()) +
                                  " flags for " + std::to_string(nv) + " vertices");
  if (options.iterations < 0 || options.smoothing_steps < 0 || options.ramp_rounds < 0)
    return Result<TriMesh>::error("iterations, smoothing_steps and ramp_rounds must not be negative");
  if (!(options.max_flip_normal_angle_deg >= 0 && options.max_flip_normal_angle_deg <= 180))
    return Result<TriMesh>::error("max_flip_normal_angle_deg must be in [0, 180]");
  if (!(options.alpha > 0) || !(options.tangential_step >= 0 && options.tangential_step <= 1) ||
      !(options.normal_step >= 0 && options.normal_step <= 1))
    return Result<TriMesh>::error("alpha must be positive; tangential_step and normal_step in [0, 1]");
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      return Result<TriMesh>::error("vertex " + std::to_string(v) + " has a non-finite coordinate");
  auto built = HalfedgeMesh::build(mesh);
  if (!built) return Result<TriMesh>::error("improve_mesh: " + built.message());
  HalfedgeMesh m = std::move(built).value();
  std::vector<std::uint8_t> fixed(idx(nv), 0);
  for (int v = 0; v < nv; ++v) fixed[idx(v)] = fixed_vertex[idx(v)] ? 1 : 0;
  for (std::size_t e = 0; e < fixed_edges.size(); ++e) {
    const auto [a, b] = fixed_edges[e];
    if (a < 0 || b < 0 || a >= nv || b >= nv || !m.constrain_edge(a, b))
      return Result<TriMesh>::error("fixed edge " + std::to_string(e) + " (" + std::to_string(a) +
                                    ", " + std::to_string(b) + ") is not an edge of the mesh");
    fixed[idx(a)] = fixed[idx(b)] = 1;
  }
  rep.faces_in = m.num_faces();
  // The input's figures, for the early give-up below and for improve_mesh's kept-input test
  // (computed once, here on the scaled copy: scaling by a power of two leaves every figure's bits
  // as they are, short of subnormal coordinates).
  rep.quality_in = mesh_quality(mesh);
  const MeshQuality& quality_in = rep.quality_in;

  RefineOptions ropt;
  ropt.alpha = options.alpha;
  if (options.min_length_fraction > 0) {
    Box3 curve_box, all_box;
    for (int v = 0; v < nv; ++v) {
      all_box.extend(m.position(v));
      if (fixed[idx(v)]) curve_box.extend(m.position(v));
    }
    ropt.min_length = options.min_length_fraction * (curve_box.empty() ? all_box : curve_box).diagonal();
  }
  ropt.max_faces = options.max_faces;
  // The valence limit of each input vertex: twice its valence in the input (RefineOptions).
  std::vector<int> base_valence(idx(nv));
  for (int v = 0; v < nv; ++v) base_valence[idx(v)] = m.valence(v);
  ropt.base_valence = &base_valence;
  ropt.max_flip_normal_angle_deg = options.max_flip_normal_angle_deg;
  SmoothOptions sopt;
  sopt.flow = options.curvature_evening ? NormalFlow::kCurvatureEvening : NormalFlow::kMeanCurvature;
  sopt.normal_step = options.normal_step;
  sopt.tangential_step = options.tangential_step;
  // The fourth-order flow is only stable below 1/2 (mesh_smooth.h).
  if (options.curvature_evening) sopt.normal_step = std::min(sopt.normal_step, 0.45);

  using EL = ImproveOptions::EveningLimit;
  sopt.limit_evening = options.curvature_evening && options.evening_limit == EL::kAlways;
  bool thin_parts = false;  // set by a smoothing check that found many crossings (below)
  for (int it = 0; it < options.iterations; ++it) {
    // Coarse to fine: with alpha ramping up over the first rounds, early rounds split only the
    // largest faces, and their smoothing steps reach further (docs/mesh-improvement.md).
    ropt.alpha = options.alpha;
    if (options.ramp_rounds > 0)
      ropt.alpha *= std::min(1.0, static_cast<double>(it + 1) / options.ramp_rounds);
    const HalfedgeMesh start = m;
    const std::vector<std::uint8_t> fixed_start = fixed;

    // === Refinement (Liepa), checked at once. Flips are what mostly makes faces cross; splits
    // at centroids keep each face's plane only up to the centroid's rounding. So the faces that
    // came from flips or splits are tested against the mesh before any smoothing, and after a
    // crossing the refinement is redone from the round's start with flips locked near it; if that
    // crosses too, the round goes on unrefined.
    // (Until 2026-12-05 the one check came after smoothing, and a round with a bad flip was
    // refined, smoothed and checked twice: 7 of 10 rounds on hand_ok. Until 2026-12-07 only the
    // flipped faces were tested, on the grounds that a crossing made by a rounded centroid would
    // show in the smoothing check below; it does only where smoothing moved a corner, and stress
    // seed 418 came out with 123 crossing pairs of split needles that no move had touched.)
    bool refine = true;
    for (;;) {
      FlipLock lock;
      RefineStats rs;
      // Faces made by the previous attempt that cross no face of it (below).
      std::optional<FaceKeySet> clean_before;
      for (int attempt = 0; refine; ++attempt) {
        auto t0 = Clock::now();
        std::vector<std::uint8_t> changed;  // faces made by flips or splits
        rs = refine_mesh(m, fixed, lock, ropt, &changed);
        rep.refine_ms += ms_since(t0);
        if (!options.check_self_intersections) break;
        t0 = Clock::now();
        // The retry (attempt 1) mostly remakes the faces of attempt 0, which were all tested then:
        // a new face was tested against every face of that mesh, an untouched one is a face of
        // the round's start, clean too. A pair of faces that both occur in attempt 0 (as the same
        // three points) and crossed nothing there cannot cross now, as whether two triangles
        // cross depends on their points alone. So only the faces that attempt 0 did not make
        // clean (clean_before) are tested. (Stress seed 737: the retry's check was 60% of the
        // refinement checks, about 2 s, on faces mostly the same as the first attempt's.)
        std::vector<int> new_faces;
        for (std::size_t f = 0; f < changed.size(); ++f)
          if (changed[f] && (attempt == 0 || !clean_before->contains(face_key(m, static_cast<int>(f)))))
            new_faces.push_back(static_cast<int>(f));
        const auto pairs = intersecting_face_pairs(m.positions, m.faces, new_faces);
        rep.check_ms += ms_since(t0);
        if (pairs.empty()) break;
        if (attempt == 0) {
          t0 = Clock::now();
          std::vector<std::uint8_t> crossing(idx(m.num_faces()), 0);
          for (const auto& pr : pairs) crossing[idx(pr[0])] = crossing[idx(pr[1])] = 1;
          // Only the faces it made: a face of the round's start is clean too, but the retry
          // rarely makes one again (a flip and its reverse), and testing it then costs less
          // than keeping every face here.
          clean_before.emplace(new_faces.size());
          for (int f : new_faces)
            if (!crossing[idx(f)]) clean_before->insert(face_key(m, f));
          rep.check_ms += ms_since(t0);
        }
        ++rep.refinement_rollbacks;
        if (attempt == 1) {
          // Crossings again with their regions locked: this round is not refined. (Until
          // 2026-12-06 it was refined with every flip locked; centroid splits with no flip to
          // follow them only make needles: stress seed 37 came out with 59% of its faces under 2
          // degrees.)
          m = start;
          fixed = fixed_start;
          rs = RefineStats{};
          refine = false;
          break;
        }
        for (const auto& pr : pairs) {
          Box3 region;
          for (int f : pr)
            for (int v : m.faces[idx(f)]) region.extend(m.position(v));
          // Grown by the pair's own size, at most twice the length floor. A crossing pair of long
          // needles (the stitched walls of dense orthogonal inputs) otherwise locked a box several
          // times their length: no flips over much of the surface, so the centroid splits there
          // multiplied needles (stress seed 783: 400k faces, the cap, in the first round instead
          // of 272k; mean smallest angle 11.5 deg instead of 37.2; 33 s instead of 8).
          double g = region.diagonal();
          if (ropt.min_length > 0) g = std::min(g, kLockGrowthFloors * ropt.min_length);
          const Vec3 grow = Vec3::Constant(g);
          region.min -= grow;
          region.max += grow;
          lock.regions.push_back(region);
        }
        m = start;
        fixed = fixed_start;
      }
      const std::vector<Vec3> refined = m.positions;

      // === Smoothing (Eq. 4.3); moves that turn a face over are undone at once
      auto t0 = Clock::now();
      if (options.smoothing_steps > 0) {
        for (;;) {
          if (sopt.limit_evening && rep.evening_limited_from < 0) rep.evening_limited_from = it;
          Smoother smoother(m, fixed, sopt);
          long long folds = 0;
          for (int s = 0; s < options.smoothing_steps; ++s) folds += smoother.step(m);
          rep.smoothing_rollbacks += static_cast<int>(folds);
          // Rough surface (EveningLimit::kAuto): many moves folded faces. This round's
          // smoothing is done again with the evening limited, and so is every later round's
          // (a crinkle left by one unlimited round stays: stress seed 217, limited from the round
          // after, kept 47 degrees RMS dihedral instead of 27).
          if (sopt.limit_evening || !options.curvature_evening || options.evening_limit != EL::kAuto ||
              20 * folds <= static_cast<long long>(options.smoothing_steps) * m.num_vertices())
            break;
          sopt.limit_evening = true;
          m.positions = refined;
        }
      }
      // Once thin parts have shown (kAuto, below) or always (kAlways), moves towards a facing
      // sheet nearer than the move are shortened (smoothing_clearance.h); a shortened move can
      // leave a face turned over between its corners' moves.
      using CL = ImproveOptions::ClearanceLimit;
      const CL cl = options.clearance_limit;
      bool limited_round = options.smoothing_steps > 0 && (cl == CL::kAlways || (cl == CL::kAuto && thin_parts));
      auto limit_by_clearance = [&] {
        const int limited = limit_moves_by_clearance(m.positions, refined, m.faces);
        rep.clearance_limits += limited;
        if (limited > 0) rep.smoothing_rollbacks += revert_folded_faces(m, refined);
      };
      if (limited_round) limit_by_clearance();
      rep.smooth_ms += ms_since(t0);
      if (!options.check_self_intersections) {
        rep.splits += rs.splits;
        rep.flips += rs.flips;
        break;
      }

      // === Self-intersection check of the smoothing: faces with a moved corner are tested, and
      // the moves of the corners of every crossing pair are undone until the mesh is clean.
      t0 = Clock::now();
      const int nf = m.num_faces();
      std::vector<std::uint8_t> moved(idx(m.num_vertices()), 0);
      std::vector<int> query;
      auto query_moved = [&] {
        for (int v = 0; v < m.num_vertices(); ++v) moved[idx(v)] = m.positions[idx(v)] != refined[idx(v)];
        query.clear();
        for (int f = 0; f < nf; ++f) {
          const Face& fc = m.faces[idx(f)];
          if (moved[idx(fc[0])] || moved[idx(fc[1])] || moved[idx(fc[2])]) query.push_back(f);
        }
      };
      // The first pass queries every face with a moved corner. Each later pass queries only the
      // faces whose corners were just put back (plus the faces of pairs not yet resolved): any
      // other face kept its position since the previous pass, which tested it against the whole
      // mesh, so a new intersection must involve a face that moved in between. This keeps the
      // rollback passes local instead of rescanning the whole mesh each time.
      query_moved();
      std::vector<std::uint8_t> reset(idx(m.num_vertices()), 0);
      std::vector<std::array<int, 2>> unresolved;
      bool first_pass = true;
      for (;;) {
        const auto pairs = intersecting_face_pairs(m.positions, m.faces, query);
        // Thin parts (kAuto): smoothing pushed more than 1 in 12 of the moved faces through
        // another face. Measured in the first check of each round without the limit: at most
        // 1 in 14 on the CSL sets where the limit does not pay (Skull-20 and armadillo, thin in
        // places: there it made the mesh worse), 1 in 9 to 4 in 5 on eight_20's sheets and up to
        // 1 in 6 on Abdomen (docs/mesh-improvement.md). The moves are then limited by clearance,
        // in this round and every later one, and the check starts again. The limit costs 20-70
        // ms a round on 50-130k faces, so it does not run before it is needed.
        if (first_pass && !limited_round && cl == CL::kAuto && 12 * pairs.size() > query.size()) {
          thin_parts = limited_round = true;
          limit_by_clearance();
          query_moved();
          continue;
        }
        unresolved.clear();
        if (pairs.empty()) break;
        int undone = 0;
        first_pass = false;
        for (const auto& pr : pairs) {
          bool any_moved = false;
          for (int f : pr)
            for (int v : m.faces[idx(f)])
              if (moved[idx(v)]) {
                m.positions[idx(v)] = refined[idx(v)];
                moved[idx(v)] = 0;
                reset[idx(v)] = 1;
                any_moved = true;
                ++undone;
              }
          if (!any_moved) unresolved.push_back(pr);
        }
        rep.smoothing_rollbacks += undone;
        rep.crossing_rollbacks += undone;
        // Undoing some moves can turn a face whose other vertices stay moved.
        const std::vector<Vec3> before_fold = m.positions;
        rep.smoothing_rollbacks += revert_folded_faces(m, refined);
        for (int v = 0; v < m.num_vertices(); ++v)
          if (m.positions[idx(v)] != before_fold[idx(v)]) {
            reset[idx(v)] = 1;
            moved[idx(v)] = m.positions[idx(v)] != refined[idx(v)];
          }
        if (undone == 0) break;  // only crossings without a moved corner are left
        query.clear();
        std::vector<std::uint8_t> in_query(idx(nf), 0);
        for (int f = 0; f < nf; ++f) {
          const Face& fc = m.faces[idx(f)];
          if (reset[idx(fc[0])] || reset[idx(fc[1])] || reset[idx(fc[2])]) in_query[idx(f)] = 1;
        }
        for (const auto& pr : unresolved)
          for (int f : pr) in_query[idx(f)] = 1;
        for (int f = 0; f < nf; ++f)
          if (in_query[idx(f)]) query.push_back(f);
        std::fill(reset.begin(), reset.end(), 0);
      }
      rep.check_ms += ms_since(t0);
      // Crossings left without a moved corner: from a split (refinement), or in the input (then
      // the round without refinement keeps them, as nothing here made them).
      if (unresolved.empty() || !refine) {
        rep.splits += rs.splits;
        rep.flips += rs.flips;
        break;
      }
      ++rep.refinement_rollbacks;
      refine = false;
      m = start;
      fixed = fixed_start;
    }

    // === Early give-up: worse than the input on both figures after this round (options).
    if (it == options.give_up_after_round && it + 1 < options.iterations) {
      if (worse_on_both(mesh_quality(m.to_trimesh()), quality_in)) {
        rep.gave_up_after_round = it;
        break;
      }
    }
  }

  rep.faces_out = m.num_faces();
  if (report) *report = rep;
  return m.to_trimesh();
}
}  // namespace

// === Quality figures
MeshQuality mesh_quality(const TriMesh& mesh) {
  MeshQuality q;
  if (mesh.faces.empty()) return q;
  const double rad = 180.0 / std::numbers::pi;
  q.min_angle_deg = 180.0;
  double sum_min = 0, sum_aspect = 0;
  std::vector<Vec3> normals(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& fc = mesh.faces[f];
    const Vec3 p[3] = {mesh.vertices[idx(fc[0])], mesh.vertices[idx(fc[1])], mesh.vertices[idx(fc[2])]};
    double min_angle = 180.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
      min_angle = std::min(min_angle, rad * std::atan2(u.cross(v).norm(), u.dot(v)));
    }
    q.min_angle_deg = std::min(q.min_angle_deg, min_angle);
    sum_min += min_angle;
    const double a = (p[1] - p[0]).norm(), b = (p[2] - p[1]).norm(), c = (p[0] - p[2]).norm();
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
    const double area = 0.5 * n.norm();
    const double aspect = area > 0 ? a * b * c * (a + b + c) / (16.0 * area * area)
                                   : std::numeric_limits<double>::infinity();
    q.max_aspect = std::max(q.max_aspect, aspect);
    sum_aspect += aspect;
    normals[f] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
  }
  q.mean_min_angle_deg = sum_min / static_cast<double>(mesh.faces.size());
  q.mean_aspect = sum_aspect / static_cast<double>(mesh.faces.size());
  // Dihedral figures over edges with exactly two faces.
  std::unordered_map<std::uint64_t, std::array<int, 3>> edges;  // key -> {face, face, count}
  edges.reserve(mesh.faces.size() * 2);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int a = mesh.faces[f][idx(k)], b = mesh.faces[f][idx((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
                                static_cast<std::uint32_t>(b);
      auto [itr, inserted] = edges.try_emplace(key, std::array<int, 3>{static_cast<int>(f), -1, 0});
      if (!inserted && itr->second[2] == 0) itr->second[1] = static_cast<int>(f);
      if (!inserted) ++itr->second[2];
    }
  double wsum = 0, sq = 0;
  std::size_t interior = 0, over_60 = 0, over_90 = 0;
  for (const auto& [key, e] : edges) {
    if (e[2] != 1) continue;
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const double len = (mesh.vertices[idx(a)] - mesh.vertices[idx(b)]).norm();
    const Vec3& n1 = normals[idx(e[0])];
    const Vec3& n2 = normals[idx(e[1])];
    const double ang = rad * std::atan2(n1.cross(n2).norm(), n1.dot(n2));
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, ang);
    ++interior;
    if (ang > 60.0) ++over_60;
    if (ang > 90.0) ++over_90;
    sq += len * ang * ang;
    wsum += len;
  }
  q.rms_dihedral_deg = wsum > 0 ? std::sqrt(sq / wsum) : 0.0;
  if (interior > 0) {
    q.sharp_edge_share = static_cast<double>(over_60) / static_cast<double>(interior);
    q.folded_edge_share = static_cast<double>(over_90) / static_cast<double>(interior);
  }
  return q;
}

}  // namespace ps
