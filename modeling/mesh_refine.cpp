#include "modeling/mesh_refine.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "modeling/mesh_smooth.h"

namespace ps {
namespace {

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

class Relaxer {
 public:
  Relaxer(HalfedgeMesh& m, const FlipLock& lock, const RefineOptions& o)
      : m_(m), lock_(lock), cos_max_(std::cos(o.max_flip_normal_angle_deg * std::numbers::pi / 180.0)) {}

  // Delaunay-like test plus the manifold and no-fold guards.
  bool should_flip(int h) const {
    if (m_.is_constrained(h)) return false;
    const int t = m_.twin(h);
    const int a = m_.source(h), b = m_.target(h);
    const int c = m_.target(HalfedgeMesh::next(h)), d = m_.target(HalfedgeMesh::next(t));
    const Vec3 &pa = m_.position(a), &pb = m_.position(b), &pc = m_.position(c), &pd = m_.position(d);
    if (lock_.all) return false;
    // Opposite angles gamma, delta summing to more than pi: with sines > 0 this is
    // cot gamma + cot delta < 0, i.e. cos g sin d + cos d sin g < 0 (scaled by the edge
    // lengths); a tiny relative margin keeps co-circular quads stable.
    const Vec3 ca = pa - pc, cb = pb - pc, da = pa - pd, db = pb - pd;
    const double cos_c = ca.dot(cb), sin_c = ca.cross(cb).norm();
    const double cos_d = da.dot(db), sin_d = da.cross(db).norm();
    const double scale = ca.norm() * cb.norm() * da.norm() * db.norm();
    if (!(cos_c * sin_d + cos_d * sin_c < -1e-9 * scale)) return false;
    // Locked regions after the angle test: most edges fail that, and the regions are scanned.
    if (!lock_.regions.empty()) {
      Box3 quad;
      for (const Vec3* p : {&pa, &pb, &pc, &pd}) quad.extend(*p);
      if (lock_.locks(quad)) return false;
    }
    // No fold: the current faces must not meet at a sharp crease, and the new faces must face
    // the same way as the old ones and as each other, and be proper triangles.
    const Vec3 nf = (pb - pa).cross(pc - pa), ng = (pa - pb).cross(pd - pb);
    const double lf = nf.norm(), lg = ng.norm();
    if (!(nf.dot(ng) >= cos_max_ * lf * lg)) return false;
    const Vec3 n1 = (pc - pd).cross(pa - pd), n2 = (pd - pc).cross(pb - pc);  // (d,c,a), (c,d,b)
    const Vec3 old_sum = nf + ng;
    const double l1 = n1.norm(), l2 = n2.norm();
    const double cd2 = (pc - pd).squaredNorm();
    if (!(l1 > 1e-12 * cd2 && l2 > 1e-12 * cd2)) return false;
    if (!(n1.dot(n2) >= cos_max_ * l1 * l2)) return false;
    if (!(n1.dot(old_sum) > 0.0 && n2.dot(old_sum) > 0.0)) return false;
    return m_.can_flip(h);
  }

  // Flips the edge when it should; pushes the four outer edges for re-examination.
  bool relax(int h, std::vector<int>* stack) {
    if (!should_flip(h)) return false;
    if (valence_) {
      // Edge a-b becomes c-d (HalfedgeMesh::flip).
      const int t = m_.twin(h);
      --(*valence_)[idx(m_.source(h))];
      --(*valence_)[idx(m_.target(h))];
      ++(*valence_)[idx(m_.target(HalfedgeMesh::next(h)))];
      ++(*valence_)[idx(m_.target(HalfedgeMesh::next(t)))];
    }
    m_.flip(h);
    ++flips_;
    for (std::vector<std::uint8_t>* marks : {flipped_, dirty_})
      if (marks) {
        marks->resize(idx(m_.num_faces()), 0);
        (*marks)[idx(HalfedgeMesh::face_of(h))] = 1;
        (*marks)[idx(HalfedgeMesh::face_of(m_.twin(h)))] = 1;
      }
    if (stack) {
      const int t = m_.twin(h);
      stack->push_back(HalfedgeMesh::next(h));
      stack->push_back(HalfedgeMesh::prev(h));
      stack->push_back(HalfedgeMesh::next(t));
      stack->push_back(HalfedgeMesh::prev(t));
    }
    return true;
  }

  int relax_all() {
    std::vector<int> stack;
    const int nh = m_.num_halfedges();
    stack.reserve(idx(nh));
    for (int h = nh - 1; h >= 0; --h)
      if (h < m_.twin(h)) stack.push_back(h);
    return relax_from(stack);
  }

  // Relaxes the edges on the stack and, after each flip, the quad's outer edges.
  int relax_from(std::vector<int>& stack) {
    const int nh = m_.num_halfedges();
    const long cap = 8L * (nh / 2) + 16;
    const int before = flips_;
    while (!stack.empty() && flips_ - before < cap) {
      const int h = stack.back();
      stack.pop_back();
      relax(h, &stack);
    }
    return flips_ - before;
  }

  int flips() const { return flips_; }
  void track_flips(std::vector<std::uint8_t>* flipped) { flipped_ = flipped; }
  // A second set of marks, for refine_mesh's faces to look at again (cleared by the caller).
  void track_dirty(std::vector<std::uint8_t>* dirty) { dirty_ = dirty; }
  // Keeps per-vertex valences up to date across flips (the split loop's valence limit reads
  // them; walking the fans there was 4% of a stress case's reconstruction, perf).
  void track_valences(std::vector<int>* valence) { valence_ = valence; }

 private:
  HalfedgeMesh& m_;
  const FlipLock& lock_;
  double cos_max_;
  int flips_ = 0;
  std::vector<std::uint8_t>* flipped_ = nullptr;
  std::vector<std::uint8_t>* dirty_ = nullptr;
  std::vector<int>* valence_ = nullptr;
};

}  // namespace

// === Length attributes (thesis 4.5.1, first paragraph)
std::vector<double> length_attributes(const HalfedgeMesh& m, const std::vector<std::uint8_t>& fixed) {
  const int nv = m.num_vertices();
  std::vector<double> sigma(idx(nv), 0.0);
  std::vector<int> ring(idx(nv), -1);  // ring number, -1: unassigned
  std::vector<int> frontier;
  for (int v = 0; v < nv; ++v) {
    if (!fixed[idx(v)] || m.out[idx(v)] < 0) continue;
    double curve_sum = 0, all_sum = 0;
    int curve_n = 0, all_n = 0;
    m.for_each_outgoing(v, [&](int h) {
      const double len = (m.position(m.target(h)) - m.position(v)).norm();
      all_sum += len;
      ++all_n;
      if (m.is_constrained(h)) {
        curve_sum += len;
        ++curve_n;
      }
    });
    sigma[idx(v)] = curve_n > 0 ? curve_sum / curve_n : all_sum / std::max(all_n, 1);
    ring[idx(v)] = 0;
    frontier.push_back(v);
  }
  // Ring by ring: a vertex of ring r + 1 takes the mean sigma of its neighbours in rings <= r.
  std::vector<int> next_ring;
  for (int r = 0; !frontier.empty(); ++r) {
    next_ring.clear();
    for (int v : frontier)
      m.for_each_outgoing(v, [&](int h) {
        const int w = m.target(h);
        if (ring[idx(w)] == -1) {
          ring[idx(w)] = r + 1;
          next_ring.push_back(w);
        }
      });
    for (int w : next_ring) {
      double sum = 0;
      int n = 0;
      m.for_each_outgoing(w, [&](int h) {
        const int u = m.target(h);
        if (ring[idx(u)] >= 0 && ring[idx(u)] <= r) {
          sum += sigma[idx(u)];
          ++n;
        }
      });
      sigma[idx(w)] = sum / n;  // n >= 1: w was reached from a vertex of ring r
    }
    frontier.swap(next_ring);
  }
  // Components without curve vertices: their mean edge length (one flood fill per component).
  for (int s = 0; s < nv; ++s) {
    if (ring[idx(s)] != -1 || m.out[idx(s)] < 0) continue;
    std::vector<int> comp{s};
    ring[idx(s)] = 0;
    double sum = 0;
    long n = 0;
    for (std::size_t i = 0; i < comp.size(); ++i)
      m.for_each_outgoing(comp[i], [&](int h) {
        const int u = m.target(h);
        sum += (m.position(u) - m.position(comp[i])).norm();
        ++n;
        if (ring[idx(u)] == -1) {
          ring[idx(u)] = 0;
          comp.push_back(u);
        }
      });
    for (int v : comp) sigma[idx(v)] = sum / static_cast<double>(n);
  }
  return sigma;
}

bool FlipLock::locks(const Box3& quad) const {
  if (all) return true;
  for (const Box3& r : regions)
    if ((quad.min.array() <= r.max.array()).all() && (r.min.array() <= quad.max.array()).all()) return true;
  return false;
}

int relax_all_edges(HalfedgeMesh& mesh, const FlipLock& lock, const RefineOptions& options) {
  Relaxer r(mesh, lock, options);
  return r.relax_all();
}

// === Refinement: split + relax until no face splits
RefineStats refine_mesh(HalfedgeMesh& m, std::vector<std::uint8_t>& fixed, const FlipLock& lock,
                        const RefineOptions& o, std::vector<std::uint8_t>* changed) {
  RefineStats stats;
  std::vector<double> sigma = length_attributes(m, fixed);
  if (o.min_length > 0)
    for (double& x : sigma) x = std::max(x, o.min_length);
  Relaxer relaxer(m, lock, o);
  // Current valences, for the valence limit; kept up to date by the splits below and the
  // relaxer's flips.
  std::vector<int> valence;
  if (o.max_valence > 0) {
    valence.resize(idx(m.num_vertices()));
    for (int v = 0; v < m.num_vertices(); ++v) valence[idx(v)] = m.valence(v);
    relaxer.track_valences(&valence);
  }
  // Starting valences for the limit: the caller's, or this mesh's as it comes in.
  std::vector<int> own_base;
  if (!o.base_valence && o.max_valence > 0) own_base = valence;
  const std::vector<int>& base = o.base_valence ? *o.base_valence : own_base;
  auto valence_cap = [&](int v) {
    const std::size_t k = idx(v);
    return k < base.size() ? std::max(o.max_valence, 2 * base[k]) : o.max_valence;
  };
  if (changed) changed->assign(idx(m.num_faces()), 0);
  relaxer.track_flips(changed);
  // The geometry changed everywhere since the last refinement (smoothing): relax every edge
  // first; later passes only need the edges around the new faces.
  relaxer.relax_all();
  std::vector<int> touched;
  // Faces to look at in the next pass: every face in the first; then only those a split or a
  // flip rewrote since they were last looked at, and those the valence limit refused (a flip
  // elsewhere can lower a corner's valence). A face's own test reads only its corners, their
  // length attributes and its plane, which nothing else changes, so a face left out would be
  // refused again: the splits are the same, in the same order (each pass still goes in face
  // order, and a face rewritten before its turn in a pass is looked at in that pass). On the
  // 200k-face refinements of stress inputs the later passes re-tested every face to split a few.
  std::vector<std::uint8_t> dirty(idx(m.num_faces()), 1);
  relaxer.track_dirty(&dirty);
  for (int pass = 0; pass < o.max_passes; ++pass) {
    touched.clear();
    ++stats.passes;
    int splits = 0;
    const int nf0 = m.num_faces();
    for (int f = 0; f < nf0 && m.num_faces() + 2 <= o.max_faces; ++f) {
      if (!dirty[idx(f)] && !o.rescan_every_face) continue;
      dirty[idx(f)] = 0;
      const Face fc = m.faces[idx(f)];
      const Vec3 c = (m.position(fc[0]) + m.position(fc[1]) + m.position(fc[2])) / 3.0;
      const double sc = (sigma[idx(fc[0])] + sigma[idx(fc[1])] + sigma[idx(fc[2])]) / 3.0;
      bool split = true;
      for (int v : fc) {
        const double d = o.alpha * (m.position(v) - c).norm();
        if (!(d > sc && d > sigma[idx(v)])) {
          split = false;
          break;
        }
      }
      if (!split) continue;
      // A sliver (the fold checks' collapse test, degenerate_face) is not split: its centroid
      // lies on its long edge up to rounding, and its children lie along the neighbouring faces'
      // edges, which the exact check counts as crossings (stress seed 418: every round from the
      // second refined twice, then not at all).
      if (degenerate_face(m.face_normal(f), fc, m.positions)) {
        ++stats.sliver_refusals;
        continue;
      }
      // Valence limit (RefineOptions::max_valence): where flips cannot follow the splits (a
      // crease, a pinch, locked flips), each split of a face around a vertex adds one more
      // needle to its fan; stress seed 938 grew one vertex from 16 to 906 edges and a quarter
      // of its faces to slivers.
      if (o.max_valence > 0 && (valence[idx(fc[0])] >= valence_cap(fc[0]) || valence[idx(fc[1])] >= valence_cap(fc[1]) ||
                                valence[idx(fc[2])] >= valence_cap(fc[2]))) {
        ++stats.valence_refusals;
        dirty[idx(f)] = 1;
        continue;
      }
      m.split_face(f, c);
      dirty.resize(idx(m.num_faces()), 0);
      dirty[idx(f)] = dirty[idx(m.num_faces() - 2)] = dirty[idx(m.num_faces() - 1)] = 1;
      if (o.max_valence > 0) {
        for (int v : fc) ++valence[idx(v)];
        valence.push_back(3);
      }
      if (changed) {
        changed->resize(idx(m.num_faces()), 0);
        // Split faces are marked too, not only flipped ones: a split keeps its face's plane
        // only up to the centroid's rounding (on stress seed 418 split needles crossed their
        // neighbours, and no smoothing move was there for the later check to find them). Same
        // outputs where nothing crossed; the check's time is about the same (the flipped faces
        // were most of the new ones already).
        (*changed)[idx(f)] = (*changed)[idx(m.num_faces() - 2)] = (*changed)[idx(m.num_faces() - 1)] = 1;
      }
      sigma.push_back(sc);
      fixed.push_back(0);
      ++splits;
      // Relax the three edges of the split face (Liepa): they are now 3f, 3f1, 3f2.
      const int f1 = m.num_faces() - 2, f2 = m.num_faces() - 1;
      relaxer.relax(3 * f, nullptr);
      relaxer.relax(3 * f1, nullptr);
      relaxer.relax(3 * f2, nullptr);
      for (int g : {f, f1, f2})
        for (int k = 0; k < 3; ++k) touched.push_back(3 * g + k);
    }
    stats.splits += splits;
    if (splits == 0) break;
    relaxer.relax_from(touched);
  }
  stats.flips = relaxer.flips();
  if (changed) changed->resize(idx(m.num_faces()), 0);
  return stats;
}

}  // namespace ps
