// planesketch render MESH --png FILE [--size WxH] [--view iso|x|y|z] [--wireframe]
// Renders a mesh headless (lavapipe when there is no GPU) with the three basic planes around it.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/commands.h"
#include "engine/renderer.h"
#include "engine/scene.h"
#include "modeling/mesh_io.h"

namespace ps::app {
namespace {

struct RenderArgs {
  std::string mesh;
  std::string png;
  std::string size = "1280x800";
  std::string view = "iso";
  bool wireframe = false;
  bool validation = false;
};

// "WIDTHxHEIGHT" with 1 to 5 digits each (std::regex is avoided: GCC 12 warns inside it under
// the sanitizer build, and -Werror is on in CI).
std::optional<std::pair<int, int>> parse_size(const std::string& s) {
  const auto x = s.find('x');
  if (x == std::string::npos) return std::nullopt;
  const auto number = [](const std::string& t) -> std::optional<int> {
    if (t.empty() || t.size() > 5) return std::nullopt;
    int v = 0;
    for (char c : t) {
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
    }
    return v;
  };
  const auto w = number(s.substr(0, x)), h = number(s.substr(x + 1));
  if (!w || !h) return std::nullopt;
  return std::pair{*w, *h};
}

void run_render(const RenderArgs& a) {
  // === Arguments
  const auto size = parse_size(a.size);
  if (!size) throw CommandFailed("--size '" + a.size + "': expected WIDTHxHEIGHT, e.g. 1280x800", 2);
  const auto [w, h] = *size;
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw CommandFailed("--size '" + a.size + "': width and height must be in 1..16384", 2);
  const auto view = engine::parse_view(a.view);
  if (!view) throw CommandFailed("--view '" + a.view + "': expected iso, x, y or z", 2);
  if (a.png.empty()) throw CommandFailed("--png: an output file is required", 2);

  // === Load, frame, render, write
  auto mesh = ps::read_mesh(a.mesh);
  if (!mesh) throw CommandFailed(mesh.message());
  const engine::Scene scene = engine::default_scene(*mesh, *view, w, h, a.wireframe);
  engine::RendererOptions opts;
  opts.width = w;
  opts.height = h;
  opts.validation = a.validation;
  auto renderer = engine::create_offscreen_renderer(opts);
  if (!renderer) throw CommandFailed("cannot start the renderer: " + renderer.message());
  auto image = (*renderer)->render(scene);
  if (!image) throw CommandFailed("rendering failed: " + image.message());
  if (a.validation && (*renderer)->validation_messages() > 0)
    throw CommandFailed(std::to_string((*renderer)->validation_messages()) +
                        " Vulkan validation messages (see above); no PNG written");
  if (auto st = engine::write_png(a.png, *image); !st) throw CommandFailed(st.message());
}

void setup_render(CLI::App& root) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = root.add_subcommand(
      "render", "Render a mesh (OBJ, OFF, PLY, STL) with the three reference planes to a PNG");
  cmd->add_option("mesh", args->mesh, "input mesh")->required();
  cmd->add_option("--png", args->png, "output PNG file")->required();
  cmd->add_option("--size", args->size, "image size WxH (default 1280x800)");
  cmd->add_option("--view", args->view, "iso, x, y or z (default iso)");
  cmd->add_flag("--wireframe", args->wireframe, "overlay the triangle edges");
  cmd->add_flag("--validation", args->validation,
                "enable Vulkan validation layers; fail if they report anything");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace

PLANESKETCH_COMMAND(40, setup_render);

}  // namespace ps::app
