// Scene -> vertex arrays (CPU only). Ribbons are expanded on the CPU in clip space because
// strokes are small (thousands of points) and this keeps one simple vertex shader for all
// coloured geometry; meshes are the heavy part and are cached by the renderer.
#include "engine/frame_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

namespace ps::engine {

Eigen::Matrix4d vulkan_clip_matrix(const ps::Camera& cam) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Identity();
  c(1, 1) = -1.0;  // Vulkan NDC y points down, as window pixels do
  c(2, 2) = 0.5;   // depth [-1, 1] -> [0, 1]
  c(2, 3) = 0.5;
  return c * cam.projection_matrix() * cam.view_matrix();
}

glm::mat4 vulkan_view_projection(const ps::Camera& cam) {
  const Eigen::Matrix4d m = vulkan_clip_matrix(cam);
  glm::mat4 out(1.f);
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) out[col][row] = static_cast<float>(m(row, col));
  return out;
}

namespace {

glm::vec4 to_glm(const Eigen::Vector4d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()),
          static_cast<float>(v.w())};
}
glm::vec4 to_glm(const Rgba& c) { return {c.r, c.g, c.b, c.a}; }

// Move p towards the camera along its viewing ray by `fraction` of its view depth.
ps::Vec3 pull_towards_camera(const ps::Camera& cam, const ps::Vec3& p, double fraction) {
  if (fraction == 0.0) return p;
  if (!cam.orthographic) return p + (cam.eye - p) * fraction;
  const ps::Vec3 f = (cam.target - cam.eye).normalized();
  return p - f * (fraction * std::abs(f.dot(p - cam.eye)));
}

struct RibbonPoint {
  Eigen::Vector4d clip;
  double half_width;  // pixels
};

// Segments of the polyline with clip.w >= w_min, split where the line passes behind the near
// plane (clip coordinates are affine in the world point, so interpolating them is exact).
std::vector<std::vector<RibbonPoint>> clip_runs(const std::vector<RibbonPoint>& pts, double w_min) {
  std::vector<std::vector<RibbonPoint>> runs;
  std::vector<RibbonPoint> run;
  const auto lerp = [](const RibbonPoint& a, const RibbonPoint& b, double t) {
    return RibbonPoint{a.clip + t * (b.clip - a.clip),
                       a.half_width + t * (b.half_width - a.half_width)};
  };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const bool in = pts[i].clip.w() >= w_min;
    if (i > 0) {
      const RibbonPoint& a = pts[i - 1];
      const bool a_in = a.clip.w() >= w_min;
      if (a_in != in) {
        const double t = (w_min - a.clip.w()) / (pts[i].clip.w() - a.clip.w());
        run.push_back(lerp(a, pts[i], t));
        if (!in) {
          runs.push_back(std::move(run));
          run.clear();
        }
      }
    }
    if (in) run.push_back(pts[i]);
  }
  if (run.size() >= 2) runs.push_back(std::move(run));
  std::erase_if(runs, [](const auto& r) { return r.size() < 2; });
  return runs;
}

void emit_run(const std::vector<RibbonPoint>& run_in, bool closed_loop, double half_w,
              double half_h, const glm::vec4& color, std::vector<ColorVertex>& out) {
  // === Screen positions (pixels from the viewport centre); drop repeated points
  std::vector<RibbonPoint> run;
  std::vector<Eigen::Vector2d> s;
  for (const auto& p : run_in) {
    const Eigen::Vector2d sp(p.clip.x() / p.clip.w() * half_w, p.clip.y() / p.clip.w() * half_h);
    if (!s.empty() && (sp - s.back()).norm() < 1e-6) {
      run.back().half_width = std::max(run.back().half_width, p.half_width);
      continue;
    }
    s.push_back(sp);
    run.push_back(p);
  }
  if (closed_loop && s.size() > 2 && (s.front() - s.back()).norm() < 1e-6) {
    s.pop_back();
    run.pop_back();
  }
  const std::size_t n = run.size();
  if (n < 2) return;
  const std::size_t nseg = closed_loop ? n : n - 1;
  std::vector<Eigen::Vector2d> normal(nseg);
  for (std::size_t j = 0; j < nseg; ++j) {
    const Eigen::Vector2d d = (s[(j + 1) % n] - s[j]).normalized();
    normal[j] = Eigen::Vector2d(-d.y(), d.x());
  }

  // === Offsets: mitred joints, capped at twice the half width
  std::vector<Eigen::Vector4d> left(n), right(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector2d m;
    double scale = 1.0;
    const bool has_prev = closed_loop || i > 0;
    const bool has_next = closed_loop || i + 1 < n;
    if (has_prev && has_next) {
      const Eigen::Vector2d& a = normal[(i + nseg - 1) % nseg];
      const Eigen::Vector2d& b = normal[i % nseg];
      const Eigen::Vector2d sum = a + b;
      m = sum.norm() > 1e-9 ? Eigen::Vector2d(sum.normalized()) : b;
      scale = 1.0 / std::max(m.dot(b), 0.5);
    } else {
      m = has_next ? normal[i] : normal[nseg - 1];
    }
    const Eigen::Vector2d off_px = m * (run[i].half_width * scale);
    const double w = run[i].clip.w();
    const Eigen::Vector4d off(off_px.x() / half_w * w, off_px.y() / half_h * w, 0.0, 0.0);
    left[i] = run[i].clip + off;
    right[i] = run[i].clip - off;
  }

  // === Two triangles per segment
  for (std::size_t j = 0; j < nseg; ++j) {
    const std::size_t k = (j + 1) % n;
    const glm::vec4 l0 = to_glm(left[j]), r0 = to_glm(right[j]);
    const glm::vec4 l1 = to_glm(left[k]), r1 = to_glm(right[k]);
    out.push_back({l0, color});
    out.push_back({r0, color});
    out.push_back({l1, color});
    out.push_back({l1, color});
    out.push_back({r0, color});
    out.push_back({r1, color});
  }
}

}  // namespace

void append_ribbon(const ps::Camera& cam, const std::vector<ps::Vec3>& points,
                   const std::vector<float>& pressure, float width_px, bool closed,
                   const Rgba& color, double depth_pull, std::vector<ColorVertex>& out) {
  if (points.size() < 2 || cam.width <= 0 || cam.height <= 0) return;
  const Eigen::Matrix4d m = vulkan_clip_matrix(cam);
  std::vector<RibbonPoint> pts;
  pts.reserve(points.size() + 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double p = pressure.size() == points.size()
                         ? std::clamp(static_cast<double>(pressure[i]), 0.0, 1.0)
                         : 1.0;
    const double half = std::max(0.25, 0.5 * static_cast<double>(width_px) * p);
    const ps::Vec3 q = pull_towards_camera(cam, points[i], depth_pull);
    pts.push_back({m * q.homogeneous(), half});
  }
  const double w_min = cam.orthographic ? 0.0 : cam.near_plane;
  // A closed loop entirely in front stays a loop (mitred at its start); otherwise the closing
  // segment is an ordinary segment of an open polyline.
  const bool all_in = std::all_of(pts.begin(), pts.end(),
                                  [&](const RibbonPoint& p) { return p.clip.w() >= w_min; });
  if (closed && !all_in) pts.push_back(pts.front());
  const double half_w = 0.5 * cam.width, half_h = 0.5 * cam.height;
  const glm::vec4 c = to_glm(color);
  if (closed && all_in) {
    emit_run(pts, true, half_w, half_h, c, out);
    return;
  }
  for (const auto& run : clip_runs(pts, w_min)) emit_run(run, false, half_w, half_h, c, out);
}

// === Planes

std::array<ps::Vec3, 4> plane_corners(const PlaneVisual& p) {
  ps::Vec3 u, v;
  p.plane.basis(u, v);
  const ps::Vec3 c = p.plane.project(p.center);
  const double h = p.half_size;
  return {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v};
}

Rgba plane_fill_color(const PlaneVisual& p) {
  Rgba c = p.color;
  if (p.selected) c.a = std::min(1.f, std::max(c.a * 2.f, c.a + 0.15f));
  return c;
}

Rgba plane_border_color(const PlaneVisual& p) {
  // Borders are the plane's hue, darker so they read against a white background; the selected
  // plane's border is darker still and drawn thicker.
  const float k = p.selected ? 0.45f : 0.7f;
  return {p.color.r * k, p.color.g * k, p.color.b * k, 1.f};
}

float plane_border_width_px(const PlaneVisual& p) { return p.selected ? 3.5f : 1.5f; }

// === Screen bounds

PixelBounds make_bounds(int width, int height) {
  PixelBounds b;
  b.width = width;
  b.height = height;
  b.x0 = width;
  b.y0 = height;
  return b;
}

void PixelBounds::add_all() {
  x0 = 0;
  y0 = 0;
  x1 = width;
  y1 = height;
}

void PixelBounds::add_clip(const glm::vec4& c) {
  if (!(c.w > 0.f)) {
    add_all();
    return;
  }
  const double px = (double(c.x) / double(c.w) + 1.0) * 0.5 * width;
  const double py = (double(c.y) / double(c.w) + 1.0) * 0.5 * height;
  if (!std::isfinite(px) || !std::isfinite(py)) {
    add_all();
    return;
  }
  const auto clampi = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
  x0 = std::min(x0, clampi(std::floor(px) - 1.0, width));
  y0 = std::min(y0, clampi(std::floor(py) - 1.0, height));
  x1 = std::max(x1, clampi(std::ceil(px) + 1.0, width));
  y1 = std::max(y1, clampi(std::ceil(py) + 1.0, height));
}

// === Whole frame

namespace {
constexpr double kRibbonDepthPull = 2e-3;
}

FrameGeometry build_frame_geometry(const Scene& scene) {
  FrameGeometry fg;
  const ps::Camera& cam = scene.camera;
  fg.view_proj = vulkan_view_projection(cam);
  fg.translucent_bounds = make_bounds(cam.width, cam.height);
  for (const auto& p : scene.planes) {
    const auto k = plane_corners(p);
    const glm::vec4 fill = to_glm(plane_fill_color(p));
    const auto world = [](const ps::Vec3& v) {
      return glm::vec4(static_cast<float>(v.x()), static_cast<float>(v.y()),
                       static_cast<float>(v.z()), 1.f);
    };
    for (int idx : {0, 1, 2, 0, 2, 3}) fg.plane_fills.push_back({world(k[std::size_t(idx)]), fill});
    const Rgba border = plane_border_color(p);
    append_ribbon(cam, {k.begin(), k.end()}, {}, plane_border_width_px(p), true, border,
                  kRibbonDepthPull, border.a >= 1.f ? fg.opaque_ribbons : fg.translucent_ribbons);
  }
  for (const auto& s : scene.strokes) {
    append_ribbon(cam, s.points, s.pressure, s.width_px, s.closed, s.color, kRibbonDepthPull,
                  s.color.a >= 1.f ? fg.opaque_ribbons : fg.translucent_ribbons);
  }
  for (const auto& v : fg.plane_fills) fg.translucent_bounds.add_clip(fg.view_proj * v.pos);
  for (const auto& v : fg.translucent_ribbons) fg.translucent_bounds.add_clip(v.pos);
  return fg;
}

bool is_closed_and_outward(const ps::TriMesh& mesh) {
  if (mesh.faces.empty()) return false;
  std::unordered_map<uint64_t, int> directed;
  directed.reserve(3 * mesh.faces.size());
  const auto key = [](int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); };
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[std::size_t(k)], b = f[std::size_t((k + 1) % 3)];
      if (a == b) return false;
      if (++directed[key(a, b)] > 1) return false;  // the same directed edge twice
    }
  for (const auto& [k, count] : directed) {
    const int a = int(uint32_t(k >> 32)), b = int(uint32_t(k & 0xffffffffu));
    if (!directed.contains(key(b, a))) return false;
  }
  double six_volume = 0.0;
  for (const auto& f : mesh.faces)
    six_volume += mesh.vertices[std::size_t(f[0])].dot(
        mesh.vertices[std::size_t(f[1])].cross(mesh.vertices[std::size_t(f[2])]));
  return six_volume > 0.0;
}

std::vector<ps::Vec3> vertex_normals(const ps::TriMesh& mesh) {
  std::vector<ps::Vec3> n(mesh.vertices.size(), ps::Vec3::Zero());
  for (const auto& f : mesh.faces) {
    const ps::Vec3& a = mesh.vertices[std::size_t(f[0])];
    const ps::Vec3& b = mesh.vertices[std::size_t(f[1])];
    const ps::Vec3& c = mesh.vertices[std::size_t(f[2])];
    const ps::Vec3 fn = (b - a).cross(c - a);  // length = 2 * area: area weighting
    for (int k : f) n[std::size_t(k)] += fn;
  }
  for (auto& v : n) {
    const double len = v.norm();
    v = len > 0.0 ? ps::Vec3(v / len) : ps::Vec3::Zero();
  }
  return n;
}

MeshBuffers prepare_mesh(const ps::TriMesh& mesh, bool wireframe) {
  MeshBuffers out;
  const auto normals = vertex_normals(mesh);
  const auto vertex = [&](std::size_t i) {
    const ps::Vec3& p = mesh.vertices[i];
    const ps::Vec3& n = normals[i];
    return MeshVertex{glm::vec3(float(p.x()), float(p.y()), float(p.z())),
                      glm::vec3(float(n.x()), float(n.y()), float(n.z()))};
  };
  if (!wireframe) {
    out.vertices.reserve(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) out.vertices.push_back(vertex(i));
    out.indices.reserve(3 * mesh.faces.size());
    for (const auto& f : mesh.faces)
      for (int k : f) out.indices.push_back(static_cast<uint32_t>(k));
  } else {
    out.vertices.reserve(3 * mesh.faces.size());
    out.indices.reserve(3 * mesh.faces.size());
    for (const auto& f : mesh.faces)
      for (int k : f) {
        out.indices.push_back(static_cast<uint32_t>(out.vertices.size()));
        out.vertices.push_back(vertex(std::size_t(k)));
      }
  }
  return out;
}

uint64_t mesh_fingerprint(const ps::TriMesh& mesh) {
  // FNV-1a style mixing over 64-bit words: cheap enough to run every frame (about 0.5 ms per
  // 100k faces) and changes whenever any coordinate bit or index changes.
  uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](uint64_t w) {
    h ^= w;
    h *= 1099511628211ull;
  };
  mix(mesh.vertices.size());
  mix(mesh.faces.size());
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      uint64_t bits;
      const double d = v[k];
      std::memcpy(&bits, &d, sizeof bits);
      mix(bits);
    }
  for (const auto& f : mesh.faces)
    mix((uint64_t(uint32_t(f[0])) << 32) ^ (uint64_t(uint32_t(f[1])) << 16) ^ uint64_t(uint32_t(f[2])));
  return h;
}

namespace {
Status validate_mesh(const MeshVisual& m, const char* name) {
  const auto nv = m.mesh.vertices.size();
  for (std::size_t i = 0; i < nv; ++i)
    if (!m.mesh.vertices[i].allFinite())
      return Status::error(std::string("scene.") + name + ": vertex " + std::to_string(i) +
                           " is not finite");
  for (std::size_t f = 0; f < m.mesh.faces.size(); ++f)
    for (int k : m.mesh.faces[f])
      if (k < 0 || std::size_t(k) >= nv)
        return Status::error(std::string("scene.") + name + ": face " + std::to_string(f) +
                             " has vertex index " + std::to_string(k) + " out of range [0, " +
                             std::to_string(nv) + ")");
  return Status::ok();
}
}  // namespace

Status validate_scene(const Scene& scene) {
  const ps::Camera& c = scene.camera;
  if (c.width <= 0 || c.height <= 0 || c.width > 16384 || c.height > 16384)
    return Status::error("scene.camera: size " + std::to_string(c.width) + "x" +
                         std::to_string(c.height) + " is outside 1..16384");
  if (!c.eye.allFinite() || !c.target.allFinite() || !c.up.allFinite() ||
      (c.target - c.eye).norm() <= 0.0 || (c.target - c.eye).cross(c.up).norm() <= 0.0)
    return Status::error("scene.camera: eye, target and up must be finite, eye != target, "
                         "and up not parallel to the view direction");
  if (!(c.near_plane > 0.0) || !(c.far_plane > c.near_plane))
    return Status::error("scene.camera: need 0 < near_plane < far_plane");
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    const auto& p = scene.planes[i];
    if (!p.plane.normal.allFinite() || std::abs(p.plane.normal.norm() - 1.0) > 1e-6 ||
        !std::isfinite(p.plane.offset) || !p.center.allFinite() || !(p.half_size > 0.0) ||
        !std::isfinite(p.half_size))
      return Status::error("scene.planes[" + std::to_string(i) +
                           "]: needs a unit normal and finite offset, centre and half_size > 0");
  }
  for (std::size_t i = 0; i < scene.strokes.size(); ++i) {
    const auto& s = scene.strokes[i];
    if (!s.pressure.empty() && s.pressure.size() != s.points.size())
      return Status::error("scene.strokes[" + std::to_string(i) + "]: " +
                           std::to_string(s.pressure.size()) + " pressure values for " +
                           std::to_string(s.points.size()) + " points");
    for (std::size_t k = 0; k < s.points.size(); ++k)
      if (!s.points[k].allFinite())
        return Status::error("scene.strokes[" + std::to_string(i) + "]: point " +
                             std::to_string(k) + " is not finite");
    if (!(s.width_px >= 0.f) || !std::isfinite(s.width_px))
      return Status::error("scene.strokes[" + std::to_string(i) + "]: width_px must be >= 0");
  }
  if (scene.preview)
    if (auto st = validate_mesh(*scene.preview, "preview"); !st) return st;
  if (scene.solid)
    if (auto st = validate_mesh(*scene.solid, "solid"); !st) return st;
  return Status::ok();
}

}  // namespace ps::engine
