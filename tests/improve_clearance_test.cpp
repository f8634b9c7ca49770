// The clearance limit of mesh improvement's smoothing (modeling/smoothing_clearance.h): the
// point-triangle distance against dense sampling; moves through a thin slab shortened so that
// the sheets no longer cross; moves far from any facing sheet kept bit for bit, moves near one
// limited in every direction, and only the vertices asked for; improve_mesh on
// thin slabs with the limit off, automatic and always on, and on a flat ellipsoid that never
// turns the automatic limit on; the grid search against every face, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "modeling/face_intersections.h"
#include "modeling/mesh_improve.h"
#include "modeling/mesh_topology.h"
#include "modeling/point_triangle_distance.h"
#include "modeling/smoothing_clearance.h"
#include "tests/mesh_fixtures.h"

using namespace ps;

namespace {

// A closed box [0,1] x [0,1] x [0,gap]: top and bottom are n x n grids (normals +z and -z), the
// four sides one strip of two triangles per grid step.
TriMesh slab(int n, double gap) {
  TriMesh m;
  auto grid = [&](double z) {
    const int base = static_cast<int>(m.vertices.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) m.vertices.push_back(Vec3(static_cast<double>(i) / n, static_cast<double>(j) / n, z));
    return base;
  };
  const int bottom = grid(0.0), top = grid(gap);
  auto id = [&](int base, int i, int j) { return base + i * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.faces.push_back({id(top, i, j), id(top, i + 1, j), id(top, i + 1, j + 1)});
      m.faces.push_back({id(top, i, j), id(top, i + 1, j + 1), id(top, i, j + 1)});
      m.faces.push_back({id(bottom, i, j), id(bottom, i + 1, j + 1), id(bottom, i + 1, j)});
      m.faces.push_back({id(bottom, i, j), id(bottom, i, j + 1), id(bottom, i + 1, j + 1)});
    }
  // Sides: walk the boundary of the grid counter-clockwise seen from +z.
  std::vector<std::array<int, 2>> ring;
  for (int i = 0; i < n; ++i) ring.push_back({i, 0});
  for (int j = 0; j < n; ++j) ring.push_back({n, j});
  for (int i = n; i > 0; --i) ring.push_back({i, n});
  for (int j = n; j > 0; --j) ring.push_back({0, j});
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto a = ring[k], b = ring[(k + 1) % ring.size()];
    const int a0 = id(bottom, a[0], a[1]), b0 = id(bottom, b[0], b[1]);
    const int a1 = id(top, a[0], a[1]), b1 = id(top, b[0], b[1]);
    m.faces.push_back({a0, b0, b1});
    m.faces.push_back({a0, b1, a1});
  }
  return m;
}

}  // namespace

TEST(SmoothingClearance, PointTriangleDistanceMatchesSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3 p = 2.0 * Vec3(u(rng), u(rng), u(rng));
    const double d = point_triangle_distance(p, a, b, c);
    double sampled = 1e300;
    constexpr int k = 120;
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double s = static_cast<double>(i) / k, t = static_cast<double>(j) / k;
        sampled = std::min(sampled, (p - (a + s * (b - a) + t * (c - a))).norm());
      }
    const double spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / k;
    EXPECT_LE(d, sampled + 1e-12) << trial;          // the exact closest point is no farther
    EXPECT_GE(d, sampled - spacing) << trial;        // and the samples come within a step of it
  }
  // Each region: a vertex, an edge, the face.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(-3, -4, 0), a, b, c), 5.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0.5, -2, 0), a, b, c), 2.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(0.25, 0.25, -3), a, b, c), 3.0);
  EXPECT_NEAR(point_triangle_distance(Vec3(1, 1, 0), a, b, c), std::sqrt(0.5), 1e-15);
}

TEST(SmoothingClearance, MovesThroughAThinSlabAreShortened) {
  const double gap = 0.01;
  const TriMesh m = slab(10, gap);
  ASSERT_TRUE(self_intersecting_pairs(m).empty());
  // Top and bottom sheets pushed through each other (interior grid points only, so the sides
  // stay put): 2.5 gaps each.
  std::vector<Vec3> moved = m.vertices;
  for (auto& p : moved) {
    const bool interior = p.x() > 1e-9 && p.x() < 1 - 1e-9 && p.y() > 1e-9 && p.y() < 1 - 1e-9;
    if (interior) p.z() += p.z() > 0.5 * gap ? -2.5 * gap : 2.5 * gap;
  }
  TriMesh crossed = m;
  crossed.vertices = moved;
  ASSERT_FALSE(self_intersecting_pairs(crossed).empty());

  const int limited = limit_moves_by_clearance(moved, m.vertices, m.faces);
  EXPECT_EQ(limited, 2 * 9 * 9);  // every moved vertex
  for (std::size_t v = 0; v < moved.size(); ++v) {
    const double d = (moved[v] - m.vertices[v]).norm();
    EXPECT_LE(d, kClearanceShare * gap * (1 + 1e-12)) << v;
    // Shortened along its own direction, not turned.
    if (d > 0) {
      EXPECT_NEAR(std::abs(moved[v].z() - m.vertices[v].z()), d, 1e-15);
    }
  }
  crossed.vertices = moved;
  EXPECT_TRUE(self_intersecting_pairs(crossed).empty());
}

TEST(SmoothingClearance, FarSheetsLeaveMovesBitForBitNearOnesLimitEveryDirection) {
  // A sphere of radius 1 with small random moves: the only faces facing a vertex are on the far
  // side, 2 away, so nothing is limited and every position is kept exactly.
  const TriMesh s = ps::testing::uv_sphere(Vec3::Zero(), 1.0, 24, 48);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  std::vector<Vec3> moved = s.vertices;
  for (auto& p : moved) p += Vec3(u(rng), u(rng), u(rng));
  const std::vector<Vec3> before = moved;
  EXPECT_EQ(limit_moves_by_clearance(moved, s.vertices, s.faces), 0);
  EXPECT_EQ(moved, before);
  // On a slab with sheets 0.01 apart the limit bounds what both sheets may do, whatever the
  // direction: moves of 0.3 away from the other sheet, or 0.05 along the sheets, are shortened
  // to 0.4 of the gap as well (a curved sheet moved along its tangent leaves its surface, and a
  // rim moved outward drags faces across the other sheet). With only = the top sheet, the
  // bottom one keeps its moves.
  const TriMesh m = slab(8, 0.01);
  auto interior = [](const Vec3& p) { return p.x() > 1e-9 && p.x() < 1 - 1e-9 && p.y() > 1e-9 && p.y() < 1 - 1e-9; };
  for (const Vec3& step : {Vec3(0, 0, 0.3), Vec3(0.05, 0.03, 0)}) {
    std::vector<Vec3> out = m.vertices;
    for (auto& p : out)
      if (interior(p)) p += p.z() > 0.005 ? step : Vec3(-step);
    std::vector<Vec3> top_only = out;
    EXPECT_EQ(limit_moves_by_clearance(out, m.vertices, m.faces), 2 * 7 * 7);
    for (std::size_t v = 0; v < out.size(); ++v)
      EXPECT_LE((out[v] - m.vertices[v]).norm(), kClearanceShare * 0.01 * (1 + 1e-12));
    std::vector<std::uint8_t> top(m.vertices.size(), 0);
    for (std::size_t v = 0; v < top.size(); ++v) top[v] = m.vertices[v].z() > 0.005;
    const std::vector<Vec3> unlimited = top_only;
    EXPECT_EQ(limit_moves_by_clearance(top_only, m.vertices, m.faces, &top), 7 * 7);
    for (std::size_t v = 0; v < out.size(); ++v)
      EXPECT_EQ(top_only[v], top[v] ? out[v] : unlimited[v]) << v;
  }
}

// improve_mesh on thin slabs (sheets 0.002 and 0.005 apart, edges 0.1 and 0.06 long): without the
// limit, smoothing rounds the rims by pushing the sheets through each other and the check undoes
// hundreds of moves; with it (kAuto turns it on after the first such round) almost none. Every
// result is a valid solid. A flat ellipsoid whose smoothing makes few crossings (under 1 in 32)
// never turns kAuto on, so its result is bit for bit the one without the limit.
TEST(SmoothingClearance, ImprovementOfThinParts) {
  using CL = ImproveOptions::ClearanceLimit;
  auto run = [](const TriMesh& m, CL mode, ImproveReport& r) {
    ImproveOptions o;
    o.clearance_limit = mode;
    auto out = improve_mesh(m, std::vector<bool>(m.vertices.size(), false), {}, o, &r);
    EXPECT_TRUE(out) << out.message();
    if (!out) return TriMesh{};
    EXPECT_TRUE(self_intersecting_pairs(*out).empty());
    const auto t = mesh_topology(*out);
    EXPECT_TRUE(t.closed && t.manifold() && t.consistently_oriented);
    return *out;
  };
  for (const auto& [n, gap] : {std::pair{10, 0.002}, std::pair{16, 0.005}}) {
    const TriMesh m = slab(n, gap);
    ImproveReport off, on, always;
    run(m, CL::kOff, off);
    run(m, CL::kAuto, on);
    run(m, CL::kAlways, always);
    std::printf("slab %d x %g: moves undone after crossing %d without the limit, %d (auto), %d (always); limited %d / %d\n",
                n, gap, off.crossing_rollbacks, on.crossing_rollbacks, always.crossing_rollbacks, on.clearance_limits, always.clearance_limits);
    EXPECT_EQ(off.clearance_limits, 0);
    EXPECT_GT(off.crossing_rollbacks, 300);
    EXPECT_GT(on.clearance_limits, 0);
    EXPECT_LT(10 * on.crossing_rollbacks, off.crossing_rollbacks);
    EXPECT_LT(10 * always.crossing_rollbacks, off.crossing_rollbacks);
  }
  TriMesh e = ps::testing::uv_sphere(Vec3::Zero(), 1.0, 20, 64);
  for (auto& p : e.vertices) p.z() *= 0.01;
  ImproveReport off, on;
  const TriMesh a = run(e, CL::kOff, off), b = run(e, CL::kAuto, on);
  EXPECT_EQ(on.clearance_limits, 0);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.faces, b.faces);
}

// The grid search (and its half-reach first stage) against every face, on a thin spherical shell
// (sheets 0.02 apart, random moves up to 0.014 so that reaches run from below to above
// the gap), near the origin and translated by 1000 (where the rounding of the search cube's
// corners is largest): the limited positions are bit for bit those of the brute-force rule.
TEST(SmoothingClearance, GridSearchEqualsEveryFace) {
  for (const double offset : {0.0, 1000.0}) {
    TriMesh outer = ps::testing::uv_sphere(Vec3::Zero(), 1.0, 20, 40);
    const TriMesh inner = ps::testing::uv_sphere(Vec3::Zero(), 0.98, 20, 40);
    const int base = static_cast<int>(outer.vertices.size());
    for (const Vec3& p : inner.vertices) outer.vertices.push_back(p);
    for (const Face& f : inner.faces) outer.faces.push_back({f[0] + base, f[2] + base, f[1] + base});  // inward
    for (Vec3& p : outer.vertices) p += Vec3::Constant(offset);
    const TriMesh& m = outer;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.008, 0.008);
    std::vector<Vec3> moved = m.vertices;
    for (auto& p : moved) p += Vec3(u(rng), u(rng), u(rng));

    // Brute force: the rule of smoothing_clearance.h over every face.
    const std::size_t nv = m.vertices.size();
    std::vector<Vec3> face_n(m.faces.size()), vertex_n(nv, Vec3::Zero());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      const Face& fc = m.faces[f];
      const Vec3 n = (m.vertices[static_cast<std::size_t>(fc[1])] - m.vertices[static_cast<std::size_t>(fc[0])])
                         .cross(m.vertices[static_cast<std::size_t>(fc[2])] - m.vertices[static_cast<std::size_t>(fc[0])]);
      for (int v : fc) vertex_n[static_cast<std::size_t>(v)] += n;
      face_n[f] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
    }
    std::vector<Vec3> expected = moved;
    int expected_count = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      const Vec3& r = m.vertices[v];
      const Vec3 move = moved[v] - r;
      const double d = move.norm();
      const Vec3 vn = vertex_n[v].norm() > 0 ? Vec3(vertex_n[v].normalized()) : Vec3::Zero();
      if (!(d > 0) || vn == Vec3::Zero()) continue;
      const double limit = d / kClearanceShare;
      double best = limit;
      for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Face& fc = m.faces[f];
        const float dot = static_cast<float>(face_n[f].x()) * static_cast<float>(vn.x()) +
                          static_cast<float>(face_n[f].y()) * static_cast<float>(vn.y()) +
                          static_cast<float>(face_n[f].z()) * static_cast<float>(vn.z());
        if (!(dot < 0.0f)) continue;
        if (fc[0] == static_cast<int>(v) || fc[1] == static_cast<int>(v) || fc[2] == static_cast<int>(v)) continue;
        best = std::min(best, point_triangle_distance(r, m.vertices[static_cast<std::size_t>(fc[0])],
                                                      m.vertices[static_cast<std::size_t>(fc[1])],
                                                      m.vertices[static_cast<std::size_t>(fc[2])]));
      }
      const double allowed = kClearanceShare * best;
      if (best < limit && d > allowed) {
        expected[v] = r + (allowed / d) * move;
        ++expected_count;
      }
    }
    ASSERT_GT(expected_count, 100) << offset;                          // the shell limits many moves
    ASSERT_LT(expected_count, static_cast<int>(nv) - 100) << offset;  // and leaves many alone
    EXPECT_EQ(limit_moves_by_clearance(moved, m.vertices, m.faces), expected_count) << offset;
    for (std::size_t v = 0; v < nv; ++v) EXPECT_EQ(moved[v], expected[v]) << offset << " vertex " << v;
  }
}
