// separate_pinches (modeling/pinch_separate.h): two solids touching along an edge or at a
// vertex become a closed 2-manifold without self-intersections, the touching sheets moved
// apart by the gap; surfaces without pinches are left alone; open surfaces are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/pinch_separate.h"

namespace {

using ps::TriMesh;
using ps::Vec3;

// Axis-aligned box [lo, hi], outward triangles.
TriMesh box(const Vec3& lo, const Vec3& hi) {
  TriMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), (i >> 1) & 1 ? hi.y() : lo.y(), (i >> 2) & 1 ? hi.z() : lo.z());
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Both boxes in one mesh, vertices at the same position merged (the stitched surface's welding).
TriMesh merged(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  for (const auto& f : b.faces) {
    ps::Face g{};
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = b.vertices[static_cast<std::size_t>(f[static_cast<std::size_t>(k)])];
      int found = -1;
      for (std::size_t v = 0; v < m.vertices.size(); ++v)
        if (m.vertices[v] == p) found = static_cast<int>(v);
      if (found < 0) {
        found = static_cast<int>(m.vertices.size());
        m.vertices.push_back(p);
      }
      g[static_cast<std::size_t>(k)] = found;
    }
    m.faces.push_back(g);
  }
  return m;
}

std::vector<int> all_faces(const TriMesh& m) {
  std::vector<int> f(m.faces.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = static_cast<int>(i);
  return f;
}

void expect_separated(const TriMesh& m, int components, double volume) {
  const ps::MeshTopology t = ps::mesh_topology(m);
  EXPECT_TRUE(t.closed) << t.problem;
  EXPECT_TRUE(t.manifold()) << t.problem;
  EXPECT_TRUE(t.consistently_oriented) << t.problem;
  EXPECT_EQ(t.components, components);
  EXPECT_NEAR(t.signed_volume, volume, 1e-6);
  EXPECT_TRUE(ps::intersecting_face_pairs(m.vertices, m.faces, all_faces(m)).empty());
}

TEST(PinchSeparate, BoxesTouchingAlongAnEdge) {
  // A in x, y < 0 and B in x, y > 0 share the segment x = y = 0, 0 <= z <= 1.
  TriMesh m = merged(box(Vec3(-1, -1, 0), Vec3(0, 0, 1)), box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  const ps::MeshTopology before = ps::mesh_topology(m);
  ASSERT_FALSE(before.edge_manifold);
  ASSERT_EQ(m.vertices.size(), 14u);
  const double gap = 1e-9;
  std::vector<int> moved;
  EXPECT_EQ(ps::separate_pinches(m, gap, &moved), 2);
  EXPECT_EQ(m.vertices.size(), 16u);
  EXPECT_EQ(moved.size(), 4u);  // both ends of the edge, once per box
  expect_separated(m, 2, 2.0);
  // Each copy moved by the gap from (0, 0, 0) or (0, 0, 1), into its own box.
  for (int v : moved) {
    const Vec3& p = m.vertices[static_cast<std::size_t>(v)];
    EXPECT_NEAR((p - Vec3(0, 0, std::round(p.z()))).norm(), gap, 1e-15);
    EXPECT_NE(p.x(), 0.0);
    EXPECT_EQ(p.x() < 0, p.y() < 0);  // into A (x, y < 0) or into B (x, y > 0)
  }
}

TEST(PinchSeparate, JoiningSplitsNoVertexWhereSeparatingDoes) {
  // Paired across the empty quadrants, the faces around each end of the shared edge form one
  // fan (A's three faces, then B's): nothing to split, so kJoin leaves the mesh to the caller's
  // refusal; the stress seeds of recon_stress_regression_test are the converse case.
  TriMesh m = merged(box(Vec3(-1, -1, 0), Vec3(0, 0, 1)), box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  const TriMesh copy = m;
  EXPECT_EQ(ps::separate_pinches(m, 1e-9, nullptr, ps::PinchMode::kJoin), 0);
  EXPECT_EQ(m.vertices, copy.vertices);
  EXPECT_EQ(m.faces, copy.faces);
}

TEST(PinchSeparate, BoxesTouchingAtACorner) {
  TriMesh m = merged(box(Vec3(-1, -1, -1), Vec3(0, 0, 0)), box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  ASSERT_EQ(m.vertices.size(), 15u);
  ASSERT_FALSE(ps::mesh_topology(m).vertex_manifold);
  EXPECT_EQ(ps::separate_pinches(m, 1e-9), 1);
  EXPECT_EQ(m.vertices.size(), 16u);
  expect_separated(m, 2, 2.0);
}

TEST(PinchSeparate, TheResultDoesNotDependOnTheFaceOrderBeyondNumbering) {
  // Reversed face order: the same vertex positions come out (as a set).
  TriMesh a = merged(box(Vec3(-1, -1, 0), Vec3(0, 0, 1)), box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  TriMesh b = a;
  std::reverse(b.faces.begin(), b.faces.end());
  ASSERT_EQ(ps::separate_pinches(a, 1e-9), 2);
  ASSERT_EQ(ps::separate_pinches(b, 1e-9), 2);
  auto sorted = [](std::vector<Vec3> v) {
    std::sort(v.begin(), v.end(), [](const Vec3& p, const Vec3& q) {
      return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    });
    return v;
  };
  EXPECT_EQ(sorted(a.vertices), sorted(b.vertices));
}

TEST(PinchSeparate, LeavesManifoldSurfacesAloneAndRefusesOpenOnes) {
  TriMesh one = box(Vec3(0, 0, 0), Vec3(1, 2, 3));
  const TriMesh copy = one;
  EXPECT_EQ(ps::separate_pinches(one, 1e-9), 0);
  EXPECT_EQ(one.vertices, copy.vertices);
  EXPECT_EQ(one.faces, copy.faces);
  // An open surface (one face of the pinched pair removed) is refused, and left as it was.
  TriMesh open = merged(box(Vec3(-1, -1, 0), Vec3(0, 0, 1)), box(Vec3(0, 0, 0), Vec3(1, 1, 1)));
  open.faces.pop_back();
  const TriMesh open_copy = open;
  EXPECT_EQ(ps::separate_pinches(open, 1e-9), -1);
  EXPECT_EQ(open.faces, open_copy.faces);  // unchanged on refusal
}

// A tetrahedron with outward faces.
TriMesh tet(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  TriMesh m;
  m.vertices = {p0, p1, p2, p3};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  if (ps::signed_volume(m) < 0)
    for (auto& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

// The smallest value, over the moved copies and the faces around each, of -(displacement . face
// normal at the rest position): positive when every copy moved into its own solid past every
// one of its faces (kSeparate), which is what keeps the faces from sweeping through the other
// sheet at the vertex.
double worst_inward_move(const TriMesh& before, const TriMesh& after, const std::vector<int>& moved) {
  double worst = 1.0;
  for (int w : moved) {
    // The copy's rest position: the original vertex at the same place up to the move.
    const Vec3& p = after.vertices[static_cast<std::size_t>(w)];
    Vec3 rest = p;
    double best = 1.0;
    for (const Vec3& q : before.vertices)
      if ((q - p).norm() < best) best = (q - p).norm(), rest = q;
    const Vec3 d = (p - rest).normalized();
    for (const auto& f : after.faces) {
      std::array<Vec3, 3> c;
      bool has = false;
      for (std::size_t k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(f[k]);
        has = has || f[k] == w;
        c[k] = f[k] == w ? rest : after.vertices[v];
      }
      if (!has) continue;
      const Vec3 n = (c[1] - c[0]).cross(c[2] - c[0]).normalized();
      worst = std::min(worst, -n.dot(d));
    }
  }
  return worst;
}

TEST(PinchSeparate, InsideFanMovesEveryCopyInsideAllOfItsFaces) {
  // Two thin tetrahedra touching along the edge x = y = 0, 0 <= z <= 1: A fills a wedge of 0.11
  // degrees about +x, B one about -x, their far faces slanted so that each fan's normal (the
  // mean) points mostly along y, out of the wedge. kInsideFan moves each copy of the edge's ends
  // inside all of its faces; the fan normal does not.
  const double w = 0.001;
  const TriMesh a = tet(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, w, 0.2), Vec3(1, -w, 0.8));
  const TriMesh b = tet(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(-1, w, 0.2), Vec3(-1, -w, 0.8));
  const TriMesh m = merged(a, b);
  ASSERT_FALSE(ps::mesh_topology(m).edge_manifold);
  const double gap = 1e-9;
  TriMesh by_normal = m, inside = m;
  std::vector<int> moved_normal, moved_inside;
  ASSERT_EQ(ps::separate_pinches(by_normal, gap, &moved_normal), 2);
  ASSERT_EQ(ps::separate_pinches(inside, gap, &moved_inside, ps::PinchMode::kSeparate, ps::PinchDirection::kInsideFan), 2);
  ASSERT_EQ(moved_inside.size(), 4u);
  EXPECT_LT(worst_inward_move(m, by_normal, moved_normal), 0.0);
  EXPECT_GT(worst_inward_move(m, inside, moved_inside), 0.0);
  for (int v : moved_inside) {
    const Vec3& p = inside.vertices[static_cast<std::size_t>(v)];
    EXPECT_NEAR((p - Vec3(0, 0, std::round(p.z()))).norm(), gap, 1e-15);  // the copies at z = 1 round to its ulp
  }
  expect_separated(inside, 2, ps::signed_volume(a) + ps::signed_volume(b));
}

TEST(FanConeDirection, IsTheMaximinDirection) {
  // Three orthogonal normals: the direction equally far from all three.
  const Vec3 d = ps::fan_cone_direction({Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  EXPECT_NEAR((d - Vec3(1, 1, 1).normalized()).norm(), 0.0, 1e-12);
  // A thin blade (two nearly opposite faces and one across their edge, as at stress seed 938)
  // and a wide cone: no direction on a fine sphere sampling does better.
  const std::vector<std::vector<Vec3>> fans = {
      {Vec3(0.0914722, 0.8415, -0.532457).normalized(), Vec3(-0.101857, -0.798802, 0.592908).normalized(),
       Vec3(-0.155878, -0.974685, -0.160284).normalized()},
      {Vec3(1, 0.2, 0).normalized(), Vec3(0.3, 1, 0.1).normalized(), Vec3(0.2, 0.1, 1).normalized(),
       Vec3(1, 1, 0.3).normalized()}};
  for (const auto& u : fans) {
    const Vec3 c = ps::fan_cone_direction(u);
    ASSERT_NEAR(c.norm(), 1.0, 1e-12);
    auto margin = [&](const Vec3& x) {
      double m = 1.0;
      for (const auto& n : u) m = std::min(m, n.dot(x));
      return m;
    };
    EXPECT_GT(margin(c), 0.0);
    double sampled = -1.0;
    const int n = 400000;  // Fibonacci sphere, about 0.3 degrees apart
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
      sampled = std::max(sampled, margin(Vec3(r * std::cos(phi), r * std::sin(phi), z)));
    }
    EXPECT_GE(margin(c), sampled - 1e-12);
  }
}

TEST(FanConeDirection, ZeroWithoutADirectionStrictlyInside) {
  EXPECT_EQ(ps::fan_cone_direction({}), Vec3::Zero());
  EXPECT_EQ(ps::fan_cone_direction({Vec3::UnitX(), -Vec3::UnitX()}), Vec3::Zero());
  // d . x > 0 and d . y > 0 rule out d . (-(x + y)) > 0.
  EXPECT_EQ(ps::fan_cone_direction({Vec3::UnitX(), Vec3::UnitY(), -Vec3(1, 1, 0).normalized()}), Vec3::Zero());
}

}  // namespace
