#pragma once
// The scene pass (engine-internal): draws a Scene into colour + depth targets with weighted
// blended order-independent transparency. Shared by the offscreen renderer and the window
// presenter; it records into a caller's command buffer and leaves the colour target in
// TRANSFER_SRC_OPTIMAL layout for read-back or a blit to a swapchain image.
//
// One render pass, three subpasses:
//   0 opaque:      colour (RGBA8) + depth (D32, test and write): solid mesh, opaque ribbons.
//   1 translucent: accumulation (RGBA16F, blend ONE/ONE) + revealage (R16F, blend
//                  ZERO/ONE_MINUS_SRC_COLOR), depth tested but not written: preview mesh,
//                  plane fills, translucent ribbons.
//   2 composite:   full-screen triangle reading both as input attachments, blended over the
//                  colour target (McGuire and Bavoil 2013).
#include <cstdint>
#include <memory>

#include "engine/frame_geometry.h"
#include "engine/scene.h"
#include "engine/vk_context.h"

namespace ps::engine {

class ScenePass {
 public:
  static Result<std::unique_ptr<ScenePass>> create(const vk::Context& ctx, VkExtent2D extent);
  ScenePass(const ScenePass&) = delete;
  ScenePass& operator=(const ScenePass&) = delete;

  // Validate the scene, resize the targets to the camera's size, re-upload changed meshes and
  // write this frame's ribbons and plane fills. The GPU must not be using the previous frame.
  Status prepare(const Scene& scene);
  // Record the render pass for the last prepared scene.
  void record(VkCommandBuffer cmd) const;

  // Cull back faces of an opaque solid that is closed and consistently oriented (default on;
  // the image is the same either way for such meshes, culling only saves work).
  void set_cull_closed_solids(bool on) { disable_culling_ = !on; }

  VkImage color_image() const { return targets_.color.image.get(); }
  VkExtent2D extent() const { return targets_.extent; }
  // How many times mesh data has been uploaded (for tests of the cache).
  std::size_t mesh_uploads() const { return mesh_uploads_; }

 private:
  explicit ScenePass(const vk::Context& ctx) : ctx_(ctx) {}

  struct Targets {
    VkExtent2D extent{0, 0};
    vk::ImageAlloc color, depth, accum, reveal;
    vk::Framebuffer framebuffer;
  };
  struct GpuMesh {
    bool valid = false;
    uint64_t fingerprint = 0;
    bool wireframe = false;
    vk::BufferAlloc vertices, indices;
    uint32_t index_count = 0;
    bool closed = false;  // is_closed_and_outward: the opaque draw culls back faces
    ps::Box3 box;         // world bounding box, for the composite's screen bounds
  };
  struct Draw {
    bool enabled = false;
    Rgba color;
    bool wireframe = false;
  };

  Status create_pipelines();
  Status resize(VkExtent2D extent);
  Status update_mesh(GpuMesh& slot, const MeshVisual& m);
  void draw_mesh(VkCommandBuffer cmd, VkPipeline pipeline, const GpuMesh& m, const Draw& d) const;
  void draw_colored(VkCommandBuffer cmd, VkPipeline pipeline, bool world_space,
                    VkDeviceSize offset, std::size_t count) const;

  const vk::Context& ctx_;
  vk::RenderPass render_pass_;
  vk::DescriptorSetLayout set_layout_;
  vk::PipelineLayout pipeline_layout_;
  // Mesh pipelines by [wireframe][variant]: variant 0 opaque, 1 opaque with back faces culled,
  // 2 translucent (OIT).
  vk::Pipeline mesh_[2][3];
  vk::Pipeline color_opaque_, color_oit_, composite_;
  vk::DescriptorPool descriptor_pool_;
  vk::DescriptorSet composite_set_;
  Targets targets_;
  GpuMesh solid_, preview_;
  vk::BufferAlloc dynamic_;  // plane fills + ribbons of the current frame

  // The prepared frame.
  ps::Camera camera_;
  Rgba background_;
  glm::mat4 view_proj_{1.f};
  Draw solid_draw_, preview_draw_;
  VkDeviceSize fills_offset_ = 0, opaque_ribbons_offset_ = 0, translucent_ribbons_offset_ = 0;
  std::size_t fills_count_ = 0, opaque_ribbons_count_ = 0, translucent_ribbons_count_ = 0;
  VkRect2D composite_rect_{};  // where translucent fragments can be; the composite's scissor
  std::size_t mesh_uploads_ = 0;
  bool disable_culling_ = false;
};

}  // namespace ps::engine
