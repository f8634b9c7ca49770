#pragma once
// A perspective (or orthographic) pinhole camera shared by every layer: modeling lifts window
// strokes onto planes with it, input records it in stroke-log headers, engine renders with it
// (converting to GLM and Vulkan clip space at the upload boundary).
//
// Conventions:
//   Window pixels: x to the right, y DOWN, origin at the top-left corner of the viewport;
//   pixel (i, j) covers [i, i+1) x [j, j+1), its centre is (i + 0.5, j + 0.5).
//   view_matrix(): right-handed look-at; camera looks down -Z in view space.
//   projection_matrix(): OpenGL-style clip space (NDC x,y,z in [-1,1], y up). The engine
//   applies the Vulkan correction (flip y, depth to [0,1]) itself.
//   project(p) and ray(px, py) are exact inverses of each other for points in front.
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"

namespace ps {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
};

// Ray-plane intersection. Returns the ray parameter t >= 0, or nothing when the ray is parallel
// to the plane (|cos| < 1e-9) or the plane lies behind the origin.
inline std::optional<double> intersect(const Ray& r, const Plane& pl) {
  const double denom = pl.normal.dot(r.direction);
  if (std::abs(denom) < 1e-9) return std::nullopt;
  const double t = (pl.offset - pl.normal.dot(r.origin)) / denom;
  if (!(t >= 0.0) || !std::isfinite(t)) return std::nullopt;
  return t;
}

struct Camera {
  Vec3 eye{3.0, 2.5, 4.0};
  Vec3 target{0.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_y_deg = 40.0;   // perspective vertical field of view
  bool orthographic = false;
  double ortho_height = 4.0;  // visible height in scene units when orthographic
  double near_plane = 0.01;
  double far_plane = 100.0;
  int width = 1280;
  int height = 800;

  double aspect() const { return static_cast<double>(width) / static_cast<double>(height); }

  Eigen::Matrix4d view_matrix() const {
    const Vec3 f = (target - eye).normalized();
    const Vec3 s = f.cross(up).normalized();
    const Vec3 u = s.cross(f);
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = f.dot(eye);
    return m;
  }

  Eigen::Matrix4d projection_matrix() const {
    Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
    const double n = near_plane, fa = far_plane;
    if (orthographic) {
      const double t = 0.5 * ortho_height, r = t * aspect();
      p(0, 0) = 1.0 / r;
      p(1, 1) = 1.0 / t;
      p(2, 2) = -2.0 / (fa - n);
      p(2, 3) = -(fa + n) / (fa - n);
      p(3, 3) = 1.0;
    } else {
      const double t = std::tan(0.5 * fov_y_deg * M_PI / 180.0);
      p(0, 0) = 1.0 / (aspect() * t);
      p(1, 1) = 1.0 / t;
      p(2, 2) = -(fa + n) / (fa - n);
      p(2, 3) = -2.0 * fa * n / (fa - n);
      p(3, 2) = -1.0;
    }
    return p;
  }

  // World point -> window pixel (x right, y down) and NDC depth. Nothing if behind the eye.
  std::optional<Vec3> project(const Vec3& p) const {
    const Eigen::Vector4d c = projection_matrix() * view_matrix() * p.homogeneous();
    if (!(c.w() > 0.0)) return std::nullopt;
    const Vec3 ndc = c.head<3>() / c.w();
    return Vec3((ndc.x() + 1.0) * 0.5 * width, (1.0 - ndc.y()) * 0.5 * height, ndc.z());
  }

  // The ray through window pixel position (px, py) (continuous pixel coordinates).
  Ray ray(double px, double py) const {
    const double nx = 2.0 * px / width - 1.0;
    const double ny = 1.0 - 2.0 * py / height;
    const Vec3 f = (target - eye).normalized();
    const Vec3 s = f.cross(up).normalized();
    const Vec3 u = s.cross(f);
    if (orthographic) {
      const double t = 0.5 * ortho_height, r = t * aspect();
      return Ray{eye + s * (nx * r) + u * (ny * t), f};
    }
    const double t = std::tan(0.5 * fov_y_deg * M_PI / 180.0);
    const Vec3 d = (f + s * (nx * t * aspect()) + u * (ny * t)).normalized();
    return Ray{eye, d};
  }

  // Lift a window point onto a plane through this camera; nothing if the ray misses it.
  std::optional<Vec3> lift(double px, double py, const Plane& pl) const {
    const Ray r = ray(px, py);
    const auto t = intersect(r, pl);
    if (!t) return std::nullopt;
    return Vec3(r.origin + *t * r.direction);
  }
};

}  // namespace ps
