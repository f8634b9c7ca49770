// Connectors between frusta that meet on a zone edge (frustum_connectors.h): two frusta that
// touch only along their shared edge make CGAL refuse the union as non-manifold; with the
// connector the union is a closed manifold whose boundary on the zone faces is exactly the two
// bottoms.
#include <gtest/gtest.h>

#include <cmath>

#include "modeling/frustum_connectors.h"
#include "modeling/mesh_topology.h"
#include "modeling/zone_union.h"

namespace ps {
namespace {

using Tags = std::array<int, 3>;

// A prism over a convex quad (bottom first, then top = bottom + t: frustum_builder's layout),
// outward oriented.
SnappedSolid prism(const std::array<Vec3, 4>& bottom, const Vec3& t, const std::array<Tags, 4>& tags) {
  SnappedSolid s;
  for (const auto& p : bottom) s.mesh.vertices.push_back(p);
  for (const auto& p : bottom) s.mesh.vertices.push_back(p + t);
  for (const auto& g : tags) s.tags.push_back(g);
  for (int i = 0; i < 4; ++i) s.tags.push_back({-1, -1, -1});
  s.mesh.faces = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    s.mesh.faces.push_back({j, i, 4 + i});
    s.mesh.faces.push_back({j, 4 + i, 4 + j});
  }
  if (signed_volume(s.mesh) < 0)
    for (auto& f : s.mesh.faces) std::swap(f[1], f[2]);
  return s;
}

// Area of the faces lying in the plane coordinate[axis] == 0.
double area_on(const TriMesh& m, int axis) {
  double a = 0;
  for (const auto& f : m.faces) {
    const Vec3& p = m.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& q = m.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& r = m.vertices[static_cast<std::size_t>(f[2])];
    if (p[axis] == 0.0 && q[axis] == 0.0 && r[axis] == 0.0) a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

// Zone faces z = 0 (plane 0) and x = 0 (plane 1), dihedral 90 degrees. Frustum A on z = 0 is
// sheared flat towards +x, frustum B on x = 0 flat towards +z: A is {x >= 10 z}, B is
// {z >= 10 x} near the edge, so they share the edge y in [0, 1] and nothing else (the wedge
// of armadillo's zone 44, where the walls stood at 90 and 137 degrees in 142).
struct Wedge {
  std::vector<Plane> planes{Plane{Vec3::UnitZ(), 0.0}, Plane{Vec3::UnitX(), 0.0}};
  SnappedSolid a = prism({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}, Vec3(0.1, 0, 0.01),
                         {Tags{0, 1, -1}, Tags{0, -1, -1}, Tags{0, -1, -1}, Tags{0, 1, -1}});
  SnappedSolid b = prism({Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1)}, Vec3(0.01, 0, 0.1),
                         {Tags{1, 0, -1}, Tags{1, 0, -1}, Tags{1, -1, -1}, Tags{1, -1, -1}});
};

TEST(FrustumConnectors, FillTheWedgeBetweenFrustaMeetingOnAnEdge) {
  const Wedge w;
  // Without a connector, CGAL refuses the union (the shared edge would carry four faces).
  auto plain = union_snapped_solids({w.a, w.b}, w.planes);
  ASSERT_FALSE(plain);
  EXPECT_NE(plain.message().find("2-manifold"), std::string::npos) << plain.message();

  int added = 0;
  const std::vector<SnappedSolid> with = with_frustum_connectors({w.a, w.b}, w.planes, &added);
  ASSERT_EQ(added, 1);
  ASSERT_EQ(with.size(), 3u);
  // The connector comes right after the first frustum of its pair.
  EXPECT_EQ(with[0].mesh.vertices, w.a.mesh.vertices);
  EXPECT_EQ(with[2].mesh.vertices, w.b.mesh.vertices);
  // It lies in the zone (x >= 0, z >= 0) and touches the zone faces only on the shared edge.
  for (const auto& p : with[1].mesh.vertices) {
    EXPECT_GE(p.x(), 0.0);
    EXPECT_GE(p.z(), 0.0);
    if (p.x() == 0.0 || p.z() == 0.0) {
      EXPECT_TRUE(p.x() == 0.0 && p.z() == 0.0) << p.transpose();
    }
  }

  for (const auto& order : {std::vector<int>{0, 1, 2}, std::vector<int>{2, 1, 0}, std::vector<int>{1, 0, 2}}) {
    std::vector<SnappedSolid> list;
    for (int i : order) list.push_back(with[static_cast<std::size_t>(i)]);
    auto u = union_snapped_solids(list, w.planes);
    ASSERT_TRUE(u) << u.message();
    const MeshTopology t = mesh_topology(*u);
    EXPECT_TRUE(t.closed);
    EXPECT_TRUE(t.manifold());
    EXPECT_TRUE(t.consistently_oriented);
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.genus, 0);
    // No material is removed, and the wedge between the walls is filled.
    const double va = signed_volume(w.a.mesh), vb = signed_volume(w.b.mesh);
    EXPECT_GT(signed_volume(*u), va + vb);
    // The boundary on the zone faces is exactly the two bottoms.
    EXPECT_NEAR(area_on(*u, 2), 1.0, 1e-12);
    EXPECT_NEAR(area_on(*u, 0), 1.0, 1e-12);
  }
}

TEST(FrustumConnectors, NoneWithoutSharedPoints) {
  const Wedge w;
  SnappedSolid far = w.b;
  for (auto& p : far.mesh.vertices) p.y() += 2.0;  // same shape, no point in common with A
  int added = -1;
  const auto with = with_frustum_connectors({w.a, far}, w.planes, &added);
  EXPECT_EQ(added, 0);
  ASSERT_EQ(with.size(), 2u);
  EXPECT_EQ(with[1].mesh.vertices, far.mesh.vertices);
}

TEST(FrustumConnectors, TaggedTopsAreLeftOut) {
  // A top point kept on a zone face (tagged) must not enter a connector: the connector would
  // then add boundary on that face. A's top over its corner (1, 1, 0) lies on y = 1 (plane 2)
  // and is next to the shared run: tagged, it is left out; the wedge is filled all the same.
  Wedge w;
  w.planes.push_back(Plane{Vec3::UnitY(), 1.0});
  const Vec3 kept = w.a.mesh.vertices[6];
  ASSERT_EQ(kept, Vec3(1.1, 1.0, 0.01));
  w.a.tags[6] = {2, -1, -1};
  int added = 0;
  const auto with = with_frustum_connectors({w.a, w.b}, w.planes, &added);
  ASSERT_EQ(added, 1);
  for (const auto& p : with[1].mesh.vertices) EXPECT_NE(p, kept);
  auto u = union_snapped_solids(with, w.planes);
  ASSERT_TRUE(u) << u.message();
  EXPECT_TRUE(mesh_topology(*u).manifold());
}

}  // namespace
}  // namespace ps
