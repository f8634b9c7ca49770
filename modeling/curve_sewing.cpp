#include "modeling/curve_sewing.h"

#include "modeling/polygon_triangulate.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <initializer_list>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include "modeling/polyline_crossing.h"

namespace ps {

namespace {

using Index = std::size_t;

// === Plane frames: 2D coordinates (x, y) <-> origin + x u + y v
struct Frame {
  Vec3 origin, u, v;
  explicit Frame(const Plane& p) : origin(p.offset * p.normal) { p.basis(u, v); }
  Vec2 to2d(const Vec3& q) const { return Vec2((q - origin).dot(u), (q - origin).dot(v)); }
  Vec3 to3d(const Vec2& q) const { return origin + q.x() * u + q.y() * v; }
};

// The line L = Pa ∩ Pb in Pa's 2D coordinates: { x : g.x == c }, g.x - c being the signed
// distance to Pb of the 3D point.
struct Line2 {
  Vec2 g;
  double c;
  Vec2 project(const Vec2& x) const { return x - ((g.dot(x) - c) / g.squaredNorm()) * g; }
  Vec2 reflect(const Vec2& x) const { return x - (2.0 * (g.dot(x) - c) / g.squaredNorm()) * g; }
};
Line2 line_in(const Frame& fa, const Plane& pb) {
  return Line2{Vec2(pb.normal.dot(fa.u), pb.normal.dot(fa.v)), pb.offset - pb.normal.dot(fa.origin)};
}

bool parallel(const Plane& a, const Plane& b) { return a.normal.cross(b.normal).norm() < 1e-9; }

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}
std::string fmt3(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

// === Crossings of one closed curve with one plane
struct Crossing {
  int curve = -1;
  bool at_vertex = false;
  int vertex = -1;  // at_vertex: the curve point on the plane
  int edge = -1;    // otherwise: the edge (edge, edge + 1 mod n) crossed at parameter t
  double t = 0.0;
  Vec2 p2 = Vec2::Zero();  // in the curve's plane coordinates
  Vec3 p3 = Vec3::Zero();
  double s = 0.0;          // parameter along L
  bool touch = false;      // the curve touches the plane here without crossing
  double arc_depth = 0.0;  // crossings only: max |distance| on the arc from the previous crossing
  int arc_begin = -1;      // first vertex after the previous crossing (cyclic)
};

// Walks the closed curve once. eps: |distance| <= eps counts as on the plane.
std::vector<Crossing> curve_crossings(int curve, const std::vector<Vec2>& x, const Frame& frame,
                                      const Plane& other, double eps) {
  std::vector<Crossing> out;
  const Index n = x.size();
  if (n < 2) return out;
  std::vector<double> d(n);
  std::vector<int> sgn(n);
  for (Index k = 0; k < n; ++k) {
    d[k] = other.signed_distance(frame.to3d(x[k]));
    sgn[k] = std::abs(d[k]) <= eps ? 0 : (d[k] > 0.0 ? 1 : -1);
  }
  Index start = n;
  for (Index k = 0; k < n; ++k)
    if (sgn[k] != 0) {
      start = k;
      break;
    }
  if (start == n) return out;  // the curve lies in the other plane
  int last = sgn[start];
  std::vector<Index> run;  // on-plane vertices since the last off-plane one
  double depth = std::abs(d[start]);
  int arc_begin = static_cast<int>(start);
  std::vector<Crossing> crossings;
  for (Index step = 1; step <= n; ++step) {
    const Index k = (start + step) % n;
    if (sgn[k] == 0) {
      run.push_back(k);
      continue;
    }
    if (sgn[k] != last || !run.empty()) {
      Crossing c;
      c.curve = curve;
      c.touch = sgn[k] == last;
      if (!run.empty()) {
        c.at_vertex = true;
        c.vertex = static_cast<int>(run[run.size() / 2]);
        c.p2 = x[static_cast<Index>(c.vertex)];
      } else {
        const Index km = (k + n - 1) % n;
        c.edge = static_cast<int>(km);
        c.t = d[km] / (d[km] - d[k]);
        c.p2 = x[km] + c.t * (x[k] - x[km]);
      }
      c.p3 = frame.to3d(c.p2);
      if (!c.touch) {
        c.arc_depth = depth;
        c.arc_begin = arc_begin;
        depth = 0.0;
        arc_begin = static_cast<int>(k);
      }
      out.push_back(c);
    }
    run.clear();
    last = sgn[k];
    depth = std::max(depth, std::abs(d[k]));
  }
  // The arc before the first crossing started at the last crossing of the walk.
  for (auto& c : out)
    if (!c.touch) {
      c.arc_depth = std::max(c.arc_depth, depth);
      c.arc_begin = arc_begin;
      break;
    }
  return out;
}

// === Matching one pair of planes
struct CurveState {
  int plane = -1;
  std::vector<Vec2> pts;  // 2D, in the plane's frame
  bool modified = false;
  std::vector<int> original_index;  // input point i is pts[original_index[i]]
};

struct HandleRequest {
  Crossing crossing;
  Vec2 target;
  int partner_plane;
};
struct Reflection {
  int vertex;
  Vec2 target;
};

struct PairResult {
  std::vector<std::pair<Crossing, Crossing>> matched;  // (on plane a, on plane b)
  std::vector<std::pair<Crossing, Crossing>> grazes;   // consecutive crossings of one curve to remove
  int plane_b = -1;                                    // for grazes: the plane they cross
};

std::string name_curves(const std::vector<int>& ids) {
  std::string s = ids.size() == 1 ? "curve " : "curves ";
  for (Index i = 0; i < ids.size(); ++i) s += (i ? ", " : "") + std::to_string(ids[i]);
  return s;
}

// Removes near-tangent pairs (shallowest first) from `list` (all crossings of several curves,
// touches excluded) until it has `want` entries or none are left. Removed pairs go to `grazes`.
void drop_grazes(std::vector<Crossing>& list, Index want, double tol,
                 std::vector<std::pair<Crossing, Crossing>>& grazes) {
  while (list.size() > want) {
    // Candidates: crossing m whose preceding arc (from its predecessor on the same curve) is
    // shallower than tol.
    double best = tol;
    Index best_m = list.size();
    for (Index m = 0; m < list.size(); ++m)
      if (list[m].arc_depth < best) {
        best = list[m].arc_depth;
        best_m = m;
      }
    if (best_m == list.size()) return;
    // Its predecessor on the same curve: the crossing whose following arc begins at arc_begin.
    const Crossing cm = list[best_m];
    Index pred = list.size();
    int count_same = 0;
    for (Index m = 0; m < list.size(); ++m)
      if (list[m].curve == cm.curve) ++count_same;
    // Crossings of one curve are stored in walk order; the predecessor is the previous one of
    // that curve, cyclically.
    std::vector<Index> mine;
    for (Index m = 0; m < list.size(); ++m)
      if (list[m].curve == cm.curve) mine.push_back(m);
    for (Index q = 0; q < mine.size(); ++q)
      if (mine[q] == best_m) pred = mine[(q + mine.size() - 1) % mine.size()];
    if (count_same < 2 || pred == best_m) {
      list[best_m].arc_depth = std::numeric_limits<double>::infinity();
      continue;
    }
    grazes.emplace_back(list[pred], cm);
    // The crossing after cm now ends a longer arc (from pred's predecessor): its stored depth
    // no longer describes that arc, so it may not be dropped as a graze.
    for (Index q = 0; q < mine.size(); ++q)
      if (mine[q] == best_m) list[mine[(q + 1) % mine.size()]].arc_depth = std::numeric_limits<double>::infinity();
    const Index hi = std::max(pred, best_m), lo = std::min(pred, best_m);
    list.erase(list.begin() + static_cast<std::ptrdiff_t>(hi));
    list.erase(list.begin() + static_cast<std::ptrdiff_t>(lo));
  }
}

Result<PairResult> match_planes(const SectionSet& in, const std::vector<CurveState>& state,
                                const std::vector<Frame>& frames, int pa, int pb, double eps,
                                double tangent_tol) {
  const Plane& A = in.planes[static_cast<Index>(pa)];
  const Plane& B = in.planes[static_cast<Index>(pb)];
  const Vec3 dir = A.normal.cross(B.normal).normalized();
  std::vector<Crossing> on_a, on_b;  // crossings of a's curves with B, of b's curves with A
  std::vector<int> ids_a, ids_b;
  for (Index c = 0; c < state.size(); ++c) {
    const auto& cs = state[c];
    const bool is_a = cs.plane == pa;
    if (!is_a && cs.plane != pb) continue;
    (is_a ? ids_a : ids_b).push_back(static_cast<int>(c));
    auto list = curve_crossings(static_cast<int>(c), cs.pts, frames[static_cast<Index>(cs.plane)],
                                is_a ? B : A, eps);
    for (auto& x : list) {
      if (x.touch) continue;
      x.s = dir.dot(x.p3);
      (is_a ? on_a : on_b).push_back(x);
    }
  }
  PairResult r;
  r.plane_b = pb;
  if (ids_a.empty() || ids_b.empty()) return r;
  const Index count_a = on_a.size(), count_b = on_b.size();
  std::vector<std::pair<Crossing, Crossing>> grazes;
  if (count_a != count_b) {
    drop_grazes(count_a > count_b ? on_a : on_b, std::min(count_a, count_b), tangent_tol, grazes);
    if (on_a.size() != on_b.size()) {
      std::string msg;
      if (ids_a.size() == 1 && ids_b.size() == 1)
        msg = "curve " + std::to_string(ids_a[0]) + " crosses the line shared with curve " +
              std::to_string(ids_b[0]) + "'s plane at " + std::to_string(count_a) + " points, curve " +
              std::to_string(ids_b[0]) + " at " + std::to_string(count_b) + " points";
      else
        msg = name_curves(ids_a) + " (plane " + std::to_string(pa) + ") cross the line shared with plane " +
              std::to_string(pb) + " at " + std::to_string(count_a) + " points, " + name_curves(ids_b) +
              " (plane " + std::to_string(pb) + ") at " + std::to_string(count_b) + " points";
      return Result<PairResult>::error(msg + " (rule 4: curves on two planes must meet that line at the same points)");
    }
  }
  auto by_s = [](const Crossing& x, const Crossing& y) { return x.s < y.s; };
  std::sort(on_a.begin(), on_a.end(), by_s);
  std::sort(on_b.begin(), on_b.end(), by_s);
  // Sorted pairing along the line: the closest-point pairing for equal counts.
  for (Index i = 0; i < on_a.size(); ++i) r.matched.emplace_back(on_a[i], on_b[i]);
  r.grazes = std::move(grazes);
  return r;
}

// === Eq. 3.3 / 3.4: 2D Laplacian editing of one closed curve with hard constraints
// Unknowns: V' (n points, 2n scalars, x then y per point). Rows per point i:
//   L(V')_i - T_i(V') delta_i   (Eq. 3.2 Laplacian with weights 1/2; T_i = [[s, w], [-w, s]]
//   the least-squares similarity (plus translation, as in Sorkine et al. 2004, so the result
//   does not depend on where the origin is) taking the rest points {i-1, i, i+1} to their new
//   positions (Eq. 3.4); (s, w) is linear in V', so the rows are linear)
//   sqrt(mu) (V'_i - V_i)   (weak pull to the old shape, free points only; mu from influence)
// Constrained points are eliminated; the normal equations are factored with SimplicialLDLT.
//
// The linearised T_i may scale a Laplacian vector down as freely as it rotates it, which
// flattens the curve's detail next to a handle (a dent of ~10% of the handle move on an
// ellipse). A second solve fixes that: T_i is evaluated at the first solution, its scale is
// divided out, and the plain Laplacian system L(V')_i = R_i delta_i is solved with the same
// constraints (the usual scale normalisation of linear Laplacian editing).
class CurveLsq {
 public:
  CurveLsq(const std::vector<Vec2>& x, const std::map<int, Vec2>& fixed) : n_(x.size()), col_(2 * n_, -1), out_(x) {
    for (Index k = 0; k < n_; ++k)
      if (!fixed.count(static_cast<int>(k))) {
        col_[2 * k] = nf_++;
        col_[2 * k + 1] = nf_++;
      }
    for (const auto& [k, p] : fixed) out_[static_cast<Index>(k)] = p;
  }
  int free_count() const { return nf_; }
  const std::vector<Vec2>& known() const { return out_; }
  // Adds the row sum_k coeffs[k].second * unknown[coeffs[k].first] = b.
  void add_row(std::initializer_list<std::pair<Index, double>> coeffs, double b) {
    add_row_impl(coeffs.begin(), coeffs.end(), b);
  }
  template <class It>
  void add_row_impl(It first, It last, double b) {
    double r = b;
    for (It it = first; it != last; ++it) {
      const auto [var, a] = *it;
      if (a == 0.0) continue;
      if (col_[var] >= 0)
        trip_.emplace_back(rows_, col_[var], a);
      else
        r -= a * out_[var / 2][static_cast<Eigen::Index>(var % 2)];  // constrained: to the right
    }
    rhs_.push_back(r);
    ++rows_;
  }
  void add_position_rows(const std::vector<Vec2>& rest, double weight) {
    const double w = std::sqrt(weight);
    if (!(w > 0.0)) return;
    for (Index v = 0; v < 2 * n_; ++v)
      if (col_[v] >= 0) add_row({{v, w}}, w * rest[v / 2][static_cast<Eigen::Index>(v % 2)]);
  }
  Result<std::vector<Vec2>> solve() const {
    Eigen::SparseMatrix<double> M(rows_, nf_);
    M.setFromTriplets(trip_.begin(), trip_.end());
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(rhs_.data(), static_cast<Eigen::Index>(rhs_.size()));
    const Eigen::SparseMatrix<double> N = M.transpose() * M;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(N);
    if (solver.info() != Eigen::Success)
      return Result<std::vector<Vec2>>::error("the curve cannot be deformed (singular system)");
    const Eigen::VectorXd sol = solver.solve(M.transpose() * b);
    if (solver.info() != Eigen::Success || !sol.allFinite())
      return Result<std::vector<Vec2>>::error("the curve cannot be deformed (solve failed)");
    std::vector<Vec2> out = out_;
    for (Index k = 0; k < n_; ++k)
      if (col_[2 * k] >= 0) out[k] = Vec2(sol[col_[2 * k]], sol[col_[2 * k + 1]]);
    return out;
  }

 private:
  Index n_;
  std::vector<int> col_;
  int nf_ = 0;
  std::vector<Vec2> out_;  // constrained points at their targets
  std::vector<Eigen::Triplet<double>> trip_;
  std::vector<double> rhs_;
  int rows_ = 0;
};

Result<std::vector<Vec2>> deform_curve(const std::vector<Vec2>& x, const std::map<int, Vec2>& fixed,
                                       const SewingParams& params) {
  const Index n = x.size();
  CurveLsq first(x, fixed);
  if (first.free_count() == 0) return first.known();
  std::vector<Eigen::Matrix<double, 2, 6>> fit(n);  // (s_i, w_i) as a linear map of the 6 unknowns
  std::vector<Vec2> delta(n);
  for (Index i = 0; i < n; ++i) {
    const Index ids[3] = {(i + n - 1) % n, i, (i + 1) % n};
    // Eq. 3.4: local similarity fit, rest points centred for conditioning.
    const Vec2 centre = (x[ids[0]] + x[ids[1]] + x[ids[2]]) / 3.0;
    Eigen::Matrix<double, 6, 4> A;
    for (int k = 0; k < 3; ++k) {
      const Vec2 q = x[ids[k]] - centre;
      A.row(2 * k) << q.x(), q.y(), 1.0, 0.0;
      A.row(2 * k + 1) << q.y(), -q.x(), 0.0, 1.0;
    }
    const Eigen::Matrix4d AtA = A.transpose() * A;
    const Eigen::Matrix<double, 4, 6> pinv = AtA.ldlt().solve(A.transpose());
    fit[i] = pinv.topRows<2>();
    delta[i] = x[i] - 0.5 * (x[ids[0]] + x[ids[2]]);  // Eq. 3.2
    Eigen::Matrix2d D;  // T_i delta_i == D (s_i, w_i)
    D << delta[i].x(), delta[i].y(), delta[i].y(), -delta[i].x();
    Eigen::Matrix<double, 2, 6> R = -(D * fit[i]);
    // Laplacian part: columns (x_{i-1}, y_{i-1}, x_i, y_i, x_{i+1}, y_{i+1}).
    R(0, 0) -= 0.5, R(1, 1) -= 0.5, R(0, 2) += 1.0, R(1, 3) += 1.0, R(0, 4) -= 0.5, R(1, 5) -= 0.5;
    for (int r = 0; r < 2; ++r) {  // Eq. 3.3, first sum
      std::array<std::pair<Index, double>, 6> coeffs;
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 2; ++c)
          coeffs[static_cast<Index>(2 * k + c)] = {2 * ids[k] + static_cast<Index>(c), R(r, 2 * k + c)};
      first.add_row_impl(coeffs.begin(), coeffs.end(), 0.0);
    }
  }
  const double mu = std::pow(std::max(params.influence, 1e-3) * static_cast<double>(n), -4.0);
  first.add_position_rows(x, mu);
  auto v1 = first.solve();
  if (!v1 || !params.normalize_scale) return v1;

  // === Second solve: rotations from the first solution, scale divided out
  CurveLsq second(x, fixed);
  for (Index i = 0; i < n; ++i) {
    const Index ids[3] = {(i + n - 1) % n, i, (i + 1) % n};
    Eigen::Matrix<double, 6, 1> v6;
    for (int k = 0; k < 3; ++k) v6.segment<2>(2 * k) = (*v1)[ids[k]];
    const Vec2 sw = fit[i] * v6;
    const double norm = sw.norm();
    const Vec2 r = norm > 0.0 ? Vec2(sw / norm) : Vec2(1.0, 0.0);
    const Vec2 target(r.x() * delta[i].x() + r.y() * delta[i].y(), -r.y() * delta[i].x() + r.x() * delta[i].y());
    for (int c = 0; c < 2; ++c) {
      const auto cc = static_cast<Index>(c);
      second.add_row({{2 * ids[0] + cc, -0.5}, {2 * ids[1] + cc, 1.0}, {2 * ids[2] + cc, -0.5}}, target[c]);
    }
  }
  second.add_position_rows(x, mu);
  return second.solve();
}

// Turns handle requests into constrained vertices (snapping or inserting points) and deforms.
Result<bool> apply_handles(CurveState& cs, const std::vector<HandleRequest>& handles,
                           const std::vector<Reflection>& reflections, const SewingParams& params,
                           double same_target) {
  const Index n = cs.pts.size();
  const auto dn = static_cast<double>(n);
  // === Handles with one target (crossings with two planes moved to the planes' common point):
  // one curve point serves them all, and the few points between those crossings are dropped.
  std::vector<HandleRequest> hs;
  std::vector<bool> removed(n, false);
  {
    auto pos = [](const Crossing& c) { return c.at_vertex ? static_cast<double>(c.vertex) : c.edge + c.t; };
    std::vector<bool> used(handles.size(), false);
    for (Index i = 0; i < handles.size(); ++i) {
      if (used[i]) continue;
      std::vector<Index> group{i};
      for (Index j = i + 1; j < handles.size(); ++j)
        if (!used[j] && (handles[j].target - handles[i].target).norm() <= same_target) group.push_back(j);
      for (Index g : group) used[g] = true;
      if (group.size() == 1) {
        hs.push_back(handles[i]);
        continue;
      }
      // The shortest arc holding all of them: it starts after the largest gap between
      // consecutive positions (cyclically).
      std::sort(group.begin(), group.end(),
                [&](Index a, Index b) { return pos(handles[a].crossing) < pos(handles[b].crossing); });
      const Index m = group.size();
      Index after_gap = 0;
      double largest = -1.0;
      for (Index g = 0; g < m; ++g) {
        const double gap = std::fmod(pos(handles[group[(g + 1) % m]].crossing) - pos(handles[group[g]].crossing) + dn, dn);
        if (gap > largest) largest = gap, after_gap = (g + 1) % m;
      }
      const HandleRequest& first = handles[group[after_gap]];
      const double start = pos(first.crossing);
      const double span = dn - largest;
      std::vector<Index> inner;
      for (Index v = 0; v < n; ++v) {
        const double d = std::fmod(static_cast<double>(v) - start + dn, dn);
        if (d > 0.0 && d < span) inner.push_back(v);
      }
      if (inner.size() > 4) {  // not a local cluster: keep the handles apart
        for (Index g : group) hs.push_back(handles[g]);
        continue;
      }
      for (Index v : inner) removed[v] = true;
      hs.push_back(first);
    }
  }
  // === Choose a vertex for every handle; crossings at an existing vertex claim it first.
  std::map<int, std::pair<Vec2, int>> vertex_targets;  // vertex -> (sum of targets, count)
  struct Insert {
    int edge;
    double t;
    Vec2 target;
  };
  std::vector<Insert> inserts;
  for (const auto& h : hs)
    if (h.crossing.at_vertex && !removed[static_cast<Index>(h.crossing.vertex)]) {
      auto& slot = vertex_targets[h.crossing.vertex];
      slot.first += h.target;
      slot.second += 1;
    }
  for (const auto& h : hs) {
    if (h.crossing.at_vertex) {
      if (removed[static_cast<Index>(h.crossing.vertex)]) inserts.push_back({h.crossing.vertex, 0.0, h.target});
      continue;
    }
    const int e = h.crossing.edge;
    const double t = h.crossing.t;
    int snap = -1;
    if (t <= params.snap_fraction) snap = e;
    if (t >= 1.0 - params.snap_fraction) snap = static_cast<int>((static_cast<Index>(e) + 1) % n);
    if (snap >= 0 && !removed[static_cast<Index>(snap)] && !vertex_targets.count(snap)) {
      vertex_targets[snap] = {h.target, 1};
    } else {
      inserts.push_back({e, t, h.target});
    }
  }
  // === Insert new points on their edges (in order along each edge)
  std::sort(inserts.begin(), inserts.end(),
            [](const Insert& a, const Insert& b) { return a.edge != b.edge ? a.edge < b.edge : a.t < b.t; });
  std::vector<Vec2> pts;
  std::vector<int> new_index(n);
  std::map<int, Vec2> fixed;
  Index next_insert = 0;
  for (Index k = 0; k < n; ++k) {
    new_index[k] = static_cast<int>(pts.size());
    if (!removed[k]) pts.push_back(cs.pts[k]);
    while (next_insert < inserts.size() && static_cast<Index>(inserts[next_insert].edge) == k) {
      const auto& ins = inserts[next_insert++];
      const Vec2 p = cs.pts[k] + ins.t * (cs.pts[(k + 1) % n] - cs.pts[k]);
      if (!pts.empty() && (p == pts.back() || (k + 1 == n && p == pts.front()))) {
        // Coincides with an existing point (t rounded to an end): constrain that one instead.
        fixed[k + 1 == n && p == pts.front() ? 0 : static_cast<int>(pts.size() - 1)] = ins.target;
        continue;
      }
      fixed[static_cast<int>(pts.size())] = ins.target;
      pts.push_back(p);
    }
  }
  for (const auto& [v, acc] : vertex_targets)
    fixed[new_index[static_cast<Index>(v)]] = acc.first / static_cast<double>(acc.second);
  for (const auto& r : reflections) {
    if (removed[static_cast<Index>(r.vertex)]) continue;
    const int v = new_index[static_cast<Index>(r.vertex)];
    if (!fixed.count(v)) fixed[v] = r.target;
  }
  for (Index k = 0; k < n; ++k)  // dropped points have no successor
    if (removed[k]) new_index[k] = -1;
  if (pts.size() < 3) return Result<bool>::error("too few points left after merging handles");
  auto solved = deform_curve(pts, fixed, params);
  if (!solved) return solved.status();
  for (auto& oi : cs.original_index)
    if (oi >= 0) oi = new_index[static_cast<Index>(oi)];
  cs.pts = std::move(*solved);
  cs.modified = true;
  return true;
}


}  // namespace

// === Public entry points
std::vector<Vec3> required_crossings(const SectionSet& sections, const Plane& target) {
  std::vector<Vec3> out;
  const double diag = bounding_box(sections.all_points()).diagonal();
  const double eps = 1e-11 * std::max(diag, std::numeric_limits<double>::min());
  for (Index c = 0; c < sections.curves.size(); ++c) {
    const auto& cur = sections.curves[c];
    if (cur.plane < 0 || static_cast<Index>(cur.plane) >= sections.planes.size()) continue;
    const Plane& pl = sections.planes[static_cast<Index>(cur.plane)];
    if (parallel(pl, target)) continue;
    const Frame f(pl);
    std::vector<Vec2> pts;
    for (const auto& p : cur.points) pts.push_back(f.to2d(p));
    for (const auto& x : curve_crossings(static_cast<int>(c), pts, f, target, eps)) out.push_back(x.p3);
  }
  return out;
}

Result<SectionSet> sew_curves(const SectionSet& in, const SewingParams& params, SewingReport* report) {
  using R = Result<SectionSet>;
  // === Validate
  for (Index p = 0; p < in.planes.size(); ++p) {
    const auto& pl = in.planes[p];
    if (!pl.normal.allFinite() || !std::isfinite(pl.offset) || std::abs(pl.normal.norm() - 1.0) > 1e-9)
      return R::error("plane " + std::to_string(p) + " is invalid (normal must be a finite unit vector)");
  }
  for (Index c = 0; c < in.curves.size(); ++c) {
    const auto& cur = in.curves[c];
    if (cur.plane < 0 || static_cast<Index>(cur.plane) >= in.planes.size())
      return R::error("curve " + std::to_string(c) + " refers to plane " + std::to_string(cur.plane) +
                      ", which does not exist");
    if (cur.points.size() < 3) return R::error("curve " + std::to_string(c) + " has fewer than 3 points");
    for (Index i = 0; i < cur.points.size(); ++i)
      if (!cur.points[i].allFinite())
        return R::error("curve " + std::to_string(c) + " point " + std::to_string(i) + " is not finite");
  }
  SewingReport rep;
  // Refusals after matching started still hand back the first round's handle moves, so the app
  // can show which crossings were far off.
  auto fail = [&](const std::string& message) {
    if (report) {
      for (const auto& h : rep.handles) rep.max_moved = std::max(rep.max_moved, h.moved);
      *report = rep;
    }
    return R::error(message);
  };
  const double diag = bounding_box(in.all_points()).diagonal();
  if (in.curves.empty() || !(diag > 0.0)) {
    if (report) *report = rep;
    return in;
  }
  const double eps = 1e-11 * diag;
  const double match_tol = params.match_tolerance * diag;
  const double tangent_tol = params.tangent_tolerance * diag;

  std::vector<Frame> frames;
  for (const auto& pl : in.planes) frames.emplace_back(pl);
  std::vector<CurveState> state(in.curves.size());
  for (Index c = 0; c < in.curves.size(); ++c) {
    auto& cs = state[c];
    cs.plane = in.curves[c].plane;
    for (const auto& p : in.curves[c].points) cs.pts.push_back(frames[static_cast<Index>(cs.plane)].to2d(p));
    cs.original_index.resize(cs.pts.size());
    for (Index i = 0; i < cs.pts.size(); ++i) cs.original_index[i] = static_cast<int>(i);
  }
  std::vector<int> planes_used;
  for (Index p = 0; p < in.planes.size(); ++p)
    for (const auto& cs : state)
      if (cs.plane == static_cast<int>(p)) {
        planes_used.push_back(static_cast<int>(p));
        break;
      }

  // Common points of three planes holding curves (normals independent).
  struct TriplePoint {
    std::array<int, 3> planes;
    Vec3 point;
  };
  std::vector<TriplePoint> triple_points;
  for (Index i = 0; i < planes_used.size(); ++i)
    for (Index j = i + 1; j < planes_used.size(); ++j)
      for (Index k = j + 1; k < planes_used.size(); ++k) {
        const std::array<int, 3> ids{planes_used[i], planes_used[j], planes_used[k]};
        Eigen::Matrix3d M;
        Vec3 rhs;
        for (int r = 0; r < 3; ++r) {
          M.row(r) = in.planes[static_cast<Index>(ids[static_cast<Index>(r)])].normal.transpose();
          rhs[r] = in.planes[static_cast<Index>(ids[static_cast<Index>(r)])].offset;
        }
        if (std::abs(M.determinant()) < 1e-6) continue;
        triple_points.push_back({ids, M.partialPivLu().solve(rhs)});
      }
  const double common_radius = params.common_point_radius * diag;

  bool converged = false;
  std::vector<Vec3> shared;
  double worst_gap = 0.0;
  std::string worst_where;
  for (int iter = 0; iter <= params.max_iterations; ++iter) {
    // === Match every pair of non-parallel planes holding curves
    std::vector<std::vector<HandleRequest>> handles(state.size());
    std::vector<std::vector<Reflection>> reflections(state.size());
    std::vector<bool> active(state.size(), false);
    shared.clear();
    worst_gap = 0.0;
    int grazes = 0;
    for (Index ia = 0; ia < planes_used.size(); ++ia) {
      for (Index ib = ia + 1; ib < planes_used.size(); ++ib) {
        const int pa = planes_used[ia], pb = planes_used[ib];
        const Plane& A = in.planes[static_cast<Index>(pa)];
        const Plane& B = in.planes[static_cast<Index>(pb)];
        if (parallel(A, B)) continue;
        auto m = match_planes(in, state, frames, pa, pb, eps, tangent_tol);
        if (!m) {
          if (iter == 0) return fail(m.message());
          double far = 0.0;
          for (const auto& h : rep.handles) far = std::max(far, h.moved);
          return fail("the curves are too far off to sew (a crossing would move " + num(far) +
                      "); sewing made new crossings: " + m.message());
        }
        const Line2 la = line_in(frames[static_cast<Index>(pa)], B);
        const Line2 lb = line_in(frames[static_cast<Index>(pb)], A);
        for (const auto& [ca, cb] : m->matched) {
          Vec3 mid = 0.5 * (ca.p3 + cb.p3);
          // Near the common point of Pa, Pb and a third plane with curves, the shared point is that
          // common point: independent midpoints on the three lines through it would ask a curve
          // to cross its two lines on the wrong sides of each other.
          for (const auto& tp : triple_points)
            if ((tp.planes[0] == pa || tp.planes[1] == pa || tp.planes[2] == pa) &&
                (tp.planes[0] == pb || tp.planes[1] == pb || tp.planes[2] == pb) && (mid - tp.point).norm() <= common_radius) {
              mid = tp.point;
              break;
            }
          const double gap = std::max((ca.p3 - mid).norm(), (cb.p3 - mid).norm());
          shared.push_back(mid);
          if (gap > worst_gap) {
            worst_gap = gap;
            worst_where = "curves " + std::to_string(ca.curve) + " and " + std::to_string(cb.curve) + " near " + fmt3(mid);
          }
          const Vec2 ta = la.project(frames[static_cast<Index>(pa)].to2d(mid));
          const Vec2 tb = lb.project(frames[static_cast<Index>(pb)].to2d(mid));
          handles[static_cast<Index>(ca.curve)].push_back({ca, ta, pb});
          handles[static_cast<Index>(cb.curve)].push_back({cb, tb, pa});
          if (gap > match_tol) {
            active[static_cast<Index>(ca.curve)] = active[static_cast<Index>(cb.curve)] = true;
            if (iter == 0) {
              rep.handles.push_back({ca.curve, pb, ca.p3, mid, (mid - ca.p3).norm()});
              rep.handles.push_back({cb.curve, pa, cb.p3, mid, (mid - cb.p3).norm()});
            }
          }
        }
        // Near-tangent pairs: push the shallow arc back across the plane (mirror it in L).
        for (const auto& [c0, c1] : m->grazes) {
          ++grazes;
          const auto curve = static_cast<Index>(c0.curve);
          const auto& cs = state[curve];
          const Line2 l = cs.plane == pa ? la : lb;
          const Index n = cs.pts.size();
          const Index begin = static_cast<Index>(c1.arc_begin);
          const Index end = c1.at_vertex ? static_cast<Index>(c1.vertex) : (static_cast<Index>(c1.edge) + 1) % n;
          for (Index k = begin; k != end; k = (k + 1) % n) {
            const double dist = std::abs(l.g.dot(cs.pts[k]) - l.c);
            if (dist > eps) reflections[curve].push_back({static_cast<int>(k), l.reflect(cs.pts[k])});
          }
          active[curve] = true;
        }
      }
    }
    if (iter == 0) rep.tangents_removed = grazes;
    bool any = false;
    for (Index c = 0; c < state.size(); ++c) any = any || active[c];
    if (!any) {
      converged = true;
      rep.iterations = iter;
      break;
    }
    if (iter == params.max_iterations) break;
    // === Deform every curve once with all its handles
    for (Index c = 0; c < state.size(); ++c) {
      if (!active[c]) continue;
      auto ok = apply_handles(state[c], handles[c], reflections[c], params, match_tol);
      if (!ok) return fail("curve " + std::to_string(c) + ": " + ok.message());
    }
  }
  if (!converged)
    return fail("curve sewing did not converge: " + worst_where + " still differ by " + num(worst_gap));

  // === Rule 3 must survive sewing: no new self-crossings or crossings between curves on one plane
  std::vector<std::vector<Vec2>> before(state.size());
  for (Index c = 0; c < state.size(); ++c) {
    if (!state[c].modified) continue;
    const Frame& f = frames[static_cast<Index>(state[c].plane)];
    for (const auto& p : in.curves[c].points) before[c].push_back(f.to2d(p));
    if (!first_self_crossing(before[c]))
      if (auto x = first_self_crossing(state[c].pts))
        return fail("sewing would make curve " + std::to_string(c) + " cross itself at " + fmt3(f.to3d(*x)) +
                        "; redraw it closer to the highlighted points");
  }
  for (Index c = 0; c < state.size(); ++c)
    for (Index d = c + 1; d < state.size(); ++d) {
      if (state[c].plane != state[d].plane || (!state[c].modified && !state[d].modified)) continue;
      const Frame& f = frames[static_cast<Index>(state[c].plane)];
      auto old_pts = [&](Index k) {
        std::vector<Vec2> v;
        for (const auto& p : in.curves[k].points) v.push_back(f.to2d(p));
        return v;
      };
      const auto oc = old_pts(c), od = old_pts(d);
      if (first_crossing_between(oc, od)) continue;
      if (auto x = first_crossing_between(state[c].pts, state[d].pts))
        return fail("sewing would make curves " + std::to_string(c) + " and " + std::to_string(d) +
                        " cross at " + fmt3(f.to3d(*x)) + "; redraw them closer to the highlighted points");
      // Nesting (rule 2) must not change either: one curve passing over the other entirely.
      if (point_in_polygon_2d(od[0], oc) != point_in_polygon_2d(state[d].pts[0], state[c].pts) ||
          point_in_polygon_2d(oc[0], od) != point_in_polygon_2d(state[c].pts[0], state[d].pts))
        return fail("sewing would change whether curves " + std::to_string(c) + " and " + std::to_string(d) +
                        " are nested; redraw them closer to the highlighted points");
    }

  // === Output
  SectionSet out = in;
  for (Index c = 0; c < state.size(); ++c) {
    const auto& cs = state[c];
    if (!cs.modified) continue;
    const Frame& f = frames[static_cast<Index>(cs.plane)];
    std::vector<Vec3> pts;
    pts.reserve(cs.pts.size());
    for (const auto& p : cs.pts) pts.push_back(f.to3d(p));
    for (Index i = 0; i < cs.original_index.size(); ++i)
      if (cs.original_index[i] >= 0)
        rep.max_displacement = std::max(rep.max_displacement,
                                      (pts[static_cast<Index>(cs.original_index[i])] - in.curves[c].points[i]).norm());
    out.curves[c].points = std::move(pts);
  }
  for (const auto& h : rep.handles) rep.max_moved = std::max(rep.max_moved, h.moved);
  rep.crossings = std::move(shared);
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace ps
