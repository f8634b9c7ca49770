// Default scene layout: three reference planes around a bounding box and a camera framing it.
#include <algorithm>
#include <cmath>

#include "engine/scene.h"

namespace ps::engine {

std::optional<View> parse_view(const std::string& name) {
  if (name == "iso") return View::iso;
  if (name == "x") return View::x;
  if (name == "y") return View::y;
  if (name == "z") return View::z;
  return std::nullopt;
}

namespace {
// A box that is never empty or flat (a single point or a planar mesh still gets a frame).
ps::Box3 padded(const ps::Box3& box) {
  if (box.empty()) {
    ps::Box3 b;
    b.extend(ps::Vec3::Constant(-1.0));
    b.extend(ps::Vec3::Constant(1.0));
    return b;
  }
  const double d = std::max(box.diagonal(), 1e-9);
  ps::Box3 b = box;
  for (int k = 0; k < 3; ++k)
    if (b.size()[k] < 1e-3 * d) {
      b.min[k] -= 0.05 * d;
      b.max[k] += 0.05 * d;
    }
  if (box.diagonal() == 0.0) {
    b.extend(box.min - ps::Vec3::Constant(1.0));
    b.extend(box.max + ps::Vec3::Constant(1.0));
  }
  return b;
}
}  // namespace

std::vector<PlaneVisual> basic_planes(const ps::Box3& box_in) {
  const ps::Box3 box = padded(box_in);
  const ps::Vec3 c = box.center();
  const double half = 0.5 * box.size().maxCoeff() * 1.2;
  const Rgba colors[3] = {{0.90f, 0.22f, 0.20f, 0.16f},   // x: red
                          {0.20f, 0.72f, 0.28f, 0.16f},   // y: green
                          {0.20f, 0.42f, 0.95f, 0.16f}};  // z: blue
  std::vector<PlaneVisual> out;
  for (int k = 0; k < 3; ++k) {
    PlaneVisual p;
    p.plane.normal = ps::Vec3::Unit(k);
    p.plane.offset = c[k];
    p.center = c;
    p.half_size = half;
    p.color = colors[k];
    out.push_back(p);
  }
  return out;
}

ps::Camera framing_camera(const ps::Box3& box_in, View view, int width, int height) {
  const ps::Box3 box = padded(box_in);
  ps::Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fov_y_deg = 35.0;
  ps::Vec3 dir = ps::Vec3::UnitZ();  // from target to eye
  cam.up = ps::Vec3::UnitY();
  switch (view) {
    case View::iso: dir = ps::Vec3(1.0, 0.8, 1.2).normalized(); break;
    case View::x: dir = ps::Vec3::UnitX(); break;
    case View::y:
      dir = ps::Vec3::UnitY();
      cam.up = -ps::Vec3::UnitZ();  // x to the right, z down the screen
      break;
    case View::z: dir = ps::Vec3::UnitZ(); break;
  }
  // Fit the three basic planes (which reach 1.2x past the box's half extent): the smallest
  // distance at which every plane corner projects inside 92% of the viewport. For a point at
  // offset q from the target and view axes (s, u, f): depth = dist + f.q must be at least
  // |s.q| / tan(half_fov_x) and |u.q| / tan(half_fov_y).
  cam.target = box.center();
  const ps::Vec3 f = -dir;
  const ps::Vec3 s = f.cross(cam.up).normalized();
  const ps::Vec3 u = s.cross(f);
  const double tan_y = std::tan(0.5 * cam.fov_y_deg * M_PI / 180.0) * 0.92;
  const double tan_x = tan_y * cam.aspect();
  const double half = 0.5 * box.size().maxCoeff() * 1.2;
  double dist = 0.0, radius = 0.0;
  for (const auto& p : basic_planes(box))
    for (int i = -1; i <= 1; i += 2)
      for (int j = -1; j <= 1; j += 2) {
        ps::Vec3 a, b;
        p.plane.basis(a, b);
        const ps::Vec3 q = (p.center - cam.target) + half * (double(i) * a + double(j) * b);
        radius = std::max(radius, q.norm());
        dist = std::max(dist, std::abs(s.dot(q)) / tan_x - f.dot(q));
        dist = std::max(dist, std::abs(u.dot(q)) / tan_y - f.dot(q));
      }
  dist = std::max(dist, 1.05 * radius);  // keep the eye outside the planes
  cam.eye = cam.target + dir * dist;
  cam.near_plane = std::max(dist - 2.0 * radius, dist * 0.02);
  cam.far_plane = dist + 2.0 * radius;
  return cam;
}

Scene default_scene(const ps::TriMesh& mesh, View view, int width, int height, bool wireframe) {
  Scene s;
  const ps::Box3 box = ps::bounding_box(mesh.vertices);
  s.camera = framing_camera(box, view, width, height);
  s.background = {1.f, 1.f, 1.f, 1.f};
  s.planes = basic_planes(box);
  MeshVisual m;
  m.mesh = mesh;
  m.color = {0.78f, 0.74f, 0.68f, 1.f};
  m.wireframe = wireframe;
  s.solid = std::move(m);
  return s;
}

}  // namespace ps::engine
