// Input-side state driven by stroke-log actions.
#include "input/input_state.h"

namespace ps {

InputState InputState::from_header(const LogHeader& h) {
  InputState s;
  s.camera = h.camera;
  s.planes = h.planes;
  s.selected_plane = h.planes.size() > 2 ? 2 : 0;
  return s;
}

Status InputState::apply(const Event& e) {
  auto in_range = [&](int k) { return k >= 0 && static_cast<std::size_t>(k) < planes.size(); };
  if (const auto* sel = std::get_if<SelectPlane>(&e)) {
    if (!in_range(sel->plane))
      return Status::error("select_plane: no reference plane " + std::to_string(sel->plane));
    selected_plane = sel->plane;
  } else if (const auto* tr = std::get_if<TranslatePlane>(&e)) {
    if (!in_range(tr->plane))
      return Status::error("translate_plane: no reference plane " + std::to_string(tr->plane));
    planes[static_cast<std::size_t>(tr->plane)].offset = tr->offset;
  } else if (const auto* cam = std::get_if<CameraChange>(&e)) {
    camera = cam->camera;
  } else if (const auto* md = std::get_if<SetToolMode>(&e)) {
    mode = md->mode;
  } else if (const auto* par = std::get_if<SetParameter>(&e)) {
    parameters[par->name] = par->value;
  }
  return Status::ok();
}

std::optional<Plane> InputState::current_plane() const {
  if (selected_plane < 0 || static_cast<std::size_t>(selected_plane) >= planes.size()) return std::nullopt;
  return planes[static_cast<std::size_t>(selected_plane)];
}

std::optional<Vec3> InputState::lift(double x, double y) const {
  const auto pl = current_plane();
  if (!pl) return std::nullopt;
  return camera.lift(x, y, *pl);
}

}  // namespace ps
