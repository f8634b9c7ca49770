// Flexible edge-graph deformation (thesis chapter 5): constraints, invariances, lambda effects,
// edge graph versus primal domain, open meshes, warm-started drags.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <cstring>
#include <numeric>
#include <tbb/global_control.h>

#include "modeling/edge_graph.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh_io.h"

using namespace ps;

namespace {

std::string cgal_mesh(const char* name) { return std::string(PLANESKETCH_CGAL_DATA) + "/" + name; }

#define LOAD_OR_SKIP(var, name)                                              \
  if (!std::filesystem::exists(cgal_mesh(name))) GTEST_SKIP() << "missing " << cgal_mesh(name); \
  auto var##_r = read_mesh(cgal_mesh(name));                                 \
  ASSERT_TRUE(var##_r) << var##_r.message();                                 \
  const TriMesh var = *var##_r

// A deformation scenario: ROI = vertices within `roi_radius` of vertex `center`, handles = those
// within `handle_radius`, moved by `motion`; every other vertex is static.
struct Scenario {
  std::vector<int> roi, handles;
  std::vector<Vec3> targets;
};

Scenario make_scenario(const TriMesh& m, int center, double roi_radius, double handle_radius,
                       const Eigen::Isometry3d& motion) {
  Scenario s;
  const Vec3 c = m.vertices[static_cast<std::size_t>(center)];
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const double d = (m.vertices[v] - c).norm();
    if (d < handle_radius) {
      s.handles.push_back(static_cast<int>(v));
      s.targets.push_back(motion * m.vertices[v]);
    } else if (d < roi_radius) {
      s.roi.push_back(static_cast<int>(v));
    }
  }
  return s;
}

double diagonal(const TriMesh& m) { return bounding_box(m.vertices).diagonal(); }

// Edges with at least one vertex in `region`.
std::vector<std::array<int, 2>> region_edges(const TriMesh& m, const std::vector<int>& region) {
  std::vector<char> in(m.vertices.size(), 0);
  for (int v : region) in[static_cast<std::size_t>(v)] = 1;
  auto me = mesh_edges(m);
  std::vector<std::array<int, 2>> out;
  for (const auto& e : me->edges)
    if (in[static_cast<std::size_t>(e[0])] || in[static_cast<std::size_t>(e[1])]) out.push_back(e);
  return out;
}

// Mean relative edge length change over edges touching the region.
double edge_length_distortion(const TriMesh& a, const TriMesh& b, const std::vector<int>& region) {
  double sum = 0;
  const auto edges = region_edges(a, region);
  for (const auto& e : edges) {
    const double la = (a.vertices[static_cast<std::size_t>(e[0])] - a.vertices[static_cast<std::size_t>(e[1])]).norm();
    const double lb = (b.vertices[static_cast<std::size_t>(e[0])] - b.vertices[static_cast<std::size_t>(e[1])]).norm();
    sum += std::abs(lb - la) / la;
  }
  return sum / static_cast<double>(edges.size());
}

// Mean absolute change of the dihedral angle (radians) over interior edges touching the region.
double dihedral_change(const TriMesh& a, const TriMesh& b, const std::vector<int>& region) {
  std::vector<char> in(a.vertices.size(), 0);
  for (int v : region) in[static_cast<std::size_t>(v)] = 1;
  auto me = mesh_edges(a);
  auto normal = [](const TriMesh& m, int f) {
    const Face& t = m.faces[static_cast<std::size_t>(f)];
    const Vec3& p0 = m.vertices[static_cast<std::size_t>(t[0])];
    return Vec3((m.vertices[static_cast<std::size_t>(t[1])] - p0).cross(m.vertices[static_cast<std::size_t>(t[2])] - p0).normalized());
  };
  double sum = 0;
  int n = 0;
  for (std::size_t e = 0; e < me->edges.size(); ++e) {
    const auto& ef = me->edge_faces[e];
    if (ef[1] < 0) continue;
    if (!in[static_cast<std::size_t>(me->edges[e][0])] && !in[static_cast<std::size_t>(me->edges[e][1])]) continue;
    const double ta = std::acos(std::clamp(normal(a, ef[0]).dot(normal(a, ef[1])), -1.0, 1.0));
    const double tb = std::acos(std::clamp(normal(b, ef[0]).dot(normal(b, ef[1])), -1.0, 1.0));
    sum += std::abs(tb - ta);
    ++n;
  }
  return sum / n;
}

Result<TriMesh> run(const TriMesh& m, const Scenario& s, double lambda, DeformDomain domain,
                    DeformStats* stats = nullptr, int iterations = 10, double tolerance = 1e-6,
                    int anderson_window = DeformParameters{}.anderson_window) {
  std::vector<HandleTarget> h;
  for (std::size_t k = 0; k < s.handles.size(); ++k) h.push_back({s.handles[k], s.targets[k]});
  DeformParameters p;
  p.lambda = lambda;
  p.domain = domain;
  p.max_iterations = iterations;
  p.tolerance = tolerance;
  p.anderson_window = anderson_window;
  return deform_mesh(m, s.roi, h, p, stats);
}

Eigen::Isometry3d lift(const Vec3& t, double angle = 0.0, const Vec3& axis = Vec3::UnitZ(),
                       const Vec3& pivot = Vec3::Zero()) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.translate(t + pivot);
  m.rotate(Eigen::AngleAxisd(angle, axis));
  m.translate(-pivot);
  return m;
}

}  // namespace

// === Constraints

TEST(DeformSolver, HandlesLandExactlyAndStaticVerticesKeepTheirBits) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  const auto s = make_scenario(m, 100, 0.2 * d, 0.05 * d, lift(Vec3(0.05 * d, 0.03 * d, 0)));
  ASSERT_GT(s.handles.size(), 3u);
  for (auto domain : {DeformDomain::kEdgeGraph, DeformDomain::kPrimal})
    for (double lambda : {0.0, 0.5, 1.0}) {
      DeformStats st;
      auto r = run(m, s, lambda, domain, &st);
      ASSERT_TRUE(r) << r.message();
      std::vector<char> moving(m.vertices.size(), 0);
      for (int v : s.roi) moving[static_cast<std::size_t>(v)] = 1;
      for (std::size_t k = 0; k < s.handles.size(); ++k) {
        EXPECT_EQ(r->vertices[static_cast<std::size_t>(s.handles[k])], s.targets[k]);  // exact
        moving[static_cast<std::size_t>(s.handles[k])] = 1;
      }
      for (std::size_t v = 0; v < m.vertices.size(); ++v) {
        if (!moving[v]) {
          ASSERT_EQ(std::memcmp(r->vertices[v].data(), m.vertices[v].data(), sizeof(double) * 3), 0) << v;
        }
      }
      EXPECT_EQ(st.max_handle_residual, 0.0);
      // At lambda = 1 the local/global alternation is a descent (ARAP); with the Laplacian term
      // the scale update is not, so only the pure 1-form case is checked.
      if (lambda == 1.0) {
        for (std::size_t k = 2; k < st.energies.size(); ++k) EXPECT_LE(st.energies[k], st.energies[k - 1] * (1 + 1e-9));
      }
      // The ROI moved.
      double moved = 0;
      for (int v : s.roi) moved = std::max(moved, (r->vertices[static_cast<std::size_t>(v)] - m.vertices[static_cast<std::size_t>(v)]).norm());
      EXPECT_GT(moved, 1e-3 * d);
    }
}

TEST(DeformSolver, RigidMotionOfAllHandlesOfAClosedPartIsNearRigid) {
  LOAD_OR_SKIP(m, "cactus.off");
  const double d = diagonal(m);
  // Handles: every 10th vertex, spread over the whole closed surface; ROI: all the others.
  const Vec3 c = bounding_box(m.vertices).center();
  const Eigen::Isometry3d motion = lift(Vec3(0.1 * d, -0.05 * d, 0.02 * d), 0.3, Vec3(1, 2, 3).normalized(), c);
  std::vector<int> handles, roi;
  std::vector<Vec3> targets;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (v % 10 == 0) {
      handles.push_back(static_cast<int>(v));
      targets.push_back(motion * m.vertices[v]);
    } else {
      roi.push_back(static_cast<int>(v));
    }
  }
  for (double lambda : {0.0, 0.5, 1.0}) {
    EdgeGraphDeformer def;
    ASSERT_TRUE(def.set_mesh(m));
    DeformParameters p;
    p.lambda = lambda;
    p.max_iterations = 60;
    p.tolerance = 1e-10;
    ASSERT_TRUE(def.set_region(roi, handles, p));
    ASSERT_TRUE(def.deform(targets));
    double err = 0;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) err = std::max(err, (def.vertices()[v] - motion * m.vertices[v]).norm());
    // Local/global iterations converge slowly toward the rigid motion (zero energy).
    EXPECT_LT(err, 2.5e-3 * d) << "lambda " << lambda;
    EXPECT_LT(def.stats().energies.back(), 1e-3 * def.stats().energies.front()) << "lambda " << lambda;
  }
}

// === Metamorphic: rotating, translating and uniformly scaling the input and the targets gives
// the same result, transformed.
TEST(DeformSolver, InvariantToRotationTranslationAndScale) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  const auto s = make_scenario(m, 100, 0.25 * d, 0.05 * d, lift(Vec3(0.06 * d, 0.04 * d, 0.0), 0.3, Vec3::UnitY(), m.vertices[100]));
  for (auto domain : {DeformDomain::kEdgeGraph, DeformDomain::kPrimal}) {
    auto base = run(m, s, 0.5, domain);
    ASSERT_TRUE(base);
    for (double scale : {1e-3, 1.0, 1e3}) {
      Eigen::Affine3d g = Eigen::Affine3d::Identity();
      g.translate(Vec3(5.0, -3.0, 2.0));
      g.rotate(Eigen::AngleAxisd(1.1, Vec3(0.3, -1.0, 0.5).normalized()));
      g.scale(scale);
      TriMesh mt = m;
      for (auto& v : mt.vertices) v = g * v;
      Scenario st = s;
      for (auto& t : st.targets) t = g * t;
      auto r = run(mt, st, 0.5, domain);
      ASSERT_TRUE(r);
      double err = 0;
      for (std::size_t v = 0; v < m.vertices.size(); ++v) err = std::max(err, (r->vertices[v] - g * base->vertices[v]).norm());
      EXPECT_LT(err, 1e-7 * d * scale) << "scale " << scale;
    }
  }
}

// === Lambda: 1 keeps edge lengths better, 0 keeps dihedral angles better (measured here).
struct Measures {
  double length = 0, dihedral = 0;
};

Measures measure(const TriMesh& m, const Scenario& s, double lambda, DeformDomain domain) {
  auto r = run(m, s, lambda, domain, nullptr, 10);
  EXPECT_TRUE(r) << r.message();
  std::vector<int> region = s.roi;
  return {edge_length_distortion(m, *r, region), dihedral_change(m, *r, region)};
}

TEST(DeformSolver, LambdaOneKeepsLengthsLambdaZeroKeepsDihedralAngles) {
  for (const char* name : {"elephant.off", "dino.off"}) {
    LOAD_OR_SKIP(m, name);
    const double d = diagonal(m);
    const auto s = make_scenario(m, 100, 0.25 * d, 0.04 * d,
                                 lift(Vec3(0.08 * d, 0.05 * d, 0.0), 0.4, Vec3::UnitZ(), m.vertices[100]));
    for (auto domain : {DeformDomain::kEdgeGraph, DeformDomain::kPrimal}) {
      const Measures m0 = measure(m, s, 0.0, domain), m1 = measure(m, s, 1.0, domain);
      std::printf("%s %s: lambda=0 length %.5f dihedral %.5f | lambda=1 length %.5f dihedral %.5f\n", name,
                  domain == DeformDomain::kEdgeGraph ? "edge-graph" : "primal", m0.length, m0.dihedral,
                  m1.length, m1.dihedral);
      EXPECT_LT(m1.length, m0.length) << name;
      EXPECT_LT(m0.dihedral, m1.dihedral) << name;
    }
  }
}

// === Thesis 5.5 claims the edge graph beats the primal domain at lambda = 0 and 1. This records
// the comparison on two meshes (printed); it asserts only what was measured to hold here:
// at lambda = 0 the edge graph keeps both edge lengths and dihedral angles better, at lambda = 1
// it keeps edge lengths better. (At lambda = 1 the primal domain changed dihedral angles less
// on both meshes, so that part of the claim is not asserted; see docs/deformation.md.)
TEST(DeformSolver, EdgeGraphVersusPrimalDomain) {
  for (const char* name : {"elephant.off", "dino.off"}) {
    LOAD_OR_SKIP(m, name);
    const double d = diagonal(m);
    const auto s = make_scenario(m, 100, 0.25 * d, 0.04 * d,
                                 lift(Vec3(0.08 * d, 0.05 * d, 0.0), 0.4, Vec3::UnitZ(), m.vertices[100]));
    for (double lambda : {0.0, 1.0}) {
      const Measures e = measure(m, s, lambda, DeformDomain::kEdgeGraph);
      const Measures p = measure(m, s, lambda, DeformDomain::kPrimal);
      std::printf("%s lambda=%.0f: edge-graph length %.5f dihedral %.5f | primal length %.5f dihedral %.5f\n",
                  name, lambda, e.length, e.dihedral, p.length, p.dihedral);
      EXPECT_LT(e.length, p.length) << name << " lambda " << lambda;
      if (lambda == 0.0) {
        EXPECT_LT(e.dihedral, p.dihedral) << name;
      }
    }
  }
}

// === Open meshes: boundary edges have two edge-graph neighbours; the solver handles them.
TEST(DeformSolver, OpenMeshWithBoundaryInTheRoi) {
  for (const char* name : {"head.off", "plane.off"}) {
    LOAD_OR_SKIP(m, name);
    auto me = mesh_edges(m);
    ASSERT_TRUE(me);
    ASSERT_GT(me->boundary_edges, 0) << name;
    const double d = diagonal(m);
    // Centre on a boundary vertex so the ROI contains boundary edges.
    int center = me->edges[0][0];
    for (std::size_t e = 0; e < me->edges.size(); ++e)
      if (me->edge_faces[e][1] < 0) {
        center = me->edges[e][0];
        break;
      }
    const auto s = make_scenario(m, center, 0.35 * d, 0.08 * d, lift(Vec3(0.0, 0.0, 0.1 * d)));
    for (auto domain : {DeformDomain::kEdgeGraph, DeformDomain::kPrimal})
      for (double lambda : {0.0, 0.5, 1.0}) {
        DeformStats st;
        auto r = run(m, s, lambda, domain, &st);
        ASSERT_TRUE(r) << r.message();
        for (const auto& v : r->vertices) ASSERT_TRUE(v.allFinite());
        for (std::size_t k = 0; k < s.handles.size(); ++k) EXPECT_EQ(r->vertices[static_cast<std::size_t>(s.handles[k])], s.targets[k]);
        // A pure translation of the handles of a patch: the ROI moves toward it, never beyond.
        for (int v : s.roi) {
          const double dz = r->vertices[static_cast<std::size_t>(v)].z() - m.vertices[static_cast<std::size_t>(v)].z();
          EXPECT_LT(dz, 0.1 * d * 1.2) << name;
        }
      }
    // Translating every vertex's handle: ROI covering the whole open mesh moves rigidly.
    std::vector<int> handles, roi;
    std::vector<Vec3> targets;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      if (v % 20 == 0) {
        handles.push_back(static_cast<int>(v));
        targets.push_back(m.vertices[v] + Vec3(0.1 * d, 0, 0));
      } else {
        roi.push_back(static_cast<int>(v));
      }
    }
    for (double lambda : {0.0, 1.0}) {
      std::vector<HandleTarget> h;
      for (std::size_t k = 0; k < handles.size(); ++k) h.push_back({handles[k], targets[k]});
      DeformParameters p;
      p.lambda = lambda;
      auto r = deform_mesh(m, roi, h, p);
      ASSERT_TRUE(r) << r.message();
      double err = 0;
      for (std::size_t v = 0; v < m.vertices.size(); ++v)
        err = std::max(err, (r->vertices[v] - m.vertices[v] - Vec3(0.1 * d, 0, 0)).norm());
      EXPECT_LT(err, 1e-9 * d) << name << " lambda " << lambda;
    }
  }
}

// === Warm-started drags track the cold solution.
TEST(DeformSolver, DragWarmStartApproachesTheColdSolution) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  const auto s = make_scenario(m, 100, 0.25 * d, 0.05 * d, lift(Vec3(0.06 * d, 0.04 * d, 0.0)));
  DeformParameters p;
  p.max_iterations = 200;
  p.tolerance = 1e-12;
  EdgeGraphDeformer cold;
  ASSERT_TRUE(cold.set_mesh(m));
  ASSERT_TRUE(cold.set_region(s.roi, s.handles, p));
  ASSERT_TRUE(cold.deform(s.targets));
  EdgeGraphDeformer warm;
  ASSERT_TRUE(warm.set_mesh(m));
  ASSERT_TRUE(warm.set_region(s.roi, s.handles, p));
  // Drag in 10 steps from the rest positions to the targets, one iteration each, then settle.
  std::vector<Vec3> rest;
  for (int h : s.handles) rest.push_back(m.vertices[static_cast<std::size_t>(h)]);
  for (int step = 1; step <= 10; ++step) {
    std::vector<Vec3> pos;
    for (std::size_t k = 0; k < rest.size(); ++k) pos.push_back(rest[k] + (s.targets[k] - rest[k]) * (step / 10.0));
    ASSERT_TRUE(warm.drag(pos, 1));
    for (std::size_t k = 0; k < rest.size(); ++k) EXPECT_EQ(warm.vertices()[static_cast<std::size_t>(s.handles[k])], pos[k]);
  }
  double before = 0;
  for (int v : s.roi) before = std::max(before, (warm.vertices()[static_cast<std::size_t>(v)] - cold.vertices()[static_cast<std::size_t>(v)]).norm());
  ASSERT_TRUE(warm.drag(s.targets, 100));
  double after = 0;
  for (int v : s.roi) after = std::max(after, (warm.vertices()[static_cast<std::size_t>(v)] - cold.vertices()[static_cast<std::size_t>(v)]).norm());
  EXPECT_LT(after, 1e-2 * d);
  EXPECT_LE(after, before);
}

// === Balance parameters (5.4): per-vertex stiffness equal to the global value changes nothing;
// a stiff ROI keeps its edge lengths better than a soft one.
TEST(DeformSolver, PerVertexLambda) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  const auto s = make_scenario(m, 100, 0.25 * d, 0.05 * d, lift(Vec3(0.08 * d, 0.04 * d, 0.0)));
  std::vector<HandleTarget> h;
  for (std::size_t k = 0; k < s.handles.size(); ++k) h.push_back({s.handles[k], s.targets[k]});
  DeformParameters global;
  global.lambda = 0.3;
  DeformParameters local = global;
  local.vertex_lambda.assign(m.vertices.size(), 0.3);
  auto a = deform_mesh(m, s.roi, h, global), b = deform_mesh(m, s.roi, h, local);
  ASSERT_TRUE(a && b);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) EXPECT_EQ(a->vertices[v], b->vertices[v]);
  DeformParameters stiff = global, soft = global;
  stiff.vertex_lambda.assign(m.vertices.size(), std::numeric_limits<double>::quiet_NaN());
  soft.vertex_lambda = stiff.vertex_lambda;
  for (int v : s.roi) stiff.vertex_lambda[static_cast<std::size_t>(v)] = 1.0, soft.vertex_lambda[static_cast<std::size_t>(v)] = 0.0;
  auto rs = deform_mesh(m, s.roi, h, stiff), rf = deform_mesh(m, s.roi, h, soft);
  ASSERT_TRUE(rs && rf);
  EXPECT_LT(edge_length_distortion(m, *rs, s.roi), edge_length_distortion(m, *rf, s.roi));
}

// === Refusals
TEST(DeformSolver, RefusesBadRegions) {
  LOAD_OR_SKIP(m, "cactus.off");
  EdgeGraphDeformer def;
  ASSERT_TRUE(def.set_mesh(m));
  std::vector<int> all(m.vertices.size());
  std::iota(all.begin(), all.end(), 0);
  DeformParameters p;
  auto st = def.set_region(all, {}, p);
  EXPECT_FALSE(st);
  EXPECT_NE(st.message().find("no handle or static"), std::string::npos) << st.message();
  st = def.set_region({0, 1}, {5, 5}, p);
  EXPECT_NE(st.message().find("handles[1]"), std::string::npos) << st.message();
  st = def.set_region({0, static_cast<int>(m.vertices.size())}, {5}, p);
  EXPECT_NE(st.message().find("roi[1]"), std::string::npos) << st.message();
  p.lambda = 1.5;
  st = def.set_region({0}, {5}, p);
  EXPECT_NE(st.message().find("lambda"), std::string::npos) << st.message();
  p.lambda = 0.5;
  for (int window : {-1, 65, 1 << 30}) {
    p.anderson_window = window;
    st = def.set_region({0}, {5}, p);
    EXPECT_NE(st.message().find("anderson_window"), std::string::npos) << st.message();
  }
  p.anderson_window = 5;
  // Wrong number of handle positions.
  ASSERT_TRUE(def.set_region({0, 1, 2}, {5}, p));
  EXPECT_FALSE(def.deform({}));
  TriMesh bad = m;
  bad.faces.push_back(bad.faces[0]);  // a third face on three edges
  EXPECT_FALSE(def.set_mesh(bad));
}

// === Threads: a small region (under 5000 graph nodes) and a large one give bit-identical
// results with one and two threads: the parallel loops write disjoint rows and the reductions
// are deterministic (parallel_deterministic_reduce).
TEST(DeformSolver, SameBitsWithOneAndTwoThreads) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  bool saw_small = false, saw_large = false;
  for (double radius : {0.15, 0.9}) {
    const auto s = make_scenario(m, 100, radius * d, 0.05 * d, lift(Vec3(0.05 * d, 0.03 * d, 0.01 * d)));
    std::vector<Vec3> result[2];
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      DeformParameters p;
      p.lambda = 0.5;
      EdgeGraphDeformer def;
      ASSERT_TRUE(def.set_mesh(m));
      ASSERT_TRUE(def.set_region(s.roi, s.handles, p));
      ASSERT_TRUE(def.deform(s.targets));
      ASSERT_TRUE(def.drag(s.targets, 2));
      (def.stats().nodes < 5000 ? saw_small : saw_large) = true;
      result[threads - 1] = def.vertices();
    }
    ASSERT_EQ(result[0].size(), result[1].size());
    for (std::size_t v = 0; v < result[0].size(); ++v)
      ASSERT_EQ(std::memcmp(result[0][v].data(), result[1][v].data(), sizeof(double) * 3), 0) << "radius " << radius << ", vertex " << v;
  }
  EXPECT_TRUE(saw_small);
  EXPECT_TRUE(saw_large);
}

// === Anderson acceleration (anderson_acceleration.h): at the same tolerance the accelerated
// iteration stops in fewer iterations and at least as close to the solution, the fixed point
// of the plain local/global alternation (run here to a relative energy change of 1e-13).
TEST(DeformSolver, AndersonAccelerationConvergesInFewerIterationsAndAsClose) {
  LOAD_OR_SKIP(m, "elephant.off");
  const double d = diagonal(m);
  const auto s = make_scenario(m, 100, 0.25 * d, 0.05 * d, lift(Vec3(0.06 * d, 0.04 * d, 0.0), 0.3, Vec3::UnitY(), m.vertices[100]));
  double moved = 0;
  for (std::size_t k = 0; k < s.handles.size(); ++k)
    moved = std::max(moved, (s.targets[k] - m.vertices[static_cast<std::size_t>(s.handles[k])]).norm());
  double fast_total = 0, plain_total = 0;
  for (auto domain : {DeformDomain::kEdgeGraph, DeformDomain::kPrimal})
    for (double lambda : {0.0, 0.5, 1.0}) {
      auto solve = [&](int window, int iterations, double tolerance, DeformStats& st) {
        auto r = run(m, s, lambda, domain, &st, iterations, tolerance, window);
        EXPECT_TRUE(r) << r.message();
        return r ? r->vertices : std::vector<Vec3>(m.vertices.size(), Vec3::Zero());
      };
      DeformStats exact_st, plain_st, fast_st;
      const auto exact = solve(0, 3000, 1e-13, exact_st);
      ASSERT_TRUE(exact_st.converged);
      const auto plain = solve(0, 500, 1e-5, plain_st);
      const auto fast = solve(5, 500, 1e-5, fast_st);
      ASSERT_TRUE(plain_st.converged);
      ASSERT_TRUE(fast_st.converged);
      auto error = [&](const std::vector<Vec3>& x) {
        double e = 0;
        for (std::size_t v = 0; v < x.size(); ++v) e = std::max(e, (x[v] - exact[v]).norm());
        return e / moved;
      };
      const double plain_err = error(plain), fast_err = error(fast);
      std::printf("  %s lambda %.1f: plain %d iterations, error %.2e; accelerated %d (%d accelerated, %d restarts), error %.2e; exact %d\n",
                  domain == DeformDomain::kEdgeGraph ? "edge graph" : "primal", lambda, plain_st.iterations, plain_err,
                  fast_st.iterations, fast_st.accelerated_iterations, fast_st.rejected_accelerations, fast_err,
                  exact_st.iterations);
      EXPECT_LT(fast_st.iterations, plain_st.iterations) << lambda;
      EXPECT_GT(fast_st.accelerated_iterations, 0) << lambda;
      // Below lambda = 1 the energy is not a descent, and where the relative change first dips
      // under the tolerance is partly chance: measured, the accelerated result was 2-10x closer
      // at lambda 0.5 and 1 and within 2% of the plain one's error at lambda 0 (primal).
      EXPECT_LE(fast_err, 1.25 * plain_err) << lambda;
      if (lambda > 0.0) {
        EXPECT_LT(fast_err, plain_err) << lambda;
      }
      fast_total += fast_err;
      plain_total += plain_err;
    }
  EXPECT_LT(fast_total, 0.5 * plain_total);
}
