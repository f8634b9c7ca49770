// The headless renderer: a Vulkan context, the scene pass, and a read-back buffer.
#include <cstdlib>
#include <cstring>
#include <string>

#include "engine/renderer.h"
#include "engine/scene_pass.h"
#include "engine/vk_context.h"

namespace ps::engine {

Renderer::~Renderer() = default;

Result<Image> Renderer::render(const Scene& scene) {
  if (auto st = draw(scene); !st) return st;
  return read_back();
}

bool validation_requested_by_environment() {
  const char* v = std::getenv("PLANESKETCH_VALIDATION");
  return v && *v && std::string(v) != "0";
}

namespace {

class OffscreenRenderer final : public Renderer {
 public:
  static Result<std::unique_ptr<Renderer>> create(const RendererOptions& o) {
    if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
      return Status::error("renderer size " + std::to_string(o.width) + "x" +
                           std::to_string(o.height) + " is outside 1..16384");
    std::unique_ptr<OffscreenRenderer> r(new OffscreenRenderer());
    vk::ContextOptions co;
    co.validation = o.validation || validation_requested_by_environment();
    co.prefer_gpu = o.prefer_gpu;
    co.log = o.log;
    auto ctx = vk::Context::create(co);
    if (!ctx) return ctx.status();
    r->ctx_ = std::move(*ctx);
    auto pass = ScenePass::create(
        *r->ctx_, {static_cast<uint32_t>(o.width), static_cast<uint32_t>(o.height)});
    if (!pass) return pass.status();
    r->pass_ = std::move(*pass);
    r->pass_->set_cull_closed_solids(o.cull_closed_solids);
    auto cmd = r->ctx_->allocate_command_buffer();
    if (!cmd) return cmd.status();
    r->cmd_ = std::move(*cmd);
    auto fence = r->ctx_->create_fence(false);
    if (!fence) return fence.status();
    r->fence_ = std::move(*fence);
    return std::unique_ptr<Renderer>(std::move(r));
  }

  ~OffscreenRenderer() override {
    if (ctx_) vkDeviceWaitIdle(ctx_->device());
  }

  Status draw(const Scene& scene) override {
    drawn_ = false;
    if (auto st = pass_->prepare(scene); !st) return st;
    const VkCommandBuffer cmd = cmd_.get();
    if (auto st = begin(cmd); !st) return st;
    pass_->record(cmd);
    if (const VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS)
      return Status::error("vkEndCommandBuffer failed: " + vk::result_name(r));
    if (auto st = ctx_->submit_and_wait(cmd, fence_.get()); !st) return st;
    drawn_ = true;
    ++frames_;
    return Status::ok();
  }

  Result<Image> read_back() override {
    if (!drawn_) return Result<Image>::error("read_back: no frame has been drawn");
    const VkExtent2D e = pass_->extent();
    const VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * 4;
    if (!readback_.buffer || readback_.size < bytes) {
      auto b = ctx_->create_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
      if (!b) return b.status();
      readback_ = std::move(*b);
    }
    const VkCommandBuffer cmd = cmd_.get();
    if (auto st = begin(cmd); !st) return st;
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, pass_->color_image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           readback_.buffer.get(), 1, &region);
    VkBufferMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = readback_.buffer.get();
    barrier.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &barrier, 0, nullptr);
    if (const VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS)
      return Result<Image>::error("vkEndCommandBuffer failed: " + vk::result_name(r));
    if (auto st = ctx_->submit_and_wait(cmd, fence_.get()); !st) return st;
    Image img;
    img.width = static_cast<int>(e.width);
    img.height = static_cast<int>(e.height);
    img.rgba.resize(static_cast<std::size_t>(bytes));
    std::memcpy(img.rgba.data(), readback_.mapped, img.rgba.size());
    return img;
  }

  std::string device_name() const override { return ctx_->device_name(); }
  std::size_t validation_messages() const override { return ctx_->validation_messages(); }
  RenderStats stats() const override { return {frames_, pass_->mesh_uploads()}; }

 private:
  OffscreenRenderer() = default;

  static Status begin(VkCommandBuffer cmd) {
    if (const VkResult r = vkResetCommandBuffer(cmd, 0); r != VK_SUCCESS)
      return Status::error("vkResetCommandBuffer failed: " + vk::result_name(r));
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    if (const VkResult r = vkBeginCommandBuffer(cmd, &bi); r != VK_SUCCESS)
      return Status::error("vkBeginCommandBuffer failed: " + vk::result_name(r));
    return Status::ok();
  }

  // Member order = reverse destruction order: everything below ctx_ goes first.
  std::unique_ptr<vk::Context> ctx_;
  std::unique_ptr<ScenePass> pass_;
  vk::CommandBuffer cmd_;
  vk::Fence fence_;
  vk::BufferAlloc readback_;
  bool drawn_ = false;
  std::size_t frames_ = 0;
};

}  // namespace

Result<std::unique_ptr<Renderer>> create_offscreen_renderer(const RendererOptions& options) {
  return OffscreenRenderer::create(options);
}

}  // namespace ps::engine
