#include "modeling/mesh_smooth.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "modeling/parallel_over.h"

namespace ps {
namespace {

std::size_t idx(int i) { return static_cast<std::size_t>(i); }
int as_int(std::size_t i) { return static_cast<int>(i); }

// Per-vertex and per-face loops go parallel from this size on; each iteration writes only its
// own slot, so the results are bit-identical to a sequential run.
constexpr std::size_t kMinParallel = 4096;

// A face whose normal went from n0 to n turned over, or collapsed. A face that was already
// degenerate may stay so (the step may be what repairs it).
bool face_folded(const Vec3& n0, const Vec3& n, const std::vector<Vec3>& p0, const Face& f,
                 const std::vector<Vec3>& p) {
  if (n.dot(n0) > 0.0 && !degenerate_face(n, f, p)) return false;  // the common case first
  return !degenerate_face(n0, f, p0);
}

// Face f of m turned over or collapsed since `before` (its normal then computed from `before`).
bool folded_since(const HalfedgeMesh& m, int f, const std::vector<Vec3>& before) {
  const Face& fc = m.faces[idx(f)];
  const Vec3& a = before[idx(fc[0])];
  const Vec3 n0 = (before[idx(fc[1])] - a).cross(before[idx(fc[2])] - a);
  return face_folded(n0, m.face_normal(f), before, fc, m.positions);
}

// The faces for which folded(f) holds, in increasing order (scanned in parallel).
template <class Folded>
std::vector<int> folded_faces(int nf, const Folded& folded) {
  std::vector<std::vector<int>> found(32);
  const std::size_t step = (idx(nf) + found.size() - 1) / found.size();
  auto scan = [&](std::size_t c) {
    for (std::size_t f = c * step; f < std::min(idx(nf), (c + 1) * step); ++f)
      if (folded(as_int(f))) found[c].push_back(as_int(f));
  };
  if (idx(nf) < kMinParallel) {
    for (std::size_t c = 0; c < found.size(); ++c) scan(c);
  } else {
    parallel_over(found.size(), 0, scan);
  }
  std::vector<int> all;
  for (const auto& part : found) all.insert(all.end(), part.begin(), part.end());
  return all;
}

// revert_folded_faces from the faces folded at the start (`sweep`, in increasing order).
int revert_from(HalfedgeMesh& m, const std::vector<Vec3>& before, std::vector<int> sweep) {
  // The rule: sweep the faces in index order, putting back the moved corners of every folded
  // face, and sweep again until a sweep changes nothing. Sweeping all faces each time was most of
  // this function's cost on large meshes (two serial passes over 60k faces per call, in every
  // smoothing step and rollback pass with a fold), so the same sweeps visit only the faces whose
  // state can have changed, with the same outcome: a face not folded when last visited stays so
  // until one of its corners is put back. So each sweep visits, in increasing order, the faces
  // folded at its start (a parallel scan, for the first sweep) or touched by a revert in
  // the previous sweep, plus the faces of higher index touched by a revert during it (which a
  // full sweep would reach after the revert). Same reverts, in the same order, as the full sweeps.
  const int nf = m.num_faces();
  if (sweep.empty()) return 0;
  std::vector<std::uint8_t> in_sweep(idx(nf), 0), in_next(idx(nf), 0);
  for (int f : sweep) in_sweep[idx(f)] = 1;
  std::vector<int> next;
  std::greater<int> min_first;
  std::make_heap(sweep.begin(), sweep.end(), min_first);
  int reverted = 0;
  for (;;) {
    int changed = 0;
    while (!sweep.empty()) {
      std::pop_heap(sweep.begin(), sweep.end(), min_first);
      const int f = sweep.back();
      sweep.pop_back();
      in_sweep[idx(f)] = 0;
      if (!folded_since(m, f, before)) continue;
      for (int v : m.faces[idx(f)]) {
        if (m.positions[idx(v)] == before[idx(v)]) continue;
        m.positions[idx(v)] = before[idx(v)];
        ++reverted;
        ++changed;
        m.for_each_outgoing(v, [&](int h) {
          const int g = HalfedgeMesh::face_of(h);
          if (g > f) {
            if (!in_sweep[idx(g)]) {
              in_sweep[idx(g)] = 1;
              sweep.push_back(g);
              std::push_heap(sweep.begin(), sweep.end(), min_first);
            }
          } else if (!in_next[idx(g)]) {
            in_next[idx(g)] = 1;
            next.push_back(g);
          }
        });
      }
    }
    if (changed == 0) break;
    // The next sweep: the faces a revert touched after this sweep had visited them (a face
    // touched before its visit was checked with the new positions).
    for (int f : next) in_next[idx(f)] = 0;
    sweep.swap(next);
    next.clear();
    for (int f : sweep) in_sweep[idx(f)] = 1;
    std::make_heap(sweep.begin(), sweep.end(), min_first);
  }
  return reverted;
}

}  // namespace

// Twice the area is below 1e-10 times the squared longest edge (angles of about 1e-10 rad).
bool degenerate_face(const Vec3& twice_area_normal, const Face& f, const std::vector<Vec3>& p) {
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (p[idx(f[idx(k)])] - p[idx(f[idx((k + 1) % 3)])]).squaredNorm());
  return !(twice_area_normal.squaredNorm() > 1e-20 * longest * longest);
}

Smoother::Smoother(const HalfedgeMesh& m, const std::vector<std::uint8_t>& fixed, const SmoothOptions& o)
    : options_(o), fixed_(fixed) {
  const int nv = m.num_vertices();
  ring_start_.assign(idx(nv + 1), 0);
  fan_start_.assign(idx(nv + 1), 0);
  for (int v = 0; v < nv; ++v) {
    ring_start_[idx(v + 1)] = ring_start_[idx(v)];
    if (m.out[idx(v)] < 0) continue;
    m.for_each_outgoing(v, [&](int h) {
      ring_.push_back(m.target(h));
      fan_.push_back(HalfedgeMesh::face_of(h));
      ++ring_start_[idx(v + 1)];
    });
  }
  fan_start_ = ring_start_;  // one face per outgoing halfedge in a closed mesh
  fixed_.resize(idx(nv), 1);  // vertices unknown to `fixed` stay put
}

// === Eq. 4.3: p' = p + tau N + eps T
std::vector<Vec3> Smoother::next_positions(const HalfedgeMesh& m) {
  const int nv = m.num_vertices(), nf = m.num_faces();
  face_normal_.resize(idx(nf));
  parallel_ranges(idx(nf), kMinParallel, [&](std::size_t b, std::size_t e) {
    for (std::size_t f = b; f < e; ++f) face_normal_[f] = m.face_normal(as_int(f));
  });
  delta_.assign(idx(nv), Vec3::Zero());
  normal_.assign(idx(nv), Vec3::Zero());
  kappa_.assign(idx(nv), 0.0);
  edge2_.assign(idx(nv), 0.0);
  parallel_ranges(idx(nv), kMinParallel, [&](std::size_t vb, std::size_t ve) {
    for (int v = as_int(vb); v < as_int(ve); ++v) {
      const int b = ring_start_[idx(v)], e = ring_start_[idx(v + 1)];
      if (b == e) continue;
      Vec3 sum = Vec3::Zero(), n = Vec3::Zero();
      double len2 = 0;
      for (int i = b; i < e; ++i) {
        const Vec3& q = m.position(ring_[idx(i)]);
        sum += q;
        len2 += (q - m.position(v)).squaredNorm();
        n += face_normal_[idx(fan_[idx(i)])];  // area-weighted: twice the area times the unit normal
      }
      delta_[idx(v)] = sum / (e - b) - m.position(v);
      const double len = n.norm();
      normal_[idx(v)] = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
      kappa_[idx(v)] = delta_[idx(v)].dot(normal_[idx(v)]);
      edge2_[idx(v)] = len2 / (e - b);
    }
  });
  std::vector<Vec3> out = m.positions;
  parallel_ranges(idx(nv), kMinParallel, [&](std::size_t vb, std::size_t ve) {
    for (int v = as_int(vb); v < as_int(ve); ++v) {
      const int b = ring_start_[idx(v)], e = ring_start_[idx(v + 1)];
      if (fixed_[idx(v)] || b == e) continue;
      const Vec3& nrm = normal_[idx(v)];
      double normal_move = kappa_[idx(v)];
      if (options_.flow == NormalFlow::kCurvatureEvening) {
        // kappa ~ -H l^2 / 2 for mean edge length l: compare curvatures, not kappas, so that a
        // sphere sampled unevenly is still a fixed point.
        double mean = 0;
        for (int i = b; i < e; ++i) {
          const int j = ring_[idx(i)];
          if (edge2_[idx(j)] > 0.0) mean += kappa_[idx(j)] / edge2_[idx(j)];
        }
        normal_move -= edge2_[idx(v)] * mean / (e - b);
        if (options_.limit_evening) {
          const double bound = std::abs(kappa_[idx(v)]);
          normal_move = std::clamp(normal_move, -bound, bound);
        }
      }
      const Vec3 tangential = delta_[idx(v)] - kappa_[idx(v)] * nrm;
      out[idx(v)] = m.position(v) + options_.normal_step * normal_move * nrm + options_.tangential_step * tangential;
    }
  });
  return out;
}

int Smoother::step(HalfedgeMesh& m) {
  std::vector<Vec3> before = m.positions;
  m.positions = next_positions(m);
  // face_normal_ holds the normals before the step (the normals folded_since would compute).
  std::vector<int> folded = folded_faces(m.num_faces(), [&](int f) {
    return face_folded(face_normal_[idx(f)], m.face_normal(f), before, m.faces[idx(f)], m.positions);
  });
  return folded.empty() ? 0 : revert_from(m, before, std::move(folded));
}

std::vector<Vec3> smooth_step(const HalfedgeMesh& m, const std::vector<std::uint8_t>& fixed,
                              const SmoothOptions& o) {
  Smoother s(m, fixed, o);
  return s.next_positions(m);
}

int revert_folded_faces(HalfedgeMesh& m, const std::vector<Vec3>& before) {
  return revert_from(m, before, folded_faces(m.num_faces(), [&](int f) { return folded_since(m, f, before); }));
}

}  // namespace ps
