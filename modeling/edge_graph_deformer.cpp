#include "modeling/edge_graph_deformer.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "modeling/anderson_acceleration.h"
#include "modeling/edge_graph.h"
#include "modeling/parallel_over.h"
#include "modeling/rotation_fit.h"

namespace ps {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using MatX3Col = Eigen::Matrix<double, Eigen::Dynamic, 3>;
using SpRow = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using SpCol = Eigen::SparseMatrix<double, Eigen::ColMajor>;

constexpr std::size_t kGrain = 512;
constexpr int kMaxAndersonWindow = 64;

// === Parallel loops
// TBB's parallel_for / parallel_reduce, except in ThreadSanitizer builds: Debian's libtbb is not
// instrumented, so its internal hand-offs are invisible to TSan and every task would look racy
// (parallel_over.h). There the range is cut into chunks of its grain size, run by parallel_over
// (std::threads taking chunk indices from an atomic counter in those builds), so what TSan
// reports is about the loop bodies and the state they share. A reduction keeps one partial per
// chunk and joins them in chunk order (deterministic too, though not the same order as TBB's
// deterministic reduce).
#if defined(__SANITIZE_THREAD__)
template <class Index>
std::vector<tbb::blocked_range<Index>> chunks_of(const tbb::blocked_range<Index>& all) {
  std::vector<tbb::blocked_range<Index>> out;
  const Index step = static_cast<Index>(std::max<std::size_t>(1, all.grainsize()));
  for (Index b = all.begin(); b < all.end(); b = b + std::min(step, all.end() - b))
    out.emplace_back(b, b + std::min(step, all.end() - b));
  return out;
}

#endif

template <class Index, class Body>
void parallel_loop(const tbb::blocked_range<Index>& all, const Body& body) {
#if defined(__SANITIZE_THREAD__)
  const auto chunks = chunks_of(all);
  parallel_over(chunks.size(), 0, [&](std::size_t i) { body(chunks[i]); });
#else
  tbb::parallel_for(all, body);
#endif
}

// body(range, acc) -> acc + the range's share; join(a, b) -> a + b; identity: the identity.
template <class Index, class Body, class Join>
double parallel_sum(const tbb::blocked_range<Index>& all, double identity, const Body& body, const Join& join) {
#if defined(__SANITIZE_THREAD__)
  const auto chunks = chunks_of(all);
  std::vector<double> partial(chunks.size(), identity);
  parallel_over(chunks.size(), 0, [&](std::size_t i) { partial[i] = body(chunks[i], identity); });
  double total = identity;
  for (double p : partial) total = join(total, p);
  return total;
#else
  // Deterministic: parallel_reduce's auto partitioner splits the range by work stealing, so the
  // order of the floating-point additions, hence the last bits of the energy, varied with the
  // machine's load; an energy change near the tolerance then stopped the iterations one step
  // apart, and the same replayed deformation was not bit-identical run to run (seen once in
  // app_deform_replay_test on a loaded machine). This one splits down to the grain size in a
  // fixed way and joins in a fixed order, whatever the threads do.
  return tbb::parallel_deterministic_reduce(all, identity, body, join);
#endif
}

// out = m * in.middleRows(offset, m.cols()) for a row-major sparse m and a dense n x 3 `in`,
// rows in parallel. `Out` is resized to m.rows() x 3.
template <class Out>
void parallel_product(const SpRow& m, const MatX3& in, Eigen::Index offset, Out& out) {
  out.resize(m.rows(), 3);
  parallel_loop(tbb::blocked_range<Eigen::Index>(0, m.rows(), kGrain), [&](const auto& range) {
    for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
      Eigen::RowVector3d acc = Eigen::RowVector3d::Zero();
      for (SpRow::InnerIterator it(m, r); it; ++it) acc += it.value() * in.row(offset + it.col());
      out.row(r) = acc;
    }
  });
}


// === Sparse assembly helpers (set_region)
struct RowEntry {
  int v;
  double c;
};

void add_to_row(std::vector<RowEntry>& row, int v, double c) {
  for (auto& e : row)
    if (e.v == v) {
      e.c += c;
      return;
    }
  row.push_back({v, c});
}

// Compressed storage written outer slice by outer slice (rows of a row-major matrix, columns of
// a column-major one), inner indices ascending within a slice.
struct CsrBuilder {
  std::vector<int> outer, inner;
  std::vector<double> values;
  void start(int n_outer, std::size_t reserve) {
    outer.assign(1, 0);
    outer.reserve(static_cast<std::size_t>(n_outer) + 1);
    inner.clear();
    values.clear();
    inner.reserve(reserve);
    values.reserve(reserve);
  }
  void push(int index, double value) {
    inner.push_back(index);
    values.push_back(value);
  }
  void end_row() { outer.push_back(static_cast<int>(inner.size())); }
  template <class Sparse>
  void finish(Sparse& out, int rows, int cols) const {
    out.resize(rows, cols);
    out.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
    std::copy(outer.begin(), outer.end(), out.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), out.innerIndexPtr());
    std::copy(values.begin(), values.end(), out.valuePtr());
  }
};
}  // namespace

struct EdgeGraphDeformer::Impl {
  // === Mesh state (set_mesh)
  TriMesh mesh;
  std::vector<Vec3> current;
  MeshEdges edges;
  std::vector<int> adj_offsets, adj;  // vertex adjacency (CSR)
  std::optional<DeformGraph> graphs[2];
  double graph_ms[2] = {0, 0};
  double connectivity_ms = 0;

  // === Region state (set_region)
  bool has_region = false;
  DeformParameters params;
  std::vector<int> handles;
  std::vector<int> global_of;  // local -> global; free first, then handles, then statics
  int n_free = 0, n_known = 0;

  struct Node {
    std::array<int, 2> v;  // local vertex ids
    std::array<double, 2> c;
    int arc_begin = 0, arc_end = 0;
    int face_begin = 0, face_end = 0;  // into node_faces
    Vec3 delta = Vec3::Zero();  // rest Laplacian (Eq. 5.1)
    Vec3 normal = Vec3::Zero();  // rest normal (unit) of the incident faces
    double normal_weight = 0.0;  // weight of the normal in the rotation fit
    double rest_norm = 0.0;      // sum_j w+_ij |e_ij|^2, the denominator of the optimal scale
  };
  std::vector<Node> nodes;
  std::vector<std::array<int, 2>> arc_v;
  std::vector<std::array<double, 2>> arc_c;
  std::vector<double> arc_w_plus;
  std::vector<double> arc_w;  // signed w_ij (Laplacian)
  std::vector<Vec3> arc_rest;
  std::vector<Vec3> arc_wrest;  // w+_ij e_ij, the arc's share of the covariance
  std::vector<int> node_faces;                 // into ref_faces
  std::vector<Eigen::Quaterniond> rot;         // R_i of the last local step, per node
  // Nodes and faces the local step reads (active nodes first, then their other neighbours), and
  // their current positions / area-weighted normals, computed once per local step.
  std::vector<std::array<int, 2>> ref_v;
  std::vector<std::array<double, 2>> ref_c;
  std::vector<int> arc_ref;                    // neighbour node of each arc, into ref_v
  std::vector<std::array<int, 3>> ref_faces;   // local vertex ids
  MatX3 ypos, fnorm;
  Eigen::VectorXd row_weight;
  SpRow jf, jk, m_rhs;  // m x n_free, m x n_known, n_free x m (= J_f^T W)
  SpRow afk;            // n_free x n_known
  Eigen::SimplicialLDLT<SpCol, Eigen::Lower, Eigen::AMDOrdering<int>> solver;
  MatX3 x;              // n_free + n_known rows (local order)
  MatX3 t, t_rest;      // m x 3 targets; identity-transform targets
  DeformStats stats;

  int rows() const { return static_cast<int>(arc_v.size() + nodes.size()); }

  const DeformGraph& graph(DeformDomain d) {
    const int k = d == DeformDomain::kEdgeGraph ? 0 : 1;
    if (!graphs[k]) {
      const auto t0 = Clock::now();
      graphs[k] = d == DeformDomain::kEdgeGraph ? build_edge_graph(mesh, edges)
                                                : build_primal_graph(mesh, edges);
      graph_ms[k] = ms_since(t0);
    }
    return *graphs[k];
  }

  Eigen::RowVector3d node_pos(const std::array<int, 2>& v, const std::array<double, 2>& c) const {
    return c[0] * x.row(v[0]) + c[1] * x.row(v[1]);
  }

  void compute_positions() {
    ypos.resize(static_cast<Eigen::Index>(ref_v.size()), 3);
    fnorm.resize(static_cast<Eigen::Index>(ref_faces.size()), 3);
    auto positions = [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t r = range.begin(); r != range.end(); ++r) ypos.row(static_cast<Eigen::Index>(r)) = node_pos(ref_v[r], ref_c[r]);
    };
    auto normals = [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t f = range.begin(); f != range.end(); ++f) {
        const auto& tri = ref_faces[f];
        const Vec3 p0 = x.row(tri[0]).transpose();
        fnorm.row(static_cast<Eigen::Index>(f)) =
            (Vec3(x.row(tri[1]).transpose()) - p0).cross(Vec3(x.row(tri[2]).transpose()) - p0).transpose();
      }
    };
    // A few flops per row: below kSerialRows rows a parallel loop costs more in hand-overs
    // (waking the other thread, twice per local step) than it saves.
    constexpr std::size_t kSerialRows = 16384;
    if (ref_v.size() < kSerialRows) positions(tbb::blocked_range<std::size_t>(0, ref_v.size()));
    else parallel_loop(tbb::blocked_range<std::size_t>(0, ref_v.size(), 1024), positions);
    if (ref_faces.size() < kSerialRows) normals(tbb::blocked_range<std::size_t>(0, ref_faces.size()));
    else parallel_loop(tbb::blocked_range<std::size_t>(0, ref_faces.size(), 1024), normals);
  }

  // Unit normal of the node's faces (after compute_positions).
  Vec3 normal_of(const Node& nd) const {
    Vec3 n = Vec3::Zero();
    for (int f = nd.face_begin; f < nd.face_end; ++f) n += fnorm.row(node_faces[static_cast<std::size_t>(f)]).transpose();
    const double len = n.norm();
    return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
  }

  // === Local step: R_i (Eq. 5.5 with the reflection fix), s_i, and the targets t.
  // Returns the energy at the current positions with the new transforms, sum W |J x - t|^2,
  // computed from the node's own edge vectors (J x is e' for a 1-form row and
  // sum_j w_ij e'_ij for a Laplacian row), so no extra sparse product is needed.
  double local_step() {
    const int n_arcs = static_cast<int>(arc_v.size());
    compute_positions();
    return parallel_sum(
        tbb::blocked_range<std::size_t>(0, nodes.size(), 256), 0.0,
        [&](const auto& range, double energy_acc) {
          for (std::size_t a = range.begin(); a != range.end(); ++a) {
            const Node& nd = nodes[a];
            const Eigen::RowVector3d yi = ypos.row(static_cast<Eigen::Index>(a));
            Eigen::Matrix3d s_cov = Eigen::Matrix3d::Zero();
            constexpr int kCache = 16;
            Vec3 cache[kCache];
            Vec3 lap_new = Vec3::Zero();
            for (int k = nd.arc_begin; k < nd.arc_end; ++k) {
              const auto ku = static_cast<std::size_t>(k);
              const Vec3 e_new = (yi - ypos.row(arc_ref[ku])).transpose();
              if (k - nd.arc_begin < kCache) cache[k - nd.arc_begin] = e_new;
              s_cov.noalias() += arc_wrest[ku] * e_new.transpose();
              lap_new += arc_w[ku] * e_new;
            }
            // The node's normal joins the fit so a node whose 1-form spans less than a plane
            // (boundary nodes with one positive weight) still gets a unique rotation.
            const Vec3 n_new = normal_of(nd);
            s_cov += nd.normal_weight * nd.normal * n_new.transpose();
            // Warm-started from the node's rotation of the previous local step (rotation_fit.h).
            const Eigen::Matrix3d r = fit_rotation_from(s_cov, rot[a]);
            double num = 0.0;
            const double den = nd.rest_norm;
            for (int k = nd.arc_begin; k < nd.arc_end; ++k) {
              const auto ku = static_cast<std::size_t>(k);
              const Vec3 re = r * arc_rest[ku];
              const Vec3 e_new = k - nd.arc_begin < kCache ? cache[k - nd.arc_begin]
                                                           : Vec3((yi - ypos.row(arc_ref[ku])).transpose());
              num += arc_w_plus[ku] * e_new.dot(re);
              t.row(k) = re.transpose();
              energy_acc += row_weight[k] * (e_new - re).squaredNorm();
            }
            const double s = den > 0.0 ? std::clamp(num / den, 0.01, 100.0) : 1.0;
            const Vec3 target = s * (r * nd.delta);
            const Eigen::Index lap_row = n_arcs + static_cast<Eigen::Index>(a);
            t.row(lap_row) = target.transpose();
            energy_acc += row_weight[lap_row] * (lap_new - target).squaredNorm();
          }
          return energy_acc;
        },
        [](double x1, double x2) { return x1 + x2; });
  }

  // === Global step: A x_f = J_f^T W t - A_fk x_k.
  // Known-vertex parts, recomputed when the handles move: A_fk x_k and J_k x_k.
  MatX3 afk_xk;
  MatX3 jk_xk;
  void known_parts() {
    parallel_product(afk, x, n_free, afk_xk);
    parallel_product(jk, x, n_free, jk_xk);
  }

  void global_step() {
    if (n_free == 0) return;
    MatX3 b;
    parallel_product(m_rhs, t, 0, b);
    b -= afk_xk;
    solve_in_place(b);
    x.topRows(n_free) = b;
  }

  // A^-1 b for the n_free x 3 right-hand side b, in place, from the LDLT factors
  // (P A P^T = L D L^T). Eigen's SimplicialLDLT::solve runs each triangular solve once per
  // right-hand-side column; with b in row-major order one pass over L serves all three
  // coordinates, so L is read twice per solve instead of six times.
  std::vector<double> permuted;
  void solve_in_place(MatX3& b) {
    const SpCol& l = solver.matrixL().nestedExpression();  // strictly lower part, unit diagonal
    const auto& d = solver.vectorD();
    const auto& perm = solver.permutationP().indices();
    const Eigen::Index n = b.rows();
    // Raw compressed storage: Eigen's LDLT keeps L compressed, one column per outer slice,
    // the diagonal not stored (it is 1); z is n x 3, row-major.
    const int* outer = l.outerIndexPtr();
    const int* inner = l.innerIndexPtr();
    const double* val = l.valuePtr();
    permuted.resize(static_cast<std::size_t>(n) * 3);
    double* z = permuted.data();
    const double* bp = b.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      double* zi = z + 3 * perm(i);
      zi[0] = bp[3 * i], zi[1] = bp[3 * i + 1], zi[2] = bp[3 * i + 2];
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      const double z0 = z[3 * j], z1 = z[3 * j + 1], z2 = z[3 * j + 2];
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        double* zi = z + 3 * inner[p];
        const double v = val[p];
        zi[0] -= v * z0, zi[1] -= v * z1, zi[2] -= v * z2;
      }
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      const double dj = d(j);
      z[3 * j] /= dj, z[3 * j + 1] /= dj, z[3 * j + 2] /= dj;
    }
    for (Eigen::Index j = n - 1; j >= 0; --j) {
      double a0 = z[3 * j], a1 = z[3 * j + 1], a2 = z[3 * j + 2];
      for (int p = outer[j]; p < outer[j + 1]; ++p) {
        const double* zi = z + 3 * inner[p];
        const double v = val[p];
        a0 -= v * zi[0], a1 -= v * zi[1], a2 -= v * zi[2];
      }
      z[3 * j] = a0, z[3 * j + 1] = a1, z[3 * j + 2] = a2;
    }
    double* out = b.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* zi = z + 3 * perm(i);
      out[3 * i] = zi[0], out[3 * i + 1] = zi[1], out[3 * i + 2] = zi[2];
    }
  }

  double energy() const {
    if (n_free == 0) return 0.0;
    MatX3 jx;
    parallel_product(jf, x, 0, jx);
    return parallel_sum(
        tbb::blocked_range<Eigen::Index>(0, jx.rows(), kGrain), 0.0,
        [&](const auto& range, double acc) {
          for (Eigen::Index r = range.begin(); r != range.end(); ++r)
            acc += row_weight[r] * (jx.row(r) + jk_xk.row(r) - t.row(r)).squaredNorm();
          return acc;
        },
        [](double a, double b) { return a + b; });
  }

  Status place_handles(const std::vector<Vec3>& targets) {
    if (!has_region) return Status::error("deformation: no region set (call set_region first)");
    if (targets.size() != handles.size())
      return Status::error("deformation: " + std::to_string(targets.size()) + " handle positions for " +
                           std::to_string(handles.size()) + " handles");
    for (std::size_t h = 0; h < targets.size(); ++h)
      if (!targets[h].allFinite())
        return Status::error("deformation: handle " + std::to_string(h) + " has a non-finite position");
    for (std::size_t h = 0; h < targets.size(); ++h)
      x.row(n_free + static_cast<Eigen::Index>(h)) = targets[h].transpose();
    known_parts();
    return Status::ok();
  }

  void write_back(const std::vector<Vec3>& targets) {
    for (int l = 0; l < n_free; ++l) current[static_cast<std::size_t>(global_of[static_cast<std::size_t>(l)])] = x.row(l).transpose();
    double res = 0.0;
    for (std::size_t h = 0; h < handles.size(); ++h) {
      current[static_cast<std::size_t>(handles[h])] = targets[h];
      res = std::max(res, (x.row(n_free + static_cast<Eigen::Index>(h)).transpose() - targets[h]).norm());
    }
    stats.max_handle_residual = res;
  }
};

EdgeGraphDeformer::EdgeGraphDeformer() : impl_(std::make_unique<Impl>()) {}
EdgeGraphDeformer::~EdgeGraphDeformer() = default;
EdgeGraphDeformer::EdgeGraphDeformer(EdgeGraphDeformer&&) noexcept = default;
EdgeGraphDeformer& EdgeGraphDeformer::operator=(EdgeGraphDeformer&&) noexcept = default;

Status EdgeGraphDeformer::set_mesh(const TriMesh& mesh) {
  const auto t0 = Clock::now();
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      return Status::error("vertex " + std::to_string(v) + " has a non-finite coordinate");
  auto edges = mesh_edges(mesh);
  if (!edges) return edges.status();
  auto fresh = std::make_unique<Impl>();
  fresh->mesh = mesh;
  fresh->current = mesh.vertices;
  fresh->edges = std::move(edges.value());
  const std::size_t nv = mesh.vertices.size();
  fresh->adj_offsets.assign(nv + 1, 0);
  for (const auto& e : fresh->edges.edges) {
    ++fresh->adj_offsets[static_cast<std::size_t>(e[0]) + 1];
    ++fresh->adj_offsets[static_cast<std::size_t>(e[1]) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) fresh->adj_offsets[v + 1] += fresh->adj_offsets[v];
  fresh->adj.resize(static_cast<std::size_t>(fresh->adj_offsets[nv]));
  std::vector<int> fill(fresh->adj_offsets.begin(), fresh->adj_offsets.end() - 1);
  for (const auto& e : fresh->edges.edges) {
    fresh->adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
    fresh->adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
  }
  fresh->connectivity_ms = ms_since(t0);
  impl_ = std::move(fresh);
  return Status::ok();
}

Status EdgeGraphDeformer::set_region(const std::vector<int>& roi, const std::vector<int>& handles,
                                     const DeformParameters& p) {
  Impl& s = *impl_;
  const auto t0 = Clock::now();
  const int nv = static_cast<int>(s.mesh.vertices.size());
  if (nv == 0) return Status::error("deformation: no mesh set (call set_mesh first)");
  // === Validate
  if (!(p.lambda >= 0.0 && p.lambda <= 1.0))
    return Status::error("lambda: " + std::to_string(p.lambda) + " is outside [0, 1]");
  if (!p.vertex_lambda.empty()) {
    if (p.vertex_lambda.size() != s.mesh.vertices.size())
      return Status::error("lambda_per_vertex: " + std::to_string(p.vertex_lambda.size()) +
                           " values for " + std::to_string(nv) + " vertices");
    for (std::size_t v = 0; v < p.vertex_lambda.size(); ++v) {
      const double l = p.vertex_lambda[v];
      if (!std::isnan(l) && !(l >= 0.0 && l <= 1.0))
        return Status::error("lambda_per_vertex[" + std::to_string(v) + "]: " + std::to_string(l) +
                             " is outside [0, 1]");
    }
  }
  if (p.max_iterations < 0) return Status::error("max_iterations: must be >= 0");
  if (!(p.tolerance >= 0.0) || !std::isfinite(p.tolerance))
    return Status::error("tolerance: must be a finite number >= 0");
  // The history is 2 x window vectors of 3 x #free doubles; past a few dozen it costs memory
  // and time and gains nothing (Peng et al. use 5-6).
  if (p.anderson_window < 0 || p.anderson_window > kMaxAndersonWindow)
    return Status::error("anderson_window: " + std::to_string(p.anderson_window) + " is outside [0, " +
                         std::to_string(kMaxAndersonWindow) + "]");
  enum : char { kStatic = 0, kFree = 1, kHandle = 2 };
  std::vector<char> kind(static_cast<std::size_t>(nv), kStatic);
  for (std::size_t k = 0; k < handles.size(); ++k) {
    const int h = handles[k];
    if (h < 0 || h >= nv)
      return Status::error("handles[" + std::to_string(k) + "]: vertex " + std::to_string(h) +
                           " out of range (mesh has " + std::to_string(nv) + " vertices)");
    if (kind[static_cast<std::size_t>(h)] == kHandle)
      return Status::error("handles[" + std::to_string(k) + "]: vertex " + std::to_string(h) +
                           " is listed twice");
    kind[static_cast<std::size_t>(h)] = kHandle;
  }
  for (std::size_t k = 0; k < roi.size(); ++k) {
    const int v = roi[k];
    if (v < 0 || v >= nv)
      return Status::error("roi[" + std::to_string(k) + "]: vertex " + std::to_string(v) +
                           " out of range (mesh has " + std::to_string(nv) + " vertices)");
    if (kind[static_cast<std::size_t>(v)] != kHandle) kind[static_cast<std::size_t>(v)] = kFree;
  }
  // A free part that touches no fixed vertex has no unique solution (translation).
  {
    std::vector<char> seen(static_cast<std::size_t>(nv), 0);
    std::vector<int> stack;
    for (int v0 = 0; v0 < nv; ++v0) {
      if (kind[static_cast<std::size_t>(v0)] != kFree || seen[static_cast<std::size_t>(v0)]) continue;
      bool anchored = false;
      stack.assign(1, v0);
      seen[static_cast<std::size_t>(v0)] = 1;
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        for (int k = s.adj_offsets[static_cast<std::size_t>(v)]; k < s.adj_offsets[static_cast<std::size_t>(v) + 1]; ++k) {
          const int w = s.adj[static_cast<std::size_t>(k)];
          if (kind[static_cast<std::size_t>(w)] != kFree) {
            anchored = true;
          } else if (!seen[static_cast<std::size_t>(w)]) {
            seen[static_cast<std::size_t>(w)] = 1;
            stack.push_back(w);
          }
        }
      }
      if (!anchored)
        return Status::error("roi: vertex " + std::to_string(v0) +
                             " lies in a part of the mesh with no handle or static vertex");
    }
  }

  const DeformGraph& g = s.graph(p.domain);
  s.params = p;
  s.handles = handles;
  s.has_region = false;
  s.current = s.mesh.vertices;
  DeformStats st;
  st.clamped_cotangents = g.clamped_cotangents;
  st.degenerate_triangles = g.degenerate_triangles;
  st.floored_areas = g.floored_areas;
  st.mesh_ms = s.connectivity_ms + s.graph_ms[p.domain == DeformDomain::kEdgeGraph ? 0 : 1];

  // === Local vertex numbering: free, then handles, then statics met in stencils.
  std::vector<int> local_of(static_cast<std::size_t>(nv), -1);
  s.global_of.clear();
  for (int v = 0; v < nv; ++v)
    if (kind[static_cast<std::size_t>(v)] == kFree) {
      local_of[static_cast<std::size_t>(v)] = static_cast<int>(s.global_of.size());
      s.global_of.push_back(v);
    }
  s.n_free = static_cast<int>(s.global_of.size());
  for (int h : handles) {
    local_of[static_cast<std::size_t>(h)] = static_cast<int>(s.global_of.size());
    s.global_of.push_back(h);
  }
  // Active nodes: nodes whose stencil (own and neighbours' vertices) has a free vertex.
  const std::size_t n_nodes = g.num_nodes();
  std::vector<int> active;
  for (std::size_t i = 0; i < n_nodes; ++i) {
    bool touches = false;
    auto check = [&](std::size_t node) {
      for (std::size_t k = 0; k < 2; ++k)
        if (kind[static_cast<std::size_t>(g.node_vertices[node][k])] == kFree) touches = true;
    };
    check(i);
    for (int k = g.offsets[i]; k < g.offsets[i + 1] && !touches; ++k)
      check(static_cast<std::size_t>(g.neighbors[static_cast<std::size_t>(k)]));
    if (touches) active.push_back(static_cast<int>(i));
  }
  auto local = [&](int v) {
    int& l = local_of[static_cast<std::size_t>(v)];
    if (l < 0) {
      l = static_cast<int>(s.global_of.size());
      s.global_of.push_back(v);
    }
    return l;
  };
  auto node_lambda = [&](std::size_t node) {
    auto lam = [&](int v) {
      if (p.vertex_lambda.empty()) return p.lambda;
      const double l = p.vertex_lambda[static_cast<std::size_t>(v)];
      return std::isnan(l) ? p.lambda : l;
    };
    const auto& nvtx = g.node_vertices[node];
    const auto& c = g.node_coef[node];
    // 5.4: an edge-graph node takes the mean of its two end vertices.
    return c[1] == 0.0 ? lam(nvtx[0]) : 0.5 * (lam(nvtx[0]) + lam(nvtx[1]));
  };

  // === Rows of J (Eq. 5.7 with D folded in) and their weights.
  s.nodes.clear();
  s.arc_v.clear();
  s.arc_c.clear();
  s.arc_w_plus.clear();
  s.arc_w.clear();
  s.arc_rest.clear();
  s.arc_wrest.clear();
  s.node_faces.clear();
  s.ref_v.clear();
  s.ref_c.clear();
  s.arc_ref.clear();
  s.ref_faces.clear();
  {
    std::size_t n_arcs_est = 0, n_faces_est = 0;
    for (int i : active) {
      const auto iu = static_cast<std::size_t>(i);
      n_arcs_est += static_cast<std::size_t>(g.offsets[iu + 1] - g.offsets[iu]);
      n_faces_est += static_cast<std::size_t>(g.face_offsets[iu + 1] - g.face_offsets[iu]);
    }
    s.nodes.reserve(active.size());
    s.arc_v.reserve(n_arcs_est);
    s.arc_c.reserve(n_arcs_est);
    s.arc_ref.reserve(n_arcs_est);
    s.arc_w_plus.reserve(n_arcs_est);
    s.arc_w.reserve(n_arcs_est);
    s.arc_rest.reserve(n_arcs_est);
    s.arc_wrest.reserve(n_arcs_est);
    s.node_faces.reserve(n_faces_est);
    s.ref_v.reserve(active.size() * 2);
    s.ref_c.reserve(active.size() * 2);
    s.ref_faces.reserve(n_faces_est);
  }
  std::vector<int> ref_of(n_nodes, -1), face_ref(s.mesh.faces.size(), -1);
  auto ref = [&](std::size_t node) {
    int& r = ref_of[node];
    if (r < 0) {
      r = static_cast<int>(s.ref_v.size());
      s.ref_v.push_back({local(g.node_vertices[node][0]), local(g.node_vertices[node][1])});
      s.ref_c.push_back(g.node_coef[node]);
    }
    return r;
  };
  for (int i : active) ref(static_cast<std::size_t>(i));  // active node a has ref index a
  std::vector<double> lambdas;
  double area_sum = 0.0;
  for (int i : active) {
    const auto iu = static_cast<std::size_t>(i);
    Impl::Node nd;
    nd.v = {local(g.node_vertices[iu][0]), local(g.node_vertices[iu][1])};
    nd.c = g.node_coef[iu];
    nd.arc_begin = static_cast<int>(s.arc_v.size());
    const Vec3 yi = nd.c[0] * s.mesh.vertices[static_cast<std::size_t>(g.node_vertices[iu][0])] +
                    nd.c[1] * s.mesh.vertices[static_cast<std::size_t>(g.node_vertices[iu][1])];
    for (int k = g.offsets[iu]; k < g.offsets[iu + 1]; ++k) {
      const auto j = static_cast<std::size_t>(g.neighbors[static_cast<std::size_t>(k)]);
      const double w = g.weight(static_cast<std::size_t>(k), iu);
      const Vec3 yj = g.node_coef[j][0] * s.mesh.vertices[static_cast<std::size_t>(g.node_vertices[j][0])] +
                      g.node_coef[j][1] * s.mesh.vertices[static_cast<std::size_t>(g.node_vertices[j][1])];
      s.arc_v.push_back({local(g.node_vertices[j][0]), local(g.node_vertices[j][1])});
      s.arc_c.push_back(g.node_coef[j]);
      s.arc_ref.push_back(ref(j));
      s.arc_w_plus.push_back(std::max(w, 0.0));
      s.arc_w.push_back(w);
      s.arc_rest.push_back(yi - yj);
      nd.delta += w * (yi - yj);  // Eq. 5.1
    }
    nd.arc_end = static_cast<int>(s.arc_v.size());
    nd.face_begin = static_cast<int>(s.node_faces.size());
    for (int k = g.face_offsets[iu]; k < g.face_offsets[iu + 1]; ++k) {
      const auto fi = static_cast<std::size_t>(g.faces[static_cast<std::size_t>(k)]);
      if (face_ref[fi] < 0) {
        const Face& f = s.mesh.faces[fi];
        face_ref[fi] = static_cast<int>(s.ref_faces.size());
        s.ref_faces.push_back({local(f[0]), local(f[1]), local(f[2])});
      }
      s.node_faces.push_back(face_ref[fi]);
    }
    nd.face_end = static_cast<int>(s.node_faces.size());
    double wl = 0.0;
    for (int k = nd.arc_begin; k < nd.arc_end; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      wl += s.arc_w_plus[ku] * s.arc_rest[ku].squaredNorm();
      s.arc_wrest.push_back(s.arc_w_plus[ku] * s.arc_rest[ku]);
    }
    nd.rest_norm = wl;
    nd.normal_weight = nd.arc_end > nd.arc_begin ? wl / (nd.arc_end - nd.arc_begin) : 0.0;
    area_sum += g.area[iu];
    lambdas.push_back(node_lambda(iu));
    s.nodes.push_back(nd);
  }
  s.n_known = static_cast<int>(s.global_of.size()) - s.n_free;
  const double area_mean = s.nodes.empty() ? 1.0 : area_sum / static_cast<double>(s.nodes.size());
  const int n_arcs = static_cast<int>(s.arc_v.size());
  const int m = s.rows();
  s.row_weight.resize(m);
  // Each row of J as a short list of (local vertex, coefficient), duplicates merged, zeros
  // dropped, sorted by vertex, written straight into J_f (free columns) and J_k (known). Arc
  // rows come in node order, so row k is arc k; the Laplacian rows follow.
  // J split by column (free | known), the right-hand-side operator M = J_f^T W, the normal
  // matrix A = J_f^T W J_f (lower triangle) and A_fk = J_f^T W J_k are written straight into
  // compressed storage. Triplets and setFromTriplets cost about 4x as much here (their sort and
  // duplicate merge over ~1M entries at 9.2k free vertices), and this is the stage that decides
  // whether a new region is interactive.
  CsrBuilder jf_b, jk_b;
  jf_b.start(m, static_cast<std::size_t>(n_arcs) * 3 + s.nodes.size() * 6);
  jk_b.start(m, 0);
  std::vector<RowEntry> row;
  auto flush_row = [&] {
    // Insertion sort: rows hold 2 to about 12 entries.
    for (std::size_t i = 1; i < row.size(); ++i)
      for (std::size_t j = i; j > 0 && row[j].v < row[j - 1].v; --j) std::swap(row[j], row[j - 1]);
    for (const auto& e : row) {
      if (e.c == 0.0) continue;
      if (e.v < s.n_free) jf_b.push(e.v, e.c);
      else jk_b.push(e.v - s.n_free, e.c);
    }
    jf_b.end_row();
    jk_b.end_row();
  };
  for (std::size_t a = 0; a < s.nodes.size(); ++a) {
    const Impl::Node& nd = s.nodes[a];
    for (int k = nd.arc_begin; k < nd.arc_end; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      // 1-form row: y_i - y_j
      row.clear();
      for (std::size_t q = 0; q < 2; ++q) {
        add_to_row(row, nd.v[q], nd.c[q]);
        add_to_row(row, s.arc_v[ku][q], -s.arc_c[ku][q]);
      }
      flush_row();
      s.row_weight[k] = lambdas[a] * s.arc_w_plus[ku];
    }
    s.row_weight[n_arcs + static_cast<Eigen::Index>(a)] = (1.0 - lambdas[a]) * area_mean;
  }
  for (std::size_t a = 0; a < s.nodes.size(); ++a) {
    // Laplacian row: sum_j w_ij (y_i - y_j)
    const Impl::Node& nd = s.nodes[a];
    row.clear();
    double wsum = 0.0;
    for (int k = nd.arc_begin; k < nd.arc_end; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      for (std::size_t q = 0; q < 2; ++q) add_to_row(row, s.arc_v[ku][q], -s.arc_w[ku] * s.arc_c[ku][q]);
      wsum += s.arc_w[ku];
    }
    for (std::size_t q = 0; q < 2; ++q) add_to_row(row, nd.v[q], wsum * nd.c[q]);
    flush_row();
  }
  jf_b.finish(s.jf, m, s.n_free);
  jk_b.finish(s.jk, m, s.n_known);
  // M = (W J_f)^T: a counting transpose of J_f, rows of zero weight left out.
  {
    std::vector<int> count(static_cast<std::size_t>(s.n_free) + 1, 0);
    for (int r = 0; r < m; ++r)
      if (s.row_weight[r] != 0.0)
        for (SpRow::InnerIterator it(s.jf, r); it; ++it) ++count[static_cast<std::size_t>(it.col()) + 1];
    for (int c = 0; c < s.n_free; ++c) count[static_cast<std::size_t>(c) + 1] += count[static_cast<std::size_t>(c)];
    s.m_rhs.resize(s.n_free, m);
    s.m_rhs.resizeNonZeros(count.back());
    std::copy(count.begin(), count.end(), s.m_rhs.outerIndexPtr());
    for (int r = 0; r < m; ++r) {
      const double w = s.row_weight[r];
      if (w == 0.0) continue;
      for (SpRow::InnerIterator it(s.jf, r); it; ++it) {
        const int slot = count[static_cast<std::size_t>(it.col())]++;
        s.m_rhs.innerIndexPtr()[slot] = r;
        s.m_rhs.valuePtr()[slot] = w * it.value();
      }
    }
  }
  // A (lower, by column) and A_fk (by row): column p of A and row p of A_fk are
  // sum over the rows r holding p of M(p, r) * (row r of J_f, resp. J_k) (Gustavson).
  SpCol a_ff;
  {
    CsrBuilder a_b, afk_b;
    a_b.start(s.n_free, static_cast<std::size_t>(s.n_free) * 16);
    afk_b.start(s.n_free, 0);
    std::vector<double> acc_f(static_cast<std::size_t>(s.n_free), 0.0), acc_k(static_cast<std::size_t>(s.n_known), 0.0);
    std::vector<int> mark_f(static_cast<std::size_t>(s.n_free), -1), mark_k(static_cast<std::size_t>(s.n_known), -1);
    std::vector<int> touched_f, touched_k;
    for (int col = 0; col < s.n_free; ++col) {
      touched_f.clear();
      touched_k.clear();
      for (SpRow::InnerIterator mt(s.m_rhs, col); mt; ++mt) {
        const auto r = mt.col();
        const double wp = mt.value();
        for (SpRow::InnerIterator it(s.jf, r); it; ++it) {
          const int q = static_cast<int>(it.col());
          if (q < col) continue;
          const auto qu = static_cast<std::size_t>(q);
          if (mark_f[qu] != col) mark_f[qu] = col, acc_f[qu] = 0.0, touched_f.push_back(q);
          acc_f[qu] += wp * it.value();
        }
        for (SpRow::InnerIterator it(s.jk, r); it; ++it) {
          const auto qu = static_cast<std::size_t>(it.col());
          if (mark_k[qu] != col) mark_k[qu] = col, acc_k[qu] = 0.0, touched_k.push_back(static_cast<int>(qu));
          acc_k[qu] += wp * it.value();
        }
      }
      std::sort(touched_f.begin(), touched_f.end());
      for (int q : touched_f) a_b.push(q, acc_f[static_cast<std::size_t>(q)]);
      a_b.end_row();
      std::sort(touched_k.begin(), touched_k.end());
      for (int q : touched_k) afk_b.push(q, acc_k[static_cast<std::size_t>(q)]);
      afk_b.end_row();
    }
    a_b.finish(a_ff, s.n_free, s.n_free);  // column p holds rows q >= p: the lower triangle
    afk_b.finish(s.afk, s.n_free, s.n_known);
  }
  // Rest positions and identity-transform targets (naive Laplacian editing).
  const int n_local = static_cast<int>(s.global_of.size());
  s.x.resize(n_local, 3);
  for (int l = 0; l < n_local; ++l)
    s.x.row(l) = s.mesh.vertices[static_cast<std::size_t>(s.global_of[static_cast<std::size_t>(l)])].transpose();
  s.compute_positions();
  for (auto& nd : s.nodes) nd.normal = s.normal_of(nd);
  s.t_rest.resize(m, 3);
  for (std::size_t a = 0; a < s.nodes.size(); ++a) {
    const Impl::Node& nd = s.nodes[a];
    for (int k = nd.arc_begin; k < nd.arc_end; ++k) s.t_rest.row(k) = s.arc_rest[static_cast<std::size_t>(k)].transpose();
    s.t_rest.row(n_arcs + static_cast<Eigen::Index>(a)) = nd.delta.transpose();
  }
  s.t = s.t_rest;
  s.rot.assign(s.nodes.size(), Eigen::Quaterniond::Identity());
  st.build_ms = ms_since(t0);
  // === Factor
  const auto t1 = Clock::now();
  if (s.n_free > 0) {
    s.solver.compute(a_ff);
    if (s.solver.info() != Eigen::Success)
      return Status::error("deformation: the system matrix could not be factored (numerical issue)");
    st.factor_nonzeros = s.solver.matrixL().nestedExpression().nonZeros();
  }
  st.factor_ms = ms_since(t1);
  st.free_vertices = s.n_free;
  st.known_vertices = s.n_known;
  st.nodes = static_cast<int>(s.nodes.size());
  st.rows = m;
  st.matrix_nonzeros = a_ff.nonZeros();
  s.stats = st;
  s.has_region = true;
  return Status::ok();
}

Status EdgeGraphDeformer::deform(const std::vector<Vec3>& targets) {
  Impl& s = *impl_;
  const auto t0 = Clock::now();
  if (Status ok = s.place_handles(targets); !ok) return ok;
  s.stats.iteration_ms.clear();
  s.stats.energies.clear();
  s.stats.converged = false;
  s.stats.iterations = 0;
  // === Initial guess: naive Laplacian editing (identity transforms).
  s.t = s.t_rest;
  s.rot.assign(s.nodes.size(), Eigen::Quaterniond::Identity());
  s.global_step();
  s.stats.initial_solve_ms = ms_since(t0);
  double e_prev = s.energy();
  s.stats.energies.push_back(e_prev);
  // === Local/global iterations until the relative energy change is below the tolerance.
  // The energy checked is the one at the start of each iteration with its new transforms,
  // E(x_{k-1}, R_k), which the local step computes for free; for lambda = 1 the sequence is
  // non-increasing. The last entry is the exact energy of the result.
  //
  // Anderson acceleration (anderson_acceleration.h) on the free vertices: after each global
  // step x_k = G(x_{k-1}) the next iterate is the accelerated one. Its safeguard depends on
  // what the alternation is:
  //   - lambda = 1 everywhere: a descent on E (the local step minimises E over the rotations,
  //     the global step over x). The next local step computes the accelerated iterate's energy,
  //     and one that does not lower it below the previous iterate's is replaced by the plain
  //     G(x_{k-1}) (one more local step; the history restarts), so E still never increases.
  //   - some lambda < 1: the scale s_i and R_i are fitted to the 1-form alone, so the
  //     alternation is a fixed-point iteration whose energy may rise on the way to its fixed
  //     point, and an energy test would refuse good steps. Its residual |G(x) - x| is the
  //     measure instead: when it grows past twice its smallest value since the last restart,
  //     the history restarts (the next iterate is the plain one).
  // The last iteration's global step is always taken as it is.
  s.stats.local_ms = s.stats.solve_ms = s.stats.energy_ms = 0;
  s.stats.accelerated_iterations = s.stats.rejected_accelerations = 0;
  const bool accelerate = s.params.anderson_window > 0 && s.n_free > 0;
  bool descent = s.params.lambda == 1.0;
  for (double l : s.params.vertex_lambda) descent = descent && (std::isnan(l) || l == 1.0);
  std::optional<AndersonAcceleration> aa;
  if (accelerate) aa.emplace(s.params.anderson_window);
  const Eigen::Index n_flat = 3 * static_cast<Eigen::Index>(s.n_free);
  Eigen::VectorXd u_prev, g_plain, x_next;
  double residual_min = std::numeric_limits<double>::infinity();
  bool pending = false;  // x is an accelerated iterate whose energy is not yet checked
  for (int it = 0; it < s.params.max_iterations; ++it) {
    const auto ti = Clock::now();
    double e = s.local_step();
    if (pending) {
      pending = false;
      if (e < e_prev) {
        ++s.stats.accelerated_iterations;
      } else {
        ++s.stats.rejected_accelerations;
        aa->reset();
        Eigen::Map<Eigen::VectorXd>(s.x.data(), n_flat) = g_plain;
        e = s.local_step();
      }
    }
    const auto tl = Clock::now();
    if (accelerate) u_prev = Eigen::Map<const Eigen::VectorXd>(s.x.data(), n_flat);
    s.global_step();
    const double rel = std::abs(e_prev - e) / std::max(e_prev, 1e-300);
    e_prev = e;
    const bool done = rel < s.params.tolerance;
    if (accelerate && !done && it + 1 < s.params.max_iterations) {
      auto x_flat = Eigen::Map<Eigen::VectorXd>(s.x.data(), n_flat);
      if (!descent) {
        // Anderson iterates' residuals are not monotone; a restart on every rise restarted 27
        // of 63 iterations at lambda = 0 (elephant), so only a doubling of the smallest
        // residual since the last restart counts (DeformSolver.AndersonAcceleration...).
        const double residual = (x_flat - u_prev).norm();
        if (!(residual < 2.0 * residual_min) && aa->history() > 0) {
          ++s.stats.rejected_accelerations;
          aa->reset();
          residual_min = residual;
        }
        residual_min = std::min(residual_min, residual);
      }
      if (aa->next(u_prev, x_flat, x_next)) {
        if (descent) {
          g_plain = x_flat;  // the fallback if the energy check refuses x_next
          pending = true;
        } else {
          ++s.stats.accelerated_iterations;
        }
        x_flat = x_next;
      }
    }
    s.stats.local_ms += std::chrono::duration<double, std::milli>(tl - ti).count();
    s.stats.solve_ms += ms_since(tl);
    s.stats.iteration_ms.push_back(ms_since(ti));
    s.stats.energies.push_back(e);
    ++s.stats.iterations;
    if (done) {
      s.stats.converged = true;
      break;
    }
  }
  if (s.params.max_iterations > 0) {
    const auto te = Clock::now();
    s.stats.energies.push_back(s.energy());
    s.stats.energy_ms = ms_since(te);
  }
  s.write_back(targets);
  s.stats.total_ms = ms_since(t0);
  return Status::ok();
}

Status EdgeGraphDeformer::drag(const std::vector<Vec3>& targets, int iterations) {
  Impl& s = *impl_;
  const auto t0 = Clock::now();
  if (Status ok = s.place_handles(targets); !ok) return ok;
  s.stats.iteration_ms.clear();
  s.stats.energies.clear();
  s.stats.iterations = 0;
  s.stats.initial_solve_ms = 0;
  for (int it = 0; it < std::max(iterations, 1); ++it) {
    const auto ti = Clock::now();
    s.local_step();
    s.global_step();
    s.stats.iteration_ms.push_back(ms_since(ti));
    ++s.stats.iterations;
  }
  s.write_back(targets);
  s.stats.total_ms = ms_since(t0);
  return Status::ok();
}

const std::vector<Vec3>& EdgeGraphDeformer::vertices() const { return impl_->current; }

TriMesh EdgeGraphDeformer::result() const {
  TriMesh out;
  out.vertices = impl_->current;
  out.faces = impl_->mesh.faces;
  return out;
}

const DeformStats& EdgeGraphDeformer::stats() const { return impl_->stats; }

Result<TriMesh> deform_mesh(const TriMesh& mesh, const std::vector<int>& roi,
                            const std::vector<HandleTarget>& handles, const DeformParameters& parameters,
                            DeformStats* stats) {
  EdgeGraphDeformer d;
  if (Status ok = d.set_mesh(mesh); !ok) return ok;
  std::vector<int> hv;
  std::vector<Vec3> hp;
  for (const auto& h : handles) hv.push_back(h.vertex), hp.push_back(h.position);
  if (Status ok = d.set_region(roi, hv, parameters); !ok) return ok;
  if (Status ok = d.deform(hp); !ok) return ok;
  if (stats) *stats = d.stats();
  return d.result();
}

}  // namespace ps
