#pragma once
// Cross sections: closed planar curves on planes (thesis 3.3.2, chapters 4 and 6).
//
// Conventions:
//   Plane:        the points p with normal.dot(p) == offset; normal has unit length.
//   CrossSection: one closed polyline on planes[plane]; the last point connects to the first,
//                 which is NOT repeated. At least 3 points. Orientation carries no meaning;
//                 nesting on one plane does (rule 2: from the outermost curve inward,
//                 region, hole, region, ...).
//   SectionSet:   planes and the curves on them. Orthogonal input is the special case where
//                 every normal is a coordinate axis.
#include <string>
#include <vector>

#include "modeling/mesh.h"

namespace ps {

struct Plane {
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;

  double signed_distance(const Vec3& p) const { return normal.dot(p) - offset; }
  Vec3 project(const Vec3& p) const { return p - signed_distance(p) * normal; }
  // An orthonormal basis (u, v) of the plane with u x v == normal.
  void basis(Vec3& u, Vec3& v) const {
    const Vec3 a = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    u = normal.cross(a).normalized();
    v = normal.cross(u);
  }
  // Which coordinate axis the normal is (0, 1, 2), or -1 if not axis-aligned.
  int axis() const {
    for (int k = 0; k < 3; ++k)
      if (std::abs(std::abs(normal[k]) - 1.0) < 1e-12) return k;
    return -1;
  }
};

struct CrossSection {
  int plane = -1;
  std::vector<Vec3> points;
};

struct SectionSet {
  std::vector<Plane> planes;
  std::vector<CrossSection> curves;
  std::string units;

  bool is_orthogonal() const {
    for (const auto& p : planes)
      if (p.axis() < 0) return false;
    return true;
  }
  std::vector<Vec3> all_points() const {
    std::vector<Vec3> out;
    for (const auto& c : curves) out.insert(out.end(), c.points.begin(), c.points.end());
    return out;
  }
};

}  // namespace ps
