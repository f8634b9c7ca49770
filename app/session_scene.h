#pragma once
// What the window and the replay picture show of a session: the reference planes (selected one
// highlighted), the sewn cross sections, the model as an opaque lit mesh, and optionally a
// stroke in progress.
#include <vector>

#include "app/session_driver.h"
#include "engine/scene.h"

namespace ps::app {

// The scene for `d` seen through `camera` (its width/height give the image size).
engine::Scene session_scene(const SessionDriver& d, const Camera& camera,
                            const std::vector<Vec3>& stroke_in_progress = {});

// A camera looking from the session's initial viewing direction, framed on the model and curves.
Camera framed_camera(const SessionDriver& d, int width, int height);

// Bounding box of the model and curves (a unit box around the origin when empty).
Box3 session_box(const SessionDriver& d);

}  // namespace ps::app
