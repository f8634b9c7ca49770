#pragma once
// What the window and the replay picture show of a session: the reference planes (selected one
// highlighted), the sewn cross sections, the model as an opaque lit mesh, and optionally a
// stroke in progress, the reference plane of a half-drawn extrusion and the sketching guides of
// the selected plane.
#include <optional>
#include <vector>

#include "app/session_driver.h"
#include "engine/scene.h"
#include "modeling/sketch_guides.h"

namespace ps::app {

// What the sketching tool shows on the selected plane (modeling/sketch_guides.h): the points
// where sections on other planes cross it (rule 4: where a new section must pass; met ones
// are drawn fainter) and the model's cross section by it, drawn semi-transparently (the curve
// an open stroke near it is completed from).
struct SketchGuides {
  std::vector<CrossingHint> crossings;
  std::vector<std::vector<Vec3>> model_section;
};
// The guides for the selected plane of `input` in "sketch" mode over the session `state`
// (none in other modes, without a selected plane, or for an imported base, which has no
// sections). Slicing the model costs about as much as a frame on lavapipe: compute once per
// snapshot and plane, not per frame.
SketchGuides sketch_guides(const SessionState& state, const InputState& input);

// The scene for session state `state` with the planes and selection of `input`, seen through
// `camera` (its width/height give the image size). The window draws published snapshots of a
// session running on another thread (app/preview_worker.h), hence values, not the driver.
// `extrusion_plane` (SessionDriver::pending_extrusion_plane) is drawn highlighted, with its base
// curve, while an extrusion waits for its silhouette. With `guides`, their markers (rings facing
// the camera, 6 px) and curves are drawn too, over the model (moved along their viewing rays to
// half the distance to the camera's target).
engine::Scene session_scene(const SessionState& state, const InputState& input, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress = {},
                            const std::optional<ExtrudePlane>& extrusion_plane = std::nullopt,
                            const SketchGuides* guides = nullptr);
// The same for the session a driver holds (its pending extrusion plane included).
engine::Scene session_scene(const SessionDriver& d, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress = {});

// A camera looking from `initial_camera`'s viewing direction, framed on the model and curves.
Camera framed_camera(const SessionState& state, const Camera& initial_camera, int width, int height);
// The same from the driver's session and initial camera (the log header's).
Camera framed_camera(const SessionDriver& d, int width, int height);

// Bounding box of the model and curves (a unit box around the origin when empty).
Box3 session_box(const SessionState& state);

}  // namespace ps::app
