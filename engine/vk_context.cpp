// Vulkan bring-up: instance, validation messenger, device selection, queue, command pool.
#include "engine/vk_context.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>
#endif

#ifndef PLANESKETCH_SHADER_DIR
#define PLANESKETCH_SHADER_DIR ""
#endif

namespace ps::engine::vk {

void destroy_debug_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger,
                             const VkAllocationCallbacks* allocator) {
  auto fn = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
  if (fn) fn(instance, messenger, allocator);
}

void free_descriptor_set(VkDevice device, VkDescriptorPool pool, uint32_t count,
                         const VkDescriptorSet* sets) {
  vkFreeDescriptorSets(device, pool, count, sets);
}

std::string result_name(VkResult r) {
  switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_SUBOPTIMAL_KHR: return "VK_SUBOPTIMAL_KHR";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    case VK_ERROR_SURFACE_LOST_KHR: return "VK_ERROR_SURFACE_LOST_KHR";
    case VK_ERROR_OUT_OF_DATE_KHR: return "VK_ERROR_OUT_OF_DATE_KHR";
    default: return "VkResult " + std::to_string(static_cast<int>(r));
  }
}

std::string shader_dir() {
  if (const char* env = std::getenv("PLANESKETCH_SHADER_DIR"); env && *env) return env;
  return PLANESKETCH_SHADER_DIR;
}

namespace {

#define PS_VK_TRY(call, what)                                                         \
  do {                                                                                \
    const VkResult ps_vk_result_ = (call);                                            \
    if (ps_vk_result_ != VK_SUCCESS)                                                  \
      return Status::error(std::string(what) + " failed: " + result_name(ps_vk_result_)); \
  } while (0)

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* counter = static_cast<ValidationCounter*>(user);
  const bool error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
  if (error)
    ++counter->errors;
  else
    ++counter->warnings;
  const std::string line = std::string("vulkan validation ") + (error ? "error: " : "warning: ") +
                           (data && data->pMessage ? data->pMessage : "(no message)");
  if (counter->log)
    counter->log(line);
  else
    std::cerr << "planesketch: " << line << "\n";
  return VK_FALSE;
}

bool has_layer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool has_instance_extension(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, ext.data());
  return std::any_of(ext.begin(), ext.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

bool has_device_extension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
  return std::any_of(ext.begin(), ext.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

int type_score(VkPhysicalDeviceType t, bool prefer_gpu) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return prefer_gpu ? 5 : 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return prefer_gpu ? 4 : 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return prefer_gpu ? 3 : 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return prefer_gpu ? 2 : 5;
    default: return 1;
  }
}

// The formats the renderer needs (see offscreen_renderer.cpp) as colour/depth attachments.
bool supports_targets(VkPhysicalDevice pd) {
  const auto color_ok = [&](VkFormat f) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(pd, f, &p);
    const VkFormatFeatureFlags need =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
    return (p.optimalTilingFeatures & need) == need;
  };
  VkFormatProperties dp;
  vkGetPhysicalDeviceFormatProperties(pd, VK_FORMAT_D32_SFLOAT, &dp);
  return color_ok(VK_FORMAT_R8G8B8A8_UNORM) && color_ok(VK_FORMAT_R16G16B16A16_SFLOAT) &&
         color_ok(VK_FORMAT_R16_SFLOAT) &&
         (dp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) != 0;
}

}  // namespace

#if defined(__SANITIZE_ADDRESS__)
// Under AddressSanitizer only: the Vulkan loader unloads the driver (libvulkan_lvp.so, with
// LLVM) and the layers when the instance is destroyed, and LeakSanitizer, which reports at
// process exit, then sees the driver's own small leaks as "<unknown module>" that no
// suppression can match. Keeping those libraries mapped (RTLD_NODELETE) lets
// tests/sanitizers/lsan.supp attribute and suppress them. Release builds do not do this.
static void pin_vulkan_libraries() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) -> int {
        const std::string name = info->dlpi_name ? info->dlpi_name : "";
        if (name.find("libvulkan_") != std::string::npos ||
            name.find("VkLayer") != std::string::npos || name.find("libLLVM") != std::string::npos)
          (void)dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
}
#endif

void Context::log(const std::string& line) const {
  if (log_)
    log_(line);
  else
    std::cerr << "planesketch: " << line << "\n";
}

Context::~Context() {
  if (device_) vkDeviceWaitIdle(device_.get());
}

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
  std::unique_ptr<Context> ctx(new Context());
  ctx->log_ = options.log;
  ctx->validation_->log = options.log;

  // === Instance (+ validation layer and messenger)
  std::vector<const char*> layers;
  std::vector<const char*> extensions = options.instance_extensions;
  const bool validation = options.validation;
  if (validation) {
    if (!has_layer("VK_LAYER_KHRONOS_validation"))
      return Status::error(
          "Vulkan validation requested but VK_LAYER_KHRONOS_validation is not installed "
          "(Debian: vulkan-validationlayers)");
    if (!has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
      return Status::error("Vulkan validation requested but " +
                           std::string(VK_EXT_DEBUG_UTILS_EXTENSION_NAME) + " is missing");
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  for (const char* e : options.instance_extensions)
    if (!has_instance_extension(e))
      return Status::error(std::string("Vulkan instance extension ") + e + " is not available");

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "planesketch";
  app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
  app.pEngineName = "planesketch";
  app.engineVersion = VK_MAKE_VERSION(0, 1, 0);
  app.apiVersion = VK_API_VERSION_1_1;

  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = on_validation_message;
  messenger_info.pUserData = ctx->validation_.get();

  VkInstanceCreateInfo ici{};
  ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  if (validation) ici.pNext = &messenger_info;  // also report instance creation problems
  VkInstance instance = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateInstance(&ici, nullptr, &instance); r != VK_SUCCESS)
    return Status::error("cannot create a Vulkan instance (" + result_name(r) +
                         "); is a Vulkan driver installed? (Debian: mesa-vulkan-drivers)");
  ctx->instance_ = Instance(instance);

  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (!create) return Status::error("vkCreateDebugUtilsMessengerEXT is not available");
    VkDebugUtilsMessengerEXT m = VK_NULL_HANDLE;
    PS_VK_TRY(create(instance, &messenger_info, nullptr, &m), "vkCreateDebugUtilsMessengerEXT");
    ctx->messenger_ = DebugMessenger(instance, m);
  }

  if (options.create_surface) {
    auto surface = options.create_surface(instance);
    if (!surface) return surface.status();
    ctx->surface_ = Surface(instance, *surface);
  }

  // === Physical device selection
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  if (devices.empty())
    return Status::error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");

  int best_score = -1;
  std::vector<std::string> rejected;
  for (VkPhysicalDevice pd : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> families(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &nq, families.data());
    int family = -1;
    for (uint32_t i = 0; i < nq; ++i) {
      if (!(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
      if (ctx->surface_) {
        VkBool32 present = VK_FALSE;
        vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, ctx->surface_.get(), &present);
        if (!present) continue;
      }
      family = static_cast<int>(i);
      break;
    }
    std::string why;
    if (family < 0) why = "no graphics queue";
    if (why.empty() && props.apiVersion < VK_API_VERSION_1_1) why = "Vulkan < 1.1";
    if (why.empty() && !supports_targets(pd)) why = "missing attachment formats";
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceFeatures(pd, &features);
    if (why.empty() && !features.independentBlend) why = "no independentBlend (needed for OIT)";
    if (why.empty() && ctx->surface_ && !has_device_extension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      why = "no swapchain";
    if (!why.empty()) {
      rejected.push_back(std::string(props.deviceName) + ": " + why);
      continue;
    }
    const int score = type_score(props.deviceType, options.prefer_gpu);
    if (score > best_score) {
      best_score = score;
      ctx->physical_ = pd;
      ctx->queue_family_ = static_cast<uint32_t>(family);
      ctx->device_type_ = props.deviceType;
      ctx->device_name_ = props.deviceName;
    }
  }
  if (!ctx->physical_) {
    std::string msg = "no usable Vulkan device:";
    for (const auto& r : rejected) msg += " [" + r + "]";
    return Status::error(msg);
  }
  vkGetPhysicalDeviceMemoryProperties(ctx->physical_, &ctx->memory_);
#if defined(__GLIBC__)
  // lavapipe allocates large vertex buffers per draw on its queue thread; glibc returns the
  // freed memory to the kernel (heap trimming) and every frame faults it back in, about 7000
  // page faults per frame for a 100k-triangle mesh. Keeping up to 256 MB of freed heap cuts
  // that by 80 % (bench/results/render.md). Process-wide, so only for CPU devices.
  if (ctx->device_type_ == VK_PHYSICAL_DEVICE_TYPE_CPU) mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  ctx->log("Vulkan device: " + ctx->device_name_ + " (" + type_name(ctx->device_type_) + ", " +
           std::to_string(devices.size()) + " found" + (validation ? ", validation on" : "") + ")");

  // === Logical device, queue, command pool
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{};
  qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qci.queueFamilyIndex = ctx->queue_family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  std::vector<const char*> device_ext;
  if (ctx->surface_) device_ext.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  VkPhysicalDeviceFeatures enabled{};
  enabled.independentBlend = VK_TRUE;  // OIT: accumulation and revealage blend differently
  VkDeviceCreateInfo dci{};
  dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  dci.pEnabledFeatures = &enabled;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(device_ext.size());
  dci.ppEnabledExtensionNames = device_ext.data();
  VkDevice device = VK_NULL_HANDLE;
  PS_VK_TRY(vkCreateDevice(ctx->physical_, &dci, nullptr, &device), "vkCreateDevice");
  ctx->device_ = Device(device);
  vkGetDeviceQueue(device, ctx->queue_family_, 0, &ctx->queue_);
#if defined(__SANITIZE_ADDRESS__)
  pin_vulkan_libraries();
#endif

  VkCommandPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx->queue_family_;
  VkCommandPool pool = VK_NULL_HANDLE;
  PS_VK_TRY(vkCreateCommandPool(device, &pci, nullptr, &pool), "vkCreateCommandPool");
  ctx->command_pool_ = CommandPool(device, pool);
  return ctx;
}

Result<uint32_t> Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags want,
                                           VkMemoryPropertyFlags prefer) const {
  int fallback = -1;
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    const VkMemoryPropertyFlags f = memory_.memoryTypes[i].propertyFlags;
    if ((f & want) != want) continue;
    if ((f & prefer) == prefer) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback < 0) return Result<uint32_t>::error("no suitable Vulkan memory type");
  return static_cast<uint32_t>(fallback);
}

Result<BufferAlloc> Context::create_buffer(VkDeviceSize size, VkBufferUsageFlags usage,
                                           bool host_visible) const {
  BufferAlloc out;
  out.size = size;
  VkBufferCreateInfo bci{};
  bci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bci.size = size;
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateBuffer(device(), &bci, nullptr, &buffer); r != VK_SUCCESS)
    return Result<BufferAlloc>::error("vkCreateBuffer (" + std::to_string(size) +
                                      " bytes) failed: " + result_name(r));
  out.buffer = Buffer(device(), buffer);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device(), buffer, &req);
  const VkMemoryPropertyFlags want =
      host_visible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                   : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  auto type = find_memory_type(req.memoryTypeBits, want, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (!type) return type.status();
  VkMemoryAllocateInfo mai{};
  mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = *type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  if (const VkResult r = vkAllocateMemory(device(), &mai, nullptr, &memory); r != VK_SUCCESS)
    return Result<BufferAlloc>::error("vkAllocateMemory (" + std::to_string(req.size) +
                                      " bytes) failed: " + result_name(r));
  out.memory = Memory(device(), memory);
  if (const VkResult r = vkBindBufferMemory(device(), buffer, memory, 0); r != VK_SUCCESS)
    return Result<BufferAlloc>::error("vkBindBufferMemory failed: " + result_name(r));
  if (host_visible) {
    if (const VkResult r = vkMapMemory(device(), memory, 0, VK_WHOLE_SIZE, 0, &out.mapped);
        r != VK_SUCCESS)
      return Result<BufferAlloc>::error("vkMapMemory failed: " + result_name(r));
  }
  return out;
}

Result<ImageAlloc> Context::create_image(VkExtent2D extent, VkFormat format,
                                         VkImageUsageFlags usage, VkImageAspectFlags aspect) const {
  ImageAlloc out;
  out.format = format;
  out.extent = extent;
  VkImageCreateInfo ici{};
  ici.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {extent.width, extent.height, 1};
  ici.mipLevels = 1;
  ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateImage(device(), &ici, nullptr, &image); r != VK_SUCCESS)
    return Result<ImageAlloc>::error("vkCreateImage " + std::to_string(extent.width) + "x" +
                                     std::to_string(extent.height) + " failed: " + result_name(r));
  out.image = Image(device(), image);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device(), image, &req);
  auto type = find_memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  if (!type) return type.status();
  VkMemoryAllocateInfo mai{};
  mai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = *type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  if (const VkResult r = vkAllocateMemory(device(), &mai, nullptr, &memory); r != VK_SUCCESS)
    return Result<ImageAlloc>::error("vkAllocateMemory for image failed: " + result_name(r));
  out.memory = Memory(device(), memory);
  if (const VkResult r = vkBindImageMemory(device(), image, memory, 0); r != VK_SUCCESS)
    return Result<ImageAlloc>::error("vkBindImageMemory failed: " + result_name(r));
  VkImageViewCreateInfo vci{};
  vci.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vci.image = image;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = format;
  vci.subresourceRange = {aspect, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateImageView(device(), &vci, nullptr, &view); r != VK_SUCCESS)
    return Result<ImageAlloc>::error("vkCreateImageView failed: " + result_name(r));
  out.view = ImageView(device(), view);
  return out;
}

Result<ShaderModule> Context::load_shader(const std::string& spv_name) const {
  const std::string path = shader_dir() + "/" + spv_name;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return Result<ShaderModule>::error("cannot open shader " + path +
                                       " (set PLANESKETCH_SHADER_DIR to the folder of *.spv)");
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  if (bytes.empty() || bytes.size() % 4 != 0)
    return Result<ShaderModule>::error("shader " + path + " is not SPIR-V (size " +
                                       std::to_string(bytes.size()) + ")");
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  VkShaderModuleCreateInfo sci{};
  sci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  sci.codeSize = bytes.size();
  sci.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateShaderModule(device(), &sci, nullptr, &module); r != VK_SUCCESS)
    return Result<ShaderModule>::error("vkCreateShaderModule " + path + ": " + result_name(r));
  return ShaderModule(device(), module);
}

Result<CommandBuffer> Context::allocate_command_buffer() const {
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = command_pool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (const VkResult r = vkAllocateCommandBuffers(device(), &ai, &cmd); r != VK_SUCCESS)
    return Result<CommandBuffer>::error("vkAllocateCommandBuffers failed: " + result_name(r));
  return CommandBuffer(device(), command_pool(), cmd);
}

Result<Fence> Context::create_fence(bool signalled) const {
  VkFenceCreateInfo fci{};
  fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  fci.flags = signalled ? VkFenceCreateFlags{VK_FENCE_CREATE_SIGNALED_BIT} : VkFenceCreateFlags{0};
  VkFence fence = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateFence(device(), &fci, nullptr, &fence); r != VK_SUCCESS)
    return Result<Fence>::error("vkCreateFence failed: " + result_name(r));
  return Fence(device(), fence);
}

Result<Semaphore> Context::create_semaphore() const {
  VkSemaphoreCreateInfo sci{};
  sci.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  VkSemaphore s = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateSemaphore(device(), &sci, nullptr, &s); r != VK_SUCCESS)
    return Result<Semaphore>::error("vkCreateSemaphore failed: " + result_name(r));
  return Semaphore(device(), s);
}

Result<DescriptorPool> Context::create_descriptor_pool(VkDescriptorType type, uint32_t descriptors,
                                                       uint32_t max_sets) const {
  VkDescriptorPoolSize size{type, descriptors};
  VkDescriptorPoolCreateInfo dpci{};
  dpci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  dpci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dpci.maxSets = max_sets;
  dpci.poolSizeCount = 1;
  dpci.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateDescriptorPool(device(), &dpci, nullptr, &pool); r != VK_SUCCESS)
    return Result<DescriptorPool>::error("vkCreateDescriptorPool failed: " + result_name(r));
  return DescriptorPool(device(), pool);
}

Status Context::submit_and_wait(VkCommandBuffer cmd, VkFence fence) const {
  PS_VK_TRY(vkResetFences(device(), 1, &fence), "vkResetFences");
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  PS_VK_TRY(vkQueueSubmit(queue(), 1, &si, fence), "vkQueueSubmit");
  PS_VK_TRY(vkWaitForFences(device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  return Status::ok();
}

}  // namespace ps::engine::vk
