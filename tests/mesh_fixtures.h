#pragma once
// Procedural closed meshes shared by tests and benchmarks (no data files needed).
#include <cmath>

#include "modeling/camera.h"
#include "modeling/mesh.h"

namespace ps::testing {

// The sculpting tests' view: from (0, 0, 4) towards the origin, y up, 640 x 480, fov 40 deg.
inline Camera front_camera() {
  Camera c;
  c.eye = Vec3(0, 0, 4);
  c.target = Vec3::Zero();
  c.up = Vec3(0, 1, 0);
  c.width = 640;
  c.height = 480;
  return c;
}

// A UV sphere around c (poles on the y axis) with 2 * segments * (rings - 1) outward triangles.
inline TriMesh uv_sphere(const Vec3& c, double r, int rings, int segments) {
  TriMesh m;
  m.vertices.push_back(c + Vec3(0, r, 0));
  for (int i = 1; i < rings; ++i) {
    const double th = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * M_PI * j / segments;
      m.vertices.push_back(c + r * Vec3(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph)));
    }
  }
  m.vertices.push_back(c + Vec3(0, -r, 0));
  const int south = int(m.vertices.size()) - 1;
  const auto at = [&](int ring, int seg) { return 1 + (ring - 1) * segments + (seg % segments); };
  for (int j = 0; j < segments; ++j) m.faces.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.faces.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  return m;
}

// A torus around c in the xz plane (axis y), radii big > small, nu x nv quads split in two.
inline TriMesh torus(const Vec3& c, double big, double small, int nu, int nv) {
  TriMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.vertices.push_back(c + Vec3((big + small * std::cos(v)) * std::cos(u), small * std::sin(v),
                                    (big + small * std::cos(v)) * std::sin(u)));
    }
  const auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
      m.faces.push_back({id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  return m;
}

}  // namespace ps::testing
