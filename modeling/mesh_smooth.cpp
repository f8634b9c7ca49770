#include "modeling/mesh_smooth.h"

#include <algorithm>
#include <atomic>

#include "modeling/parallel_over.h"

namespace ps {
namespace {

std::size_t idx(int i) { return static_cast<std::size_t>(i); }
int as_int(std::size_t i) { return static_cast<int>(i); }

// Per-vertex and per-face loops go parallel from this size on; each iteration writes only its
// own slot, so the results are bit-identical to a sequential run.
constexpr std::size_t kMinParallel = 4096;

// Twice the area is below 1e-10 times the squared longest edge (angles of about 1e-10 rad).
bool degenerate(const Vec3& n, const Face& f, const std::vector<Vec3>& p) {
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (p[idx(f[idx(k)])] - p[idx(f[idx((k + 1) % 3)])]).squaredNorm());
  return !(n.squaredNorm() > 1e-20 * longest * longest);
}

// A face whose normal went from n0 to n turned over, or collapsed. A face that was already
// degenerate may stay so (the step may be what repairs it).
bool face_folded(const Vec3& n0, const Vec3& n, const std::vector<Vec3>& p0, const Face& f,
                 const std::vector<Vec3>& p) {
  if (n.dot(n0) > 0.0 && !degenerate(n, f, p)) return false;  // the common case first
  return !degenerate(n0, f, p0);
}

// Face f of m turned over or collapsed since `before` (its normal then computed from `before`).
bool folded_since(const HalfedgeMesh& m, int f, const std::vector<Vec3>& before) {
  const Face& fc = m.faces[idx(f)];
  const Vec3& a = before[idx(fc[0])];
  const Vec3 n0 = (before[idx(fc[1])] - a).cross(before[idx(fc[2])] - a);
  return face_folded(n0, m.face_normal(f), before, fc, m.positions);
}

}  // namespace

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
  // face_normal_ holds the normals before the step: a quick scan finds whether any face folded.
  std::atomic<bool> folded{false};
  parallel_ranges(idx(m.num_faces()), kMinParallel, [&](std::size_t b, std::size_t e) {
    for (std::size_t f = b; f < e && !folded.load(std::memory_order_relaxed); ++f)
      if (face_folded(face_normal_[f], m.face_normal(as_int(f)), before, m.faces[f], m.positions)) folded = true;
  });
  return folded ? revert_folded_faces(m, before) : 0;
}

std::vector<Vec3> smooth_step(const HalfedgeMesh& m, const std::vector<std::uint8_t>& fixed,
                              const SmoothOptions& o) {
  Smoother s(m, fixed, o);
  return s.next_positions(m);
}

int revert_folded_faces(HalfedgeMesh& m, const std::vector<Vec3>& before) {
  int reverted = 0;
  const int nf = m.num_faces();
  // The first folded face, found in parallel (usually there is none): the sequential pass below
  // changes nothing before it, so starting there gives the same result as starting at face 0.
  std::atomic<int> first{nf};
  parallel_ranges(idx(nf), kMinParallel, [&](std::size_t b, std::size_t e) {
    for (std::size_t f = b; f < e && as_int(f) < first.load(std::memory_order_relaxed); ++f) {
      if (folded_since(m, as_int(f), before)) {
        int cur = first.load();
        while (as_int(f) < cur && !first.compare_exchange_weak(cur, as_int(f))) {
        }
        break;
      }
    }
  });
  if (first.load() == nf) return 0;
  // Ends: every round puts back at least one moved vertex, and none moves again.
  for (int start = first.load();; start = 0) {
    int changed = 0;
    for (int f = start; f < nf; ++f) {
      if (!folded_since(m, f, before)) continue;
      for (int v : m.faces[idx(f)])
        if (m.positions[idx(v)] != before[idx(v)]) {
          m.positions[idx(v)] = before[idx(v)];
          ++reverted;
          ++changed;
        }
    }
    if (changed == 0) break;
  }
  return reverted;
}

}  // namespace ps
