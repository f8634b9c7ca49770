#pragma once
// Jaggy closed inputs for the mesh-improvement tests and benchmark (header-only, test code).
//
// staircase(): a union-like "cylinder of slabs" around the z axis, like the initial
// reconstruction of a stack of circular cross sections. Slab k spans z in [k h - h/2, k h + h/2]
// with radius R(k h), R(z) = 1 + 0.3 sin(1.3 z / h); its side is two bands of long triangles
// split by the section ring at z = k h (the curve: fixed vertices and edges); neighbouring
// slabs are joined by flat annular steps, and the ends are closed by flat fans of thin
// triangles. Vertex i of ring j has angle 2 pi i / n.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "modeling/mesh.h"

namespace ps::testing {

struct JaggyInput {
  TriMesh mesh;
  std::vector<bool> fixed_vertex;
  std::vector<std::array<int, 2>> fixed_edges;
  double h = 1.0;  // slab height
  int slabs = 0;
  double radius_at(double z) const { return 1.0 + 0.3 * std::sin(1.3 * z / h); }
};

inline JaggyInput staircase(int slabs, int n, double h = 1.0) {
  JaggyInput in;
  in.h = h;
  in.slabs = slabs;
  TriMesh& m = in.mesh;
  auto ring = [&](double r, double z) {
    const int first = static_cast<int>(m.vertices.size());
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * std::numbers::pi * i / n;
      m.vertices.emplace_back(r * std::cos(t), r * std::sin(t), z);
    }
    return first;
  };
  auto band = [&](int a, int b) {  // ring a below ring b (along the surface), outward faces
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      m.faces.push_back({a + i, a + j, b + j});
      m.faces.push_back({a + i, b + j, b + i});
    }
  };
  std::vector<int> curve_rings;
  int previous_top = -1;
  int first_bottom = -1;
  for (int k = 0; k < slabs; ++k) {
    const double z = k * h, r = in.radius_at(z);
    const int bottom = ring(r, z - 0.5 * h);
    const int curve = ring(r, z);
    const int top = ring(r, z + 0.5 * h);
    curve_rings.push_back(curve);
    if (previous_top >= 0) band(previous_top, bottom);
    if (first_bottom < 0) first_bottom = bottom;
    band(bottom, curve);
    band(curve, top);
    previous_top = top;
  }
  const int c0 = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0.0, 0.0, -0.5 * h);
  const int c1 = c0 + 1;
  m.vertices.emplace_back(0.0, 0.0, (slabs - 1) * h + 0.5 * h);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({c0, first_bottom + j, first_bottom + i});
    m.faces.push_back({c1, previous_top + i, previous_top + j});
  }
  in.fixed_vertex.assign(m.vertices.size(), false);
  for (int c : curve_rings)
    for (int i = 0; i < n; ++i) {
      in.fixed_vertex[static_cast<std::size_t>(c + i)] = true;
      in.fixed_edges.push_back({c + i, c + (i + 1) % n});
    }
  return in;
}

// Marks as fixed the loop(s) of edges between faces whose centroid lies above `z` and the rest.
inline void fix_level_loop(const TriMesh& m, double z, std::vector<bool>& fixed_vertex,
                           std::vector<std::array<int, 2>>& fixed_edges) {
  fixed_vertex.assign(m.vertices.size(), false);
  fixed_edges.clear();
  auto above = [&](const Face& f) {
    return (m.vertices[static_cast<std::size_t>(f[0])].z() + m.vertices[static_cast<std::size_t>(f[1])].z() +
            m.vertices[static_cast<std::size_t>(f[2])].z()) / 3.0 > z;
  };
  // Directed edges of "above" faces whose reverse belongs to a face below.
  std::vector<std::array<int, 2>> up, down;
  for (const Face& f : m.faces)
    for (int k = 0; k < 3; ++k) {
      const std::array<int, 2> e{f[static_cast<std::size_t>(k)], f[static_cast<std::size_t>((k + 1) % 3)]};
      (above(f) ? up : down).push_back(e);
    }
  std::sort(down.begin(), down.end());
  for (const auto& e : up)
    if (std::binary_search(down.begin(), down.end(), std::array<int, 2>{e[1], e[0]})) {
      fixed_edges.push_back(e);
      fixed_vertex[static_cast<std::size_t>(e[0])] = fixed_vertex[static_cast<std::size_t>(e[1])] = true;
    }
}

}  // namespace ps::testing
