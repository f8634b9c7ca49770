#pragma once
// Scene logic without a device: turn a Scene into GPU-ready vertex arrays and matrices.
// Everything here is pure CPU code, tested without Vulkan (tests/engine_scene_test.cpp); the
// renderers only upload and draw what it produces.
//
// Conventions:
//   Vulkan clip space: x right, y DOWN, depth in [0, 1]. vulkan_view_projection(cam) maps a
//   world point p to clip c with pixel ((c.x/c.w + 1) W/2, (c.y/c.w + 1) H/2) equal to
//   cam.project(p).xy, and depth c.z/c.w == (cam.project(p).z + 1) / 2.
//   ColorVertex.pos is either a world position (w = 1, drawn with the view-projection) or an
//   already projected clip-space position (ribbons, drawn with the identity).
//   MeshVertex: float position and area-weighted unit vertex normal.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "engine/scene.h"

namespace ps::engine {

struct ColorVertex {
  glm::vec4 pos;
  glm::vec4 color;  // straight alpha
};
struct MeshVertex {
  glm::vec3 pos;
  glm::vec3 normal;
};
static_assert(std::is_trivially_copyable_v<ColorVertex> && sizeof(ColorVertex) == 32);
static_assert(std::is_trivially_copyable_v<MeshVertex> && sizeof(MeshVertex) == 24);

// World -> Vulkan clip: C * P * V with C = flip y, z' = (z + w) / 2. Double precision for
// CPU-side projection, float (column-major GLM) for upload.
Eigen::Matrix4d vulkan_clip_matrix(const ps::Camera& cam);
glm::mat4 vulkan_view_projection(const ps::Camera& cam);

// === Ribbons

// Append a screen-space ribbon along `points` as a triangle list of clip-space vertices.
// The ribbon's full width at point i is width_px * pressure[i] pixels (pressure empty: 1;
// values clamped to [0, 1]; a minimum of 0.5 px keeps light strokes visible). Joints are
// mitred (miter length capped at 2x). Each point is first pulled towards the camera by
// `depth_pull` of its distance so the ribbon wins the depth test against the surface it lies
// on. Parts behind the eye are clipped at the near plane.
void append_ribbon(const ps::Camera& cam, const std::vector<ps::Vec3>& points, const std::vector<float>& pressure,
                   float width_px, bool closed, const Rgba& color, double depth_pull,
                   std::vector<ColorVertex>& out);

// === Planes

// The four corners of a plane visual, counter-clockwise around plane.normal.
std::array<ps::Vec3, 4> plane_corners(const PlaneVisual& p);
// Fill alpha and border colour / width actually drawn (selection highlight applied).
Rgba plane_fill_color(const PlaneVisual& p);
Rgba plane_border_color(const PlaneVisual& p);
float plane_border_width_px(const PlaneVisual& p);

// === Screen bounds

// A conservative pixel rectangle [x0, x1) x [y0, y1) inside the image, grown point by point.
struct PixelBounds {
  int width = 0, height = 0;  // the image
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  // Add a clip-space point; a point at or behind the eye (w <= 0) makes the bounds the whole
  // image (its projection is unbounded). One pixel of margin covers rasterization rounding.
  void add_clip(const glm::vec4& c);
  void add_all();
};
PixelBounds make_bounds(int width, int height);

// === Whole frame

// Per-frame geometry (everything except the meshes, which are cached by the renderer).
struct FrameGeometry {
  glm::mat4 view_proj{1.f};
  std::vector<ColorVertex> plane_fills;          // world space, translucent, triangle list
  std::vector<ColorVertex> opaque_ribbons;       // clip space, triangle list
  std::vector<ColorVertex> translucent_ribbons;  // clip space, triangle list
  PixelBounds translucent_bounds;                // covers plane_fills and translucent_ribbons
};
FrameGeometry build_frame_geometry(const Scene& scene);

// Mesh upload data. Indexed (shared vertices) unless `wireframe`, in which case every face gets
// its own three vertices (vertex 3f + k is corner k of face f) so the fragment shader can
// derive barycentric coordinates from gl_VertexIndex; indices are then 0, 1, 2, ...
struct MeshBuffers {
  std::vector<MeshVertex> vertices;
  std::vector<uint32_t> indices;
};
MeshBuffers prepare_mesh(const ps::TriMesh& mesh, bool wireframe);

// True when every directed edge (a, b) of the mesh has exactly one opposite edge (b, a) (closed
// and consistently oriented) and the signed volume is positive (faces point outwards): back
// faces are then never visible from outside, so an opaque draw may cull them.
bool is_closed_and_outward(const ps::TriMesh& mesh);

// Area-weighted unit vertex normals (zero for isolated vertices).
std::vector<ps::Vec3> vertex_normals(const ps::TriMesh& mesh);

// A content fingerprint (FNV-1a over positions and faces) to detect changed meshes.
uint64_t mesh_fingerprint(const ps::TriMesh& mesh);

// Check that the scene can be drawn; names the offending field.
Status validate_scene(const Scene& scene);

}  // namespace ps::engine
