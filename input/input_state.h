#pragma once
// The input-side state a stroke log changes: camera, reference planes, selected plane, tool
// mode and parameters. The app keeps one and applies every action to it; tests and the
// headless replay use it to lift pen samples onto the selected plane exactly as the app does.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "input/stroke_log.h"
#include "modeling/status.h"

namespace ps {

struct InputState {
  Camera camera;
  std::vector<Plane> planes = LogHeader::default_reference_planes();
  int selected_plane = 2;  // the z plane, as the thesis's figure 3.1 starts
  std::string mode = "sketch";
  std::map<std::string, double> parameters;

  static InputState from_header(const LogHeader& h);

  // Applies a plane, camera, mode or parameter action; pen samples and model edits (undo,
  // redo, delete, save) leave this state unchanged. Refuses a plane index out of range.
  Status apply(const Event& e);

  // The selected plane, or nothing if the selection is out of range.
  std::optional<Plane> current_plane() const;
  // A window point lifted through the camera onto the selected plane (modeling/camera.h).
  std::optional<Vec3> lift(double x, double y) const;
};

}  // namespace ps
