#pragma once
// The renderer interface and the headless (offscreen) Vulkan renderer.
//
//   auto r = ps::engine::create_offscreen_renderer({.width = 1280, .height = 800});
//   if (!r) { report(r.message()); }
//   auto img = (*r)->render(scene);            // Result<Image>, RGBA8, top row first
//   ps::engine::write_png("out.png", *img);
//
// The target size follows scene.camera.width/height (targets are recreated when it changes).
// A renderer is meant to be reused for many frames: pipelines, targets and buffers are kept,
// and a mesh is re-uploaded only when its content (fingerprint) or wireframe flag changes.
// Rendering is synchronous: draw() returns when the GPU has finished the frame.
//
// Validation: RendererOptions::validation, or the environment variable
// PLANESKETCH_VALIDATION=1, enables VK_LAYER_KHRONOS_validation with a debug-utils messenger;
// validation_messages() counts the warnings and errors it reported (each is also logged).
#include <functional>
#include <memory>
#include <string>

#include "engine/image.h"
#include "engine/scene.h"
#include "modeling/status.h"

namespace ps::engine {

// Counters for tests and benchmarks.
struct RenderStats {
  std::size_t frames = 0;        // successful draw() calls
  std::size_t mesh_uploads = 0;  // times a mesh was (re)uploaded to the device
};

class Renderer {
 public:
  virtual ~Renderer();
  // Draw the scene into the target and wait for the GPU; the frame stays on the device.
  virtual Status draw(const Scene& scene) = 0;
  // Copy the last drawn frame to the CPU.
  virtual Result<Image> read_back() = 0;
  // draw() + read_back().
  Result<Image> render(const Scene& scene);

  virtual std::string device_name() const = 0;
  // Validation warnings + errors reported so far (0 when validation is off).
  virtual std::size_t validation_messages() const = 0;
  virtual RenderStats stats() const = 0;
};

struct RendererOptions {
  int width = 1280;  // initial target size; follows scene.camera afterwards
  int height = 800;
  bool validation = false;  // also on when PLANESKETCH_VALIDATION=1
  bool prefer_gpu = true;   // false: take lavapipe (CPU) even when a GPU exists
  // Cull back faces of the opaque solid when it is closed and consistently oriented. The image
  // is the same either way for such meshes (tested); off helps to look at broken meshes.
  bool cull_closed_solids = true;
  // Where the one-line device report and validation messages go; null = stderr.
  std::function<void(const std::string&)> log;
};

Result<std::unique_ptr<Renderer>> create_offscreen_renderer(const RendererOptions& options);

// True when PLANESKETCH_VALIDATION is set to a value other than "" or "0".
bool validation_requested_by_environment();

}  // namespace ps::engine
