// Edge-based graph (thesis 5.2) and cotangent weights (Eqs. 5.1, 5.2): structure, D, areas,
// the Laplacian of a constant, boundaries, clamping.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <filesystem>

#include "modeling/cotan_weights.h"
#include "modeling/edge_graph.h"
#include "modeling/mesh_io.h"

using namespace ps;

namespace {
std::string cgal_mesh(const char* name) { return std::string(PLANESKETCH_CGAL_DATA) + "/" + name; }

TriMesh tetrahedron() {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// A flat n x n grid of unit squares in z = 0, split into triangles (open, with boundary).
TriMesh grid(int n) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i, j * 1.1, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

double total_area(const TriMesh& m) {
  double a = 0;
  for (const Face& f : m.faces)
    a += 0.5 * (m.vertices[static_cast<std::size_t>(f[1])] - m.vertices[static_cast<std::size_t>(f[0])])
                   .cross(m.vertices[static_cast<std::size_t>(f[2])] - m.vertices[static_cast<std::size_t>(f[0])])
                   .norm();
  return a;
}

std::vector<TriMesh> test_meshes() {
  std::vector<TriMesh> out = {tetrahedron(), grid(6)};
  for (const char* name : {"elephant.off", "head.off"}) {
    auto r = read_mesh(cgal_mesh(name));
    if (r) out.push_back(*r);
  }
  return out;
}
}  // namespace

TEST(EdgeGraph, ValenceFourInsideTwoOnTheBoundary) {
  for (const TriMesh& m : test_meshes()) {
    auto me = mesh_edges(m);
    ASSERT_TRUE(me) << me.message();
    const DeformGraph g = build_edge_graph(m, *me);
    ASSERT_EQ(g.num_nodes(), me->edges.size());
    for (std::size_t e = 0; e < g.num_nodes(); ++e) {
      const int valence = g.offsets[e + 1] - g.offsets[e];
      const bool boundary = me->edge_faces[e][1] < 0;
      EXPECT_EQ(valence, boundary ? 2 : 4) << "edge " << e;
      // Each neighbour shares exactly one end vertex with the edge.
      for (int k = g.offsets[e]; k < g.offsets[e + 1]; ++k) {
        const auto& a = me->edges[e];
        const auto& b = me->edges[static_cast<std::size_t>(g.neighbors[static_cast<std::size_t>(k)])];
        const int shared = (a[0] == b[0]) + (a[0] == b[1]) + (a[1] == b[0]) + (a[1] == b[1]);
        EXPECT_EQ(shared, 1);
      }
    }
  }
}

TEST(EdgeGraph, NodeMatrixHasTwoHalvesPerRowAndGivesMidpoints) {
  const TriMesh m = grid(4);
  auto me = mesh_edges(m);
  const DeformGraph g = build_edge_graph(m, *me);
  const Eigen::SparseMatrix<double> d = node_matrix(g, static_cast<int>(m.vertices.size()));
  ASSERT_EQ(d.rows(), static_cast<Eigen::Index>(me->edges.size()));
  Eigen::MatrixXd x(static_cast<Eigen::Index>(m.vertices.size()), 3);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) x.row(static_cast<Eigen::Index>(v)) = m.vertices[v].transpose();
  const Eigen::MatrixXd y = d * x;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> dr = d;
  for (Eigen::Index r = 0; r < dr.rows(); ++r) {
    int nnz = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(dr, r); it; ++it) {
      EXPECT_EQ(it.value(), 0.5);
      ++nnz;
    }
    EXPECT_EQ(nnz, 2);
    const auto& e = me->edges[static_cast<std::size_t>(r)];
    const Vec3 mid = 0.5 * (m.vertices[static_cast<std::size_t>(e[0])] + m.vertices[static_cast<std::size_t>(e[1])]);
    EXPECT_NEAR((y.row(r).transpose() - mid).norm(), 0.0, 1e-15);
  }
}

TEST(EdgeGraph, LaplacianOfAConstantIsZero) {
  for (const TriMesh& m : test_meshes()) {
    auto me = mesh_edges(m);
    for (const DeformGraph& g : {build_edge_graph(m, *me), build_primal_graph(m, *me)}) {
      const Eigen::SparseMatrix<double> l = graph_laplacian(g);
      const Eigen::VectorXd c = Eigen::VectorXd::Constant(l.cols(), 3.7);
      const Eigen::VectorXd lc = l * c;
      EXPECT_LT(lc.cwiseAbs().maxCoeff(), 1e-9 * l.coeffs().cwiseAbs().maxCoeff());
    }
  }
}

TEST(EdgeGraph, AreasPartitionTheSurface) {
  for (const TriMesh& m : test_meshes()) {
    auto me = mesh_edges(m);
    const DeformGraph ge = build_edge_graph(m, *me), gp = build_primal_graph(m, *me);
    double se = 0, sp = 0;
    for (double a : ge.area) se += a;
    for (double a : gp.area) sp += a;
    const double total = total_area(m);
    // Primal mixed Voronoi areas cover the surface; edge-graph nodes own the midpoint cells of the
    // 1-to-4 subdivision, three quarters of it (the rest belongs to the original vertices).
    EXPECT_NEAR(sp, total, 1e-9 * total);
    EXPECT_NEAR(se, 0.75 * total, 1e-9 * total);
  }
}

// The edge-graph weights are those of the midpoint subdivision: check against mixed areas and
// cotangents computed on an explicitly subdivided triangle pair.
TEST(EdgeGraph, WeightsMatchTheMidpointSubdivision) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0.3, 1.4, 0.2), Vec3(1.6, -1.1, -0.3)};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  auto me = mesh_edges(m);
  const DeformGraph g = build_edge_graph(m, *me);
  // Node of edge (0, 1).
  std::size_t e01 = 0;
  while (!(me->edges[e01][0] == 0 && me->edges[e01][1] == 1)) ++e01;
  const Vec3 a = m.vertices[0], b = m.vertices[1], c = m.vertices[2], d = m.vertices[3];
  const Vec3 mab = 0.5 * (a + b), mac = 0.5 * (a + c), mbc = 0.5 * (b + c), mad = 0.5 * (a + d), mbd = 0.5 * (b + d);
  // Mixed area of m_ab over its six sub-triangles.
  double area = 0;
  for (const auto& tri : std::vector<std::array<Vec3, 3>>{{mab, mac, a}, {mab, mbc, mac}, {mab, b, mbc},
                                                          {mab, a, mad}, {mab, mad, mbd}, {mab, mbd, b}})
    area += mixed_areas(tri[0], tri[1], tri[2])[0];
  EXPECT_NEAR(g.area[e01], area, 1e-14);
  // Weight to the node of (0, 2): the two angles opposite (m_ab, m_ac) in the subdivision.
  for (int k = g.offsets[e01]; k < g.offsets[e01 + 1]; ++k) {
    const auto& n = me->edges[static_cast<std::size_t>(g.neighbors[static_cast<std::size_t>(k)])];
    if (!(n[0] == 0 && n[1] == 2)) continue;
    const double expected = 0.5 * (clamped_cot(a, mab, mac) + clamped_cot(mbc, mac, mab));
    EXPECT_NEAR(g.cot[static_cast<std::size_t>(k)], expected, 1e-12);
  }
}

TEST(EdgeGraph, DegenerateTrianglesAreClampedAndCounted) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0)};
  m.faces = {{0, 1, 3}, {1, 2, 3}, {0, 2, 1}};  // the last one has zero area
  auto me = mesh_edges(m);
  ASSERT_TRUE(me);
  const DeformGraph g = build_edge_graph(m, *me);
  EXPECT_EQ(g.degenerate_triangles, 1);
  EXPECT_GT(g.clamped_cotangents, 0);
  for (double c : g.cot) EXPECT_TRUE(std::isfinite(c) && std::abs(c) <= kMaxCotangent);
  for (double a : g.area) EXPECT_GT(a, 0.0);
  bool clamped = false;
  EXPECT_EQ(clamped_cot(Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(2, 0, 0), &clamped), -kMaxCotangent);
  EXPECT_TRUE(clamped);
}

TEST(EdgeGraph, RefusesNonManifoldEdges) {
  TriMesh m = tetrahedron();
  m.vertices.emplace_back(1, 1, 1);
  m.faces.push_back({0, 1, 4});  // edge (0, 1) now has three faces
  auto me = mesh_edges(m);
  ASSERT_FALSE(me);
  EXPECT_NE(me.message().find("more than two faces"), std::string::npos) << me.message();
}
