#pragma once
// What the engine draws: a scene description as plain values (no GPU types), shared by the
// offscreen renderer, the window presenter and the tests.
//
// Conventions:
//   Positions are world coordinates (ps::Vec3, double); the camera is ps::Camera (pixel y down,
//   OpenGL-style clip). The engine converts both to float / Vulkan clip space at upload.
//   Colours are straight (non-premultiplied) linear RGBA in [0, 1]; alpha < 1 makes an object
//   translucent. Translucent objects are composited order-independently (weighted blended OIT),
//   so the image does not depend on the order of planes, strokes or meshes in the scene.
//
// Draw classes:
//   planes:  translucent fill (colour.a, raised when selected) + opaque border lines.
//   strokes: ribbons whose on-screen width is width_px * pressure[i] pixels at point i
//            (pressure empty = 1 everywhere); opaque when color.a == 1, otherwise translucent.
//   preview: translucent lit mesh (color.a is its opacity).
//   solid:   opaque lit mesh (color.a ignored), optional wireframe overlay.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps::engine {

struct Rgba {
  float r = 0.f, g = 0.f, b = 0.f, a = 1.f;
};

// A square patch of a plane: centred at `center` (projected onto the plane), side 2 * half_size,
// its edges along Plane::basis().
struct PlaneVisual {
  ps::Plane plane;
  ps::Vec3 center = ps::Vec3::Zero();
  double half_size = 1.0;
  Rgba color{0.5f, 0.5f, 0.5f, 0.15f};
  bool selected = false;
};

struct StrokeVisual {
  std::vector<ps::Vec3> points;
  std::vector<float> pressure;  // empty, or one value in [0, 1] per point
  Rgba color{0.1f, 0.1f, 0.1f, 1.f};
  float width_px = 4.f;  // on-screen width at pressure 1
  bool closed = false;   // connect the last point back to the first
};

struct MeshVisual {
  ps::TriMesh mesh;
  Rgba color{0.8f, 0.8f, 0.8f, 1.f};
  bool wireframe = false;
};

struct Scene {
  ps::Camera camera;  // camera.width/height must equal the renderer's target size
  Rgba background{1.f, 1.f, 1.f, 1.f};
  std::vector<PlaneVisual> planes;
  std::vector<StrokeVisual> strokes;
  std::optional<MeshVisual> preview;  // translucent
  std::optional<MeshVisual> solid;    // opaque, lit
};

// === Default layout

enum class View { iso, x, y, z };  // iso: from (+x, +y, +z); x/y/z: looking down -axis

// Parse "iso", "x", "y", "z"; nothing otherwise.
std::optional<View> parse_view(const std::string& name);

// Three axis-aligned reference planes x = c.x, y = c.y, z = c.z through the centre of `box`,
// each a square covering the box's extent with a margin, in distinct colours (x red, y green,
// z blue, translucent).
std::vector<PlaneVisual> basic_planes(const ps::Box3& box);

// A perspective camera of the given size looking at `box` from `view`, far enough that the
// box's bounding sphere fits the narrower field of view with a small margin.
ps::Camera framing_camera(const ps::Box3& box, View view, int width, int height);

// The default scene for a mesh: framing camera, white background, the three basic planes and
// the mesh as an opaque lit solid.
Scene default_scene(const ps::TriMesh& mesh, View view, int width, int height,
                    bool wireframe = false);

}  // namespace ps::engine
