// GLFW window + Vulkan swapchain presenting the scene pass's colour target.
#include "engine/window_presenter.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <array>
#include <vector>

#include "engine/renderer.h"
#include "engine/scene_pass.h"
#include "engine/vk_context.h"

namespace ps::engine {

namespace {

// glfwInit / glfwTerminate as an owner (GLFW is process-global; one presenter at a time).
struct GlfwLibrary {
  bool ok = false;
  GlfwLibrary() : ok(glfwInit() == GLFW_TRUE) {}
  ~GlfwLibrary() {
    if (ok) glfwTerminate();
  }
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

struct WindowDeleter {
  void operator()(GLFWwindow* w) const { glfwDestroyWindow(w); }
};

std::string glfw_error() {
  const char* what = nullptr;
  const int code = glfwGetError(&what);
  return code == GLFW_NO_ERROR ? std::string("unknown GLFW error")
                               : std::string(what ? what : "GLFW error") + " (" +
                                     std::to_string(code) + ")";
}

}  // namespace

struct WindowPresenter::Impl {
  // Member order is destruction order reversed: the GLFW library outlives the window, the
  // window outlives the surface (inside the context), the context outlives everything else.
  WindowOptions options;
  std::unique_ptr<GlfwLibrary> glfw;
  std::unique_ptr<GLFWwindow, WindowDeleter> window;
  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<ScenePass> pass;
  vk::CommandBuffer cmd;
  vk::Fence frame_done;
  vk::Semaphore image_acquired;

  // === The panel (options.panel): ImGui's render pass over the swapchain image.
  vk::DescriptorPool panel_pool;
  vk::RenderPass panel_pass;
  VkFormat panel_format = VK_FORMAT_UNDEFINED;
  bool imgui_context = false, imgui_glfw = false, imgui_vulkan = false;
  bool panel_frame = false;  // begin_panel() was called for the coming present()

  struct Swapchain {
    vk::Swapchain handle;
    std::vector<VkImage> images;  // owned by the swapchain
    std::vector<vk::Semaphore> render_done;  // one per image, waited by its present
    std::vector<vk::ImageView> views;  // with the panel: one per image
    std::vector<vk::Framebuffer> framebuffers;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{0, 0};
  } swapchain;
  bool recreate = true;
  std::size_t frames = 0;
  std::size_t recreations = 0;

  ~Impl() {
    if (ctx) vkDeviceWaitIdle(ctx->device());
    if (imgui_vulkan) ImGui_ImplVulkan_Shutdown();
    if (imgui_glfw) ImGui_ImplGlfw_Shutdown();
    if (imgui_context) ImGui::DestroyContext();
  }

  Status create_swapchain(VkExtent2D fb);
  Status create_panel(VkFormat format, uint32_t min_images, uint32_t images);
  Status create_panel_framebuffers(Swapchain& s);
  Status present(Scene scene);
};

// The render pass the panel draws in: the blitted scene is loaded (the image comes from the
// blit in TRANSFER_DST layout) and left ready to present. ImGui's pipeline is made for it.
Status WindowPresenter::Impl::create_panel(VkFormat format, uint32_t min_images, uint32_t images) {
  const VkDevice dev = ctx->device();
  if (imgui_vulkan) {
    if (format != panel_format) return Status::error("the window surface format changed under the panel");
    ImGui_ImplVulkan_SetMinImageCount(std::max<uint32_t>(min_images, 2));
    return Status::ok();
  }
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dep.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo rpi{};
  rpi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  rpi.attachmentCount = 1;
  rpi.pAttachments = &color;
  rpi.subpassCount = 1;
  rpi.pSubpasses = &sub;
  rpi.dependencyCount = 1;
  rpi.pDependencies = &dep;
  VkRenderPass rp = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateRenderPass(dev, &rpi, nullptr, &rp); r != VK_SUCCESS)
    return Status::error("vkCreateRenderPass (panel) failed: " + vk::result_name(r));
  panel_pass = vk::RenderPass(dev, rp);
  panel_format = format;

  // ImGui needs one combined image sampler (its font); a few spare sets.
  auto pool = ctx->create_descriptor_pool(VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4, 4);
  if (!pool) return pool.status();
  panel_pool = std::move(*pool);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  imgui_context = true;
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
  ImGui::StyleColorsLight();
  if (!ImGui_ImplGlfw_InitForVulkan(window.get(), true)) return Status::error("ImGui's GLFW backend failed to start");
  imgui_glfw = true;
  ImGui_ImplVulkan_InitInfo ii{};
  ii.Instance = ctx->instance();
  ii.PhysicalDevice = ctx->physical_device();
  ii.Device = dev;
  ii.QueueFamily = ctx->queue_family();
  ii.Queue = ctx->queue();
  ii.DescriptorPool = panel_pool.get();
  ii.Subpass = 0;
  ii.MinImageCount = std::max<uint32_t>(min_images, 2);
  ii.ImageCount = std::max(images, ii.MinImageCount);
  ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  if (!ImGui_ImplVulkan_Init(&ii, rp)) return Status::error("ImGui's Vulkan backend failed to start");
  imgui_vulkan = true;

  // === The font atlas, uploaded once.
  auto cmd_buf = ctx->allocate_command_buffer();
  if (!cmd_buf) return cmd_buf.status();
  auto fence = ctx->create_fence(false);
  if (!fence) return fence.status();
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd_buf->get(), &bi);
  if (!ImGui_ImplVulkan_CreateFontsTexture(cmd_buf->get())) return Status::error("ImGui's font upload failed");
  vkEndCommandBuffer(cmd_buf->get());
  if (auto st = ctx->submit_and_wait(cmd_buf->get(), fence->get()); !st) return st;
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return Status::ok();
}

Status WindowPresenter::Impl::create_panel_framebuffers(Swapchain& s) {
  const VkDevice dev = ctx->device();
  for (VkImage image : s.images) {
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = s.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    if (const VkResult r = vkCreateImageView(dev, &vi, nullptr, &view); r != VK_SUCCESS)
      return Status::error("vkCreateImageView (panel) failed: " + vk::result_name(r));
    s.views.emplace_back(dev, view);
    VkFramebufferCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fi.renderPass = panel_pass.get();
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = s.extent.width;
    fi.height = s.extent.height;
    fi.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    if (const VkResult r = vkCreateFramebuffer(dev, &fi, nullptr, &fb); r != VK_SUCCESS)
      return Status::error("vkCreateFramebuffer (panel) failed: " + vk::result_name(r));
    s.framebuffers.emplace_back(dev, fb);
  }
  return Status::ok();
}

Status WindowPresenter::Impl::create_swapchain(VkExtent2D fb) {
  const VkDevice dev = ctx->device();
  const VkPhysicalDevice pd = ctx->physical_device();
  const VkSurfaceKHR surface = ctx->surface();
  vkDeviceWaitIdle(dev);

  VkSurfaceCapabilitiesKHR caps;
  if (const VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps); r != VK_SUCCESS)
    return Status::error("vkGetPhysicalDeviceSurfaceCapabilitiesKHR failed: " + vk::result_name(r));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {
    extent.width = std::clamp(fb.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(fb.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0) return Status::ok();  // minimised: try later
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    return Status::error("the window surface cannot be a transfer destination");
  if (options.panel && !(caps.supportedUsageFlags & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT))
    return Status::error("the window surface cannot be drawn to (needed by the panel)");

  // === Format: 8-bit UNORM so the window shows the same values as the PNGs.
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data());
  const auto blit_dst_ok = [&](VkFormat f) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(pd, f, &p);
    return (p.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
  };
  std::optional<VkSurfaceFormatKHR> chosen;
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const auto& f : formats)
      if (!chosen && f.format == want && blit_dst_ok(f.format)) chosen = f;
  for (const auto& f : formats)
    if (!chosen && blit_dst_ok(f.format)) chosen = f;
  if (!chosen) return Status::error("no window surface format accepts blits");

  // === Present mode
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, modes.data());
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always available; vsync
  if (!options.vsync) {
    for (VkPresentModeKHR m : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR})
      if (std::find(modes.begin(), modes.end(), m) != modes.end()) mode = m;
  }

  uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
  VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  const auto supports = [&](VkCompositeAlphaFlagBitsKHR a) {
    return (caps.supportedCompositeAlpha & static_cast<VkCompositeAlphaFlagsKHR>(a)) != 0;
  };
  if (!supports(alpha))
    for (auto a : {VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR, VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                   VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
      if (supports(a)) {
        alpha = a;
        break;
      }

  VkSwapchainCreateInfoKHR sci{};
  sci.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  sci.surface = surface;
  sci.minImageCount = count;
  sci.imageFormat = chosen->format;
  sci.imageColorSpace = chosen->colorSpace;
  sci.imageExtent = extent;
  sci.imageArrayLayers = 1;
  sci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (options.panel) sci.imageUsage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  sci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  sci.preTransform = caps.currentTransform;
  sci.compositeAlpha = alpha;
  sci.presentMode = mode;
  sci.clipped = VK_TRUE;
  sci.oldSwapchain = swapchain.handle.get();
  VkSwapchainKHR handle = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateSwapchainKHR(dev, &sci, nullptr, &handle); r != VK_SUCCESS)
    return Status::error("vkCreateSwapchainKHR failed: " + vk::result_name(r));

  Swapchain s;
  s.handle = vk::Swapchain(dev, handle);
  s.format = chosen->format;
  s.extent = extent;
  vkGetSwapchainImagesKHR(dev, handle, &n, nullptr);
  s.images.resize(n);
  vkGetSwapchainImagesKHR(dev, handle, &n, s.images.data());
  for (uint32_t i = 0; i < n; ++i) {
    auto sem = ctx->create_semaphore();
    if (!sem) return sem.status();
    s.render_done.push_back(std::move(*sem));
  }
  if (options.panel) {
    if (auto st = create_panel(s.format, caps.minImageCount, n); !st) return st;
    if (auto st = create_panel_framebuffers(s); !st) return st;
  }
  swapchain = std::move(s);  // the old swapchain is destroyed here (device idle)
  recreate = false;
  ++recreations;
  return Status::ok();
}

Status WindowPresenter::Impl::present(Scene scene) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window.get(), &w, &h);
  if (w <= 0 || h <= 0) return Status::ok();  // minimised
  const VkExtent2D fb{static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
  if (recreate || !swapchain.handle || fb.width != swapchain.extent.width ||
      fb.height != swapchain.extent.height) {
    if (auto st = create_swapchain(fb); !st) return st;
    if (!swapchain.handle || recreate) return Status::ok();
  }
  const VkDevice dev = ctx->device();
  const VkFence fence = frame_done.get();
  // === Previous frame done: its buffers and the acquire semaphore may be reused.
  if (const VkResult r = vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
    return Status::error("vkWaitForFences failed: " + vk::result_name(r));

  scene.camera.width = static_cast<int>(swapchain.extent.width);
  scene.camera.height = static_cast<int>(swapchain.extent.height);
  if (auto st = pass->prepare(scene); !st) return st;

  uint32_t index = 0;
  const VkResult acq = vkAcquireNextImageKHR(dev, swapchain.handle.get(), UINT64_MAX,
                                             image_acquired.get(), VK_NULL_HANDLE, &index);
  if (acq == VK_ERROR_OUT_OF_DATE_KHR) {
    recreate = true;
    return Status::ok();
  }
  if (acq != VK_SUCCESS && acq != VK_SUBOPTIMAL_KHR)
    return Status::error("vkAcquireNextImageKHR failed: " + vk::result_name(acq));
  if (acq == VK_SUBOPTIMAL_KHR) recreate = true;

  // === Record: scene pass, then blit its colour target into the swapchain image.
  const VkCommandBuffer cb = cmd.get();
  vkResetCommandBuffer(cb, 0);
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cb, &bi);
  pass->record(cb);
  const VkImage target = swapchain.images[index];
  VkImageMemoryBarrier to_dst{};
  to_dst.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  to_dst.srcAccessMask = 0;
  to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_dst.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.image = target;
  to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &to_dst);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<int32_t>(swapchain.extent.width),
                        static_cast<int32_t>(swapchain.extent.height), 1};
  blit.dstOffsets[1] = blit.srcOffsets[1];
  vkCmdBlitImage(cb, pass->color_image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
  if (panel_frame) {
    // === The panel over the scene; its render pass leaves the image ready to present.
    panel_frame = false;
    ImGui::Render();
    VkRenderPassBeginInfo rb{};
    rb.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rb.renderPass = panel_pass.get();
    rb.framebuffer = swapchain.framebuffers[index].get();
    rb.renderArea = {{0, 0}, swapchain.extent};
    vkCmdBeginRenderPass(cb, &rb, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cb);
    vkCmdEndRenderPass(cb);
  } else {
    VkImageMemoryBarrier to_present = to_dst;
    to_present.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_present.dstAccessMask = 0;
    to_present.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &to_present);
  }
  if (const VkResult r = vkEndCommandBuffer(cb); r != VK_SUCCESS)
    return Status::error("vkEndCommandBuffer failed: " + vk::result_name(r));

  // === Submit (waits for the acquired image only where the blit writes it) and present.
  const VkSemaphore wait = image_acquired.get();
  const VkSemaphore signal = swapchain.render_done[index].get();
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &wait;
  si.pWaitDstStageMask = &wait_stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &signal;
  vkResetFences(dev, 1, &fence);
  if (const VkResult r = vkQueueSubmit(ctx->queue(), 1, &si, fence); r != VK_SUCCESS)
    return Status::error("vkQueueSubmit failed: " + vk::result_name(r));
  const VkSwapchainKHR sc = swapchain.handle.get();
  VkPresentInfoKHR pi{};
  pi.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &signal;
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc;
  pi.pImageIndices = &index;
  const VkResult pr = vkQueuePresentKHR(ctx->queue(), &pi);
  if (pr == VK_ERROR_OUT_OF_DATE_KHR || pr == VK_SUBOPTIMAL_KHR)
    recreate = true;
  else if (pr != VK_SUCCESS)
    return Status::error("vkQueuePresentKHR failed: " + vk::result_name(pr));
  ++frames;
  return Status::ok();
}

// === Public interface

Result<std::unique_ptr<WindowPresenter>> WindowPresenter::create(const WindowOptions& o) {
  if (o.width <= 0 || o.height <= 0)
    return Status::error("window size " + std::to_string(o.width) + "x" +
                         std::to_string(o.height) + " must be positive");
  auto impl = std::make_unique<Impl>();
  impl->options = o;
  impl->glfw = std::make_unique<GlfwLibrary>();
  if (!impl->glfw->ok) return Status::error("cannot initialise GLFW: " + glfw_error());
  if (!glfwVulkanSupported())
    return Status::error("GLFW finds no Vulkan loader (install libvulkan1)");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  impl->window.reset(glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr));
  if (!impl->window) return Status::error("cannot open a window: " + glfw_error());

  vk::ContextOptions co;
  co.validation = o.validation || validation_requested_by_environment();
  co.prefer_gpu = o.prefer_gpu;
  co.log = o.log;
  uint32_t n = 0;
  const char** ext = glfwGetRequiredInstanceExtensions(&n);
  if (!ext) return Status::error("GLFW cannot present with Vulkan: " + glfw_error());
  co.instance_extensions.assign(ext, ext + n);
  GLFWwindow* win = impl->window.get();
  co.create_surface = [win](VkInstance instance) -> Result<VkSurfaceKHR> {
    VkSurfaceKHR s = VK_NULL_HANDLE;
    if (const VkResult r = glfwCreateWindowSurface(instance, win, nullptr, &s); r != VK_SUCCESS)
      return Result<VkSurfaceKHR>::error("glfwCreateWindowSurface failed: " + vk::result_name(r));
    return s;
  };
  auto ctx = vk::Context::create(co);
  if (!ctx) return ctx.status();
  impl->ctx = std::move(*ctx);
  {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(impl->ctx->physical_device(), VK_FORMAT_R8G8B8A8_UNORM, &p);
    if (!(p.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT))
      return Status::error("the device cannot blit from RGBA8 images");
  }
  int w = 0, h = 0;
  glfwGetFramebufferSize(win, &w, &h);
  auto pass = ScenePass::create(*impl->ctx, {static_cast<uint32_t>(std::max(w, 1)),
                                             static_cast<uint32_t>(std::max(h, 1))});
  if (!pass) return pass.status();
  impl->pass = std::move(*pass);
  auto cmd = impl->ctx->allocate_command_buffer();
  if (!cmd) return cmd.status();
  impl->cmd = std::move(*cmd);
  auto fence = impl->ctx->create_fence(true);
  if (!fence) return fence.status();
  impl->frame_done = std::move(*fence);
  auto sem = impl->ctx->create_semaphore();
  if (!sem) return sem.status();
  impl->image_acquired = std::move(*sem);
  return std::unique_ptr<WindowPresenter>(new WindowPresenter(std::move(impl)));
}

WindowPresenter::WindowPresenter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
WindowPresenter::~WindowPresenter() = default;

bool WindowPresenter::should_close() const {
  return glfwWindowShouldClose(impl_->window.get()) == GLFW_TRUE;
}
void WindowPresenter::poll_events() { glfwPollEvents(); }
std::pair<int, int> WindowPresenter::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window.get(), &w, &h);
  return {w, h};
}
Status WindowPresenter::present(Scene scene) { return impl_->present(std::move(scene)); }
GLFWwindow* WindowPresenter::window() const { return impl_->window.get(); }
bool WindowPresenter::begin_panel() {
  if (!impl_->imgui_vulkan) return false;  // no panel, or no swapchain yet
  if (impl_->panel_frame) ImGui::EndFrame();  // the last panel frame was never presented
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  impl_->panel_frame = true;
  return true;
}
bool WindowPresenter::panel_wants_mouse() const {
  return impl_->imgui_context && ImGui::GetIO().WantCaptureMouse;
}
bool WindowPresenter::panel_wants_keyboard() const {
  return impl_->imgui_context && ImGui::GetIO().WantCaptureKeyboard;
}
std::string WindowPresenter::device_name() const { return impl_->ctx->device_name(); }
std::size_t WindowPresenter::validation_messages() const {
  return impl_->ctx->validation_messages();
}
std::size_t WindowPresenter::frames_presented() const { return impl_->frames; }
std::size_t WindowPresenter::swapchain_recreations() const { return impl_->recreations; }

}  // namespace ps::engine
