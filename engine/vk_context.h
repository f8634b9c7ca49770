#pragma once
// Vulkan bring-up (engine-internal): instance, validation messenger, device selection, one
// graphics queue, a command pool, and helpers to allocate buffers and images.
//
// Device choice: with prefer_gpu, a discrete GPU beats an integrated one beats a virtual one
// beats a CPU implementation (lavapipe); without it, a CPU device is taken first (reproducible
// goldens). The choice is logged as one line.
#include <vulkan/vulkan.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/vk_raii.h"
#include "modeling/status.h"

namespace ps::engine::vk {

using LogFn = std::function<void(const std::string&)>;

// Counts validation warnings and errors; also forwards each message to the log.
struct ValidationCounter {
  std::atomic<std::size_t> warnings{0};
  std::atomic<std::size_t> errors{0};
  LogFn log;
};

struct ContextOptions {
  bool validation = false;
  bool prefer_gpu = true;
  LogFn log;                                      // null: one line on stderr
  std::vector<const char*> instance_extensions;   // e.g. from glfwGetRequiredInstanceExtensions
  // When set, called after instance creation; the chosen device must present to the surface.
  std::function<Result<VkSurfaceKHR>(VkInstance)> create_surface;
};

// A buffer with its own memory; mapped persistently when host-visible.
struct BufferAlloc {
  Memory memory;
  Buffer buffer;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

// An image with its own memory and one view.
struct ImageAlloc {
  Memory memory;
  Image image;
  ImageView view;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
};

class Context {
 public:
  static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  VkCommandPool command_pool() const { return command_pool_.get(); }
  VkSurfaceKHR surface() const { return surface_.get(); }
  const std::string& device_name() const { return device_name_; }
  bool is_cpu_device() const { return device_type_ == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  std::size_t validation_messages() const {
    return validation_->warnings.load() + validation_->errors.load();
  }
  void log(const std::string& line) const;

  // Memory and resources. `host_visible` buffers are mapped persistently (and preferably
  // device-local too, as on integrated GPUs and lavapipe).
  Result<BufferAlloc> create_buffer(VkDeviceSize size, VkBufferUsageFlags usage,
                                    bool host_visible) const;
  Result<ImageAlloc> create_image(VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                                  VkImageAspectFlags aspect) const;
  Result<ShaderModule> load_shader(const std::string& spv_name) const;
  Result<CommandBuffer> allocate_command_buffer() const;
  Result<Fence> create_fence(bool signalled) const;
  Result<Semaphore> create_semaphore() const;
  // A pool of `max_sets` sets holding up to `descriptors` descriptors of `type`; sets can be
  // freed one by one (FREE_DESCRIPTOR_SET).
  Result<DescriptorPool> create_descriptor_pool(VkDescriptorType type, uint32_t descriptors,
                                                uint32_t max_sets) const;
  // Submit a command buffer and wait for it (simple, for one-off work and the synchronous
  // offscreen path).
  Status submit_and_wait(VkCommandBuffer cmd, VkFence fence) const;

 private:
  Context() = default;
  Result<uint32_t> find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags want,
                                    VkMemoryPropertyFlags prefer) const;

  LogFn log_;
  std::unique_ptr<ValidationCounter> validation_ = std::make_unique<ValidationCounter>();
  // Member order is destruction order reversed: device children go before the device,
  // the device before the surface, messenger and instance.
  Instance instance_;
  DebugMessenger messenger_;
  Surface surface_;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceType device_type_ = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  VkPhysicalDeviceMemoryProperties memory_{};
  std::string device_name_;
  Device device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  CommandPool command_pool_;
};

// "VkResult name" for messages.
std::string result_name(VkResult r);

// Where compiled shaders are found: $PLANESKETCH_SHADER_DIR if set, else the build's folder.
std::string shader_dir();

}  // namespace ps::engine::vk
