#pragma once
// Readers for the zone fixture tests/data/zone_nudge_seed9 (see its README.md): the six
// snapped frusta of zone 18 of stress seed 9 and the partition's planes.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <string>
#include <vector>

#include "modeling/mesh_io.h"
#include "modeling/zone_union.h"

namespace ps::testing {

inline const std::string kSeed9ZoneDir = std::string(PLANESKETCH_SOURCE_DIR) + "/tests/data/zone_nudge_seed9/";

inline std::vector<Plane> read_seed9_planes() {
  std::vector<Plane> planes;
  std::ifstream f(kSeed9ZoneDir + "planes.txt");
  double a, b, c, d;
  while (f >> a >> b >> c >> d) {
    Plane p;
    p.normal = Vec3(a, b, c);
    p.offset = d;
    planes.push_back(p);
  }
  return planes;
}

inline std::vector<SnappedSolid> read_seed9_frusta() {
  std::vector<SnappedSolid> out;
  for (int i = 0; i < 6; ++i) {
    SnappedSolid s;
    auto m = read_mesh(kSeed9ZoneDir + "f" + std::to_string(i) + ".obj");
    EXPECT_TRUE(m) << m.message();
    if (!m) return {};
    s.mesh = *m;
    std::ifstream t(kSeed9ZoneDir + "f" + std::to_string(i) + ".tags");
    std::array<int, 3> tag{};
    while (t >> tag[0] >> tag[1] >> tag[2]) s.tags.push_back(tag);
    EXPECT_EQ(s.tags.size(), s.mesh.vertices.size());
    out.push_back(std::move(s));
  }
  return out;
}

// The same zone with frustum 5's free top point 7 (2.8e-17 from frustum 4's top point 11, the
// coincidence of README.md) moved by 1e-12 of frustum 4's diagonal along x: the two walls then
// coincide to more than rounding, which coincident_walls.h leaves alone (it aligns points within
// 1e-14), and corefinement refuses the pair again. The overlap nudge is the fallback for that.
inline std::vector<SnappedSolid> read_seed9_frusta_offset() {
  auto f = read_seed9_frusta();
  if (f.size() != 6) return f;
  EXPECT_LT((f[5].mesh.vertices[7] - f[4].mesh.vertices[11]).norm(), 1e-16);
  EXPECT_LT(f[5].tags[7][0], 0);
  f[5].mesh.vertices[7].x() += 1e-12 * bounding_box(f[4].mesh.vertices).diagonal();
  return f;
}

}  // namespace ps::testing
