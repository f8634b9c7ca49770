#pragma once
// Geometry as values: a triangle mesh is a copyable, movable value.
//
// Shapes and conventions (libigl style):
//   vertices: #V positions (double precision).
//   faces:    #F triangles, 0-based vertex indices, counter-clockwise seen from outside,
//             so the right-hand normal points out of a closed mesh and its signed volume is > 0.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <array>
#include <type_traits>
#include <vector>

namespace ps {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Face = std::array<int, 3>;

static_assert(std::is_trivially_copyable_v<Face>);

struct TriMesh {
  std::vector<Vec3> vertices;
  std::vector<Face> faces;

  bool empty() const { return faces.empty(); }
  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_faces() const { return faces.size(); }
};

// Axis-aligned bounding box of a point set; empty() when no points.
struct Box3 {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
  bool empty() const { return !(min.x() <= max.x()); }
  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 size() const { return max - min; }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
};

inline Box3 bounding_box(const std::vector<Vec3>& pts) {
  Box3 b;
  for (const auto& p : pts) b.extend(p);
  return b;
}

}  // namespace ps
