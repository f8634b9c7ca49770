#pragma once
// Move-only owners for Vulkan handles (engine-internal).
//
// Every Vulkan object the engine creates lives in one of these wrappers; the wrapper's
// destructor is the only place that object is destroyed, so no class keeps a hand-written list
// of vkDestroy* calls. Destruction order follows C++ member order: declare owners after the
// objects they depend on (device after instance, view after image, ...).
//
// Lifetime rule: both users keep at most one frame in flight. The offscreen renderer waits for
// each frame's fence before it returns; the window presenter waits for the previous frame's
// fence before it prepares the next one and idles the device before it replaces the swapchain.
// So when an owner is destroyed or replaced no submitted work uses it, and no deletion queue
// is needed. (Code that keeps several frames in flight would have to keep a replaced owner
// alive until the fence of the last frame using it has signalled.)
#include <vulkan/vulkan.h>

#include <utility>

namespace ps::engine::vk {

// === Instance-level and device-level owners

// An owner of a handle destroyed by a function taking (parent, handle, allocator).
template <class Parent, class Handle, auto Destroy>
class Owned {
 public:
  Owned() = default;
  Owned(Parent parent, Handle handle) : parent_(parent), handle_(handle) {}
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  Owned(Owned&& o) noexcept : parent_(o.parent_), handle_(std::exchange(o.handle_, Handle{})) {}
  Owned& operator=(Owned&& o) noexcept {
    if (this != &o) {
      reset();
      parent_ = o.parent_;
      handle_ = std::exchange(o.handle_, Handle{});
    }
    return *this;
  }
  ~Owned() { reset(); }

  void reset() {
    if (handle_ != Handle{}) Destroy(parent_, handle_, nullptr);
    handle_ = Handle{};
  }
  Handle get() const { return handle_; }
  Handle operator*() const { return handle_; }
  explicit operator bool() const { return handle_ != Handle{}; }

 private:
  Parent parent_{};
  Handle handle_{};
};

// An owner of a top-level handle destroyed by a function taking (handle, allocator).
template <class Handle, auto Destroy>
class OwnedRoot {
 public:
  OwnedRoot() = default;
  explicit OwnedRoot(Handle handle) : handle_(handle) {}
  OwnedRoot(const OwnedRoot&) = delete;
  OwnedRoot& operator=(const OwnedRoot&) = delete;
  OwnedRoot(OwnedRoot&& o) noexcept : handle_(std::exchange(o.handle_, Handle{})) {}
  OwnedRoot& operator=(OwnedRoot&& o) noexcept {
    if (this != &o) {
      reset();
      handle_ = std::exchange(o.handle_, Handle{});
    }
    return *this;
  }
  ~OwnedRoot() { reset(); }

  void reset() {
    if (handle_ != Handle{}) Destroy(handle_, nullptr);
    handle_ = Handle{};
  }
  Handle get() const { return handle_; }
  Handle operator*() const { return handle_; }
  explicit operator bool() const { return handle_ != Handle{}; }

 private:
  Handle handle_{};
};

using Instance = OwnedRoot<VkInstance, vkDestroyInstance>;
using Device = OwnedRoot<VkDevice, vkDestroyDevice>;

using Buffer = Owned<VkDevice, VkBuffer, vkDestroyBuffer>;
using Memory = Owned<VkDevice, VkDeviceMemory, vkFreeMemory>;
using Image = Owned<VkDevice, VkImage, vkDestroyImage>;
using ImageView = Owned<VkDevice, VkImageView, vkDestroyImageView>;
using RenderPass = Owned<VkDevice, VkRenderPass, vkDestroyRenderPass>;
using Framebuffer = Owned<VkDevice, VkFramebuffer, vkDestroyFramebuffer>;
using ShaderModule = Owned<VkDevice, VkShaderModule, vkDestroyShaderModule>;
using Pipeline = Owned<VkDevice, VkPipeline, vkDestroyPipeline>;
using PipelineLayout = Owned<VkDevice, VkPipelineLayout, vkDestroyPipelineLayout>;
using DescriptorSetLayout = Owned<VkDevice, VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = Owned<VkDevice, VkDescriptorPool, vkDestroyDescriptorPool>;
using CommandPool = Owned<VkDevice, VkCommandPool, vkDestroyCommandPool>;
using Fence = Owned<VkDevice, VkFence, vkDestroyFence>;
using Semaphore = Owned<VkDevice, VkSemaphore, vkDestroySemaphore>;
using Sampler = Owned<VkDevice, VkSampler, vkDestroySampler>;
using Surface = Owned<VkInstance, VkSurfaceKHR, vkDestroySurfaceKHR>;
using Swapchain = Owned<VkDevice, VkSwapchainKHR, vkDestroySwapchainKHR>;

// The debug messenger's destroy function is an extension entry point, loaded at run time.
void destroy_debug_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger,
                             const VkAllocationCallbacks* allocator);
using DebugMessenger =
    Owned<VkInstance, VkDebugUtilsMessengerEXT, destroy_debug_messenger>;

// === Pool-allocated owners (command buffers, descriptor sets)

// A command buffer or descriptor set returned to its pool on destruction.
template <class Handle, class Pool, auto Free>
class PoolOwned {
 public:
  PoolOwned() = default;
  PoolOwned(VkDevice device, Pool pool, Handle handle)
      : device_(device), pool_(pool), handle_(handle) {}
  PoolOwned(const PoolOwned&) = delete;
  PoolOwned& operator=(const PoolOwned&) = delete;
  PoolOwned(PoolOwned&& o) noexcept
      : device_(o.device_), pool_(o.pool_), handle_(std::exchange(o.handle_, Handle{})) {}
  PoolOwned& operator=(PoolOwned&& o) noexcept {
    if (this != &o) {
      reset();
      device_ = o.device_;
      pool_ = o.pool_;
      handle_ = std::exchange(o.handle_, Handle{});
    }
    return *this;
  }
  ~PoolOwned() { reset(); }

  void reset() {
    if (handle_ != Handle{}) Free(device_, pool_, 1u, &handle_);
    handle_ = Handle{};
  }
  Handle get() const { return handle_; }
  Handle operator*() const { return handle_; }
  explicit operator bool() const { return handle_ != Handle{}; }

 private:
  VkDevice device_{};
  Pool pool_{};
  Handle handle_{};
};

using CommandBuffer = PoolOwned<VkCommandBuffer, VkCommandPool, vkFreeCommandBuffers>;
// The pool must be created with VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT.
void free_descriptor_set(VkDevice device, VkDescriptorPool pool, uint32_t count,
                         const VkDescriptorSet* sets);
using DescriptorSet = PoolOwned<VkDescriptorSet, VkDescriptorPool, free_descriptor_set>;

}  // namespace ps::engine::vk
