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

engine::Scene session_scene(const SessionState& st, const InputState& input, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress,
                            const std::optional<ExtrudePlane>& extrusion_plane) {
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
