#include "app/session_scene.h"

#include <algorithm>
#include <cmath>

namespace ps::app {

Box3 session_box(const SessionState& st) {
  Box3 box = bounding_box(st.model.vertices);
  for (const auto& p : st.sewn.all_points()) box.extend(p);
  if (box.empty()) {
    box.extend(Vec3::Constant(-1.0));
    box.extend(Vec3::Constant(1.0));
  }
  return box;
}

Camera framed_camera(const SessionDriver& d, int width, int height) {
  return framed_camera(d.session().state(), d.initial_camera(), width, height);
}

Camera framed_camera(const SessionState& state, const Camera& initial_camera, int width, int height) {
  const Box3 box = session_box(state);
  Camera cam = initial_camera;
  cam.width = width;
  cam.height = height;
  const Vec3 dir = (cam.eye - cam.target).normalized();
  const double radius = 0.5 * box.diagonal() * 1.25;
  const double half_fov = 0.5 * cam.fov_y_deg * M_PI / 180.0 * std::min(1.0, cam.aspect());
  cam.target = box.center();
  cam.eye = box.center() + dir * (radius / std::sin(half_fov));
  cam.near_plane = 0.01 * radius;
  cam.far_plane = 100.0 * radius;
  return cam;
}

engine::Scene session_scene(const SessionDriver& d, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress) {
  return session_scene(d.session().state(), d.input(), camera, stroke_in_progress, d.pending_extrusion_plane());
}

SketchGuides sketch_guides(const SessionState& state, const InputState& input) {
  SketchGuides g;
  const auto plane = input.current_plane();
  if (input.mode != "sketch" || !plane || !state.base.empty()) return g;
  g.crossings = crossing_hints(state.sewn, *plane);
  if (auto loops = model_section(state.model, *plane)) g.model_section = std::move(*loops);
  return g;
}

namespace {

// The size of one window pixel at `p` (world units, in a plane facing the camera).
double pixel_size(const Camera& cam, const Vec3& p) {
  const double h = cam.orthographic ? cam.ortho_height
                                    : 2.0 * std::max((p - cam.eye).dot((cam.target - cam.eye).normalized()), cam.near_plane) *
                                          std::tan(0.5 * cam.fov_y_deg * M_PI / 180.0);
  return h / static_cast<double>(cam.height);
}

// `p` moved along its viewing ray to half the camera's distance to its target: the same place
// on screen, in front of the model. The guides are drawn there, over everything: a crossing
// the new curve must pass is a hint on the plane even where the model hides that point.
Vec3 in_front(const Camera& cam, const Vec3& p) {
  const Vec3 f = (cam.target - cam.eye).normalized();
  const double depth = (p - cam.eye).dot(f);
  const double front = std::max(0.5 * (cam.target - cam.eye).norm(), 2.0 * cam.near_plane);
  if (!(depth > front)) return p;  // already in front (or behind the eye: left to the clipper)
  if (cam.orthographic) return p - (depth - front) * f;
  return cam.eye + (p - cam.eye) * (front / depth);
}

// A ring of `radius_px` pixels (ribbon `width_px` wide) about `p`'s place on screen, facing
// the camera, in front of the model.
engine::StrokeVisual ring(const Camera& cam, const Vec3& p, double radius_px, float width_px, engine::Rgba color) {
  const Vec3 f = (cam.target - cam.eye).normalized();
  const Vec3 s = f.cross(cam.up).normalized(), u = s.cross(f);
  const Vec3 q = in_front(cam, p);
  const double r = radius_px * pixel_size(cam, q);
  engine::StrokeVisual sv;
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * M_PI * i / 16.0;
    sv.points.push_back(q + r * (std::cos(a) * s + std::sin(a) * u));
  }
  sv.closed = true;
  sv.color = color;
  sv.width_px = width_px;
  return sv;
}

void add_guides(engine::Scene& scene, const SketchGuides& g, const Camera& cam, engine::Rgba plane_color) {
  using engine::Rgba;
  for (const auto& loop : g.model_section) {
    engine::StrokeVisual sv;
    for (const Vec3& p : loop) sv.points.push_back(in_front(cam, p));
    sv.closed = true;
    // The selected plane's hue, darkened, half transparent: a reference, not a section.
    sv.color = Rgba{0.6f * plane_color.r, 0.6f * plane_color.g, 0.6f * plane_color.b, 0.5f};
    sv.width_px = 5.0f;
    scene.strokes.push_back(std::move(sv));
  }
  for (const auto& h : g.crossings) {
    if (h.met) {
      scene.strokes.push_back(ring(cam, h.point, 4.0, 2.0f, Rgba{0.85f, 0.10f, 0.75f, 0.45f}));
    } else {
      scene.strokes.push_back(ring(cam, h.point, 6.0, 2.5f, Rgba{0.85f, 0.10f, 0.75f, 1.0f}));
      scene.strokes.push_back(ring(cam, h.point, 1.0, 3.0f, Rgba{0.85f, 0.10f, 0.75f, 1.0f}));  // the centre dot
    }
  }
}

}  // namespace

engine::Scene session_scene(const SessionState& st, const InputState& input, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress,
                            const std::optional<ExtrudePlane>& extrusion_plane, const SketchGuides* guides) {
  using namespace ps::engine;
  Scene scene;
  scene.camera = camera;
  const Box3 box = session_box(st);
  const Vec3 c = box.center();
  const double half = std::max(0.75 * box.size().maxCoeff(), 0.5);
  static const Rgba colors[3] = {{0.90f, 0.25f, 0.25f, 0.16f}, {0.25f, 0.75f, 0.30f, 0.16f},
                                 {0.25f, 0.40f, 0.95f, 0.16f}};
  const auto& planes = input.planes;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    PlaneVisual pv;
    pv.plane = planes[i];
    pv.center = planes[i].project(c);
    pv.half_size = half;
    const int axis = planes[i].axis();
    pv.color = colors[axis >= 0 ? axis : static_cast<int>(i % 3)];
    pv.selected = static_cast<int>(i) == input.selected_plane;
    if (pv.selected && guides) add_guides(scene, *guides, camera, pv.color);
    scene.planes.push_back(pv);
  }
  for (const auto& cs : st.sewn.curves) {
    StrokeVisual sv;
    sv.points = cs.points;
    sv.closed = true;
    sv.color = Rgba{0.95f, 0.70f, 0.10f, 1.0f};
    sv.width_px = 3.0f;
    scene.strokes.push_back(std::move(sv));
  }
  if (extrusion_plane) {
    // Sized to the base curve: the silhouette is drawn over a few base widths of it.
    double reach = 0.0;
    for (const auto& q : extrusion_plane->base_curve) reach = std::max(reach, (q - extrusion_plane->centre).norm());
    PlaneVisual pv;
    pv.plane = extrusion_plane->plane;
    pv.center = extrusion_plane->centre;
    pv.half_size = std::max(3.0 * reach, 1e-3);
    pv.color = Rgba{0.95f, 0.55f, 0.10f, 0.22f};
    pv.selected = true;
    scene.planes.push_back(pv);
    StrokeVisual base;
    base.points = extrusion_plane->base_curve;
    base.closed = true;
    base.color = Rgba{0.95f, 0.45f, 0.05f, 1.0f};
    base.width_px = 3.0f;
    scene.strokes.push_back(std::move(base));
  }
  if (stroke_in_progress.size() >= 2) {
    StrokeVisual sv;
    sv.points = stroke_in_progress;
    sv.color = Rgba{0.10f, 0.10f, 0.12f, 1.0f};
    sv.width_px = 3.0f;
    scene.strokes.push_back(std::move(sv));
  }
  if (!st.model.empty()) scene.solid = MeshVisual{st.model, Rgba{0.78f, 0.80f, 0.84f, 1.0f}, false};
  return scene;
}

}  // namespace ps::app
