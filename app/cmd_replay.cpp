// planesketch replay LOG [-o MESH] [--png FILE] [--size WxH] [--report R.json]
// Replays a stroke log headless through the same event path as the window (SessionDriver),
// using the log's own timestamps, then writes the model and a picture of it.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>

#include "app/commands.h"
#include "app/session_driver.h"
#include "engine/renderer.h"
#include "engine/scene.h"
#include "app/session_scene.h"
#include "input/stroke_log_io.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"

namespace {

struct Options {
  std::string log, mesh, png, size = "1280x800", report;
  bool quiet = false;
  bool no_improve = false;
};

std::pair<int, int> parse_size(const std::string& s) {
  static const std::regex re(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, re))
    throw ps::app::CommandFailed("--size " + s + ": expected WIDTHxHEIGHT, e.g. 1280x800");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 16 || h < 16 || w > 8192 || h > 8192)
    throw ps::app::CommandFailed("--size " + s + ": each side must lie in [16, 8192]");
  return {w, h};
}

void run(const Options& o) {
  const auto [w, h] = parse_size(o.size);
  if (!o.mesh.empty() && !ps::is_mesh_extension(o.mesh))
    throw ps::app::CommandFailed(o.mesh + ": unknown mesh extension (expected .obj, .off, .ply or .stl)");
  std::vector<std::string> warnings;
  auto log = ps::read_stroke_log(o.log, &warnings);
  if (!log) throw ps::app::CommandFailed(log.message());
  for (const auto& wmsg : warnings) std::cerr << "planesketch: warning: " << wmsg << "\n";

  ps::SessionParams params;
  params.improve = !o.no_improve;
  ps::app::SessionDriver driver(params);
  ps::replay(*log, driver);
  for (const auto& m : driver.messages())
    std::cerr << "planesketch: " << o.log << ": t=" << m.t << " ms: " << m.text << "\n";
  const auto& st = driver.session().state();
  if (!o.quiet)
    std::cerr << "planesketch: replayed " << log->events.size() << " events: " << st.sections.curves.size()
              << " sections, model " << st.model.vertices.size() << " vertices / " << st.model.faces.size()
              << " faces\n";
  for (const auto& hint : st.hints) std::cerr << "planesketch: hint: " << hint << "\n";

  if (!o.mesh.empty()) {
    if (st.model.empty()) throw ps::app::CommandFailed(o.log + ": the log built no model (no accepted cross section)");
    if (auto s = ps::write_mesh(o.mesh, st.model); !s) throw ps::app::CommandFailed(s.message());
  }
  if (!o.png.empty()) {
    ps::engine::RendererOptions ro;
    ro.width = w;
    ro.height = h;
    ro.validation = ps::engine::validation_requested_by_environment();
    auto renderer = ps::engine::create_offscreen_renderer(ro);
    if (!renderer) throw ps::app::CommandFailed("cannot create a renderer: " + renderer.message());
    auto image = (*renderer)->render(ps::app::session_scene(driver, ps::app::framed_camera(driver, w, h)));
    if (!image) throw ps::app::CommandFailed("rendering failed: " + image.message());
    if (auto s = ps::engine::write_png(o.png, *image); !s) throw ps::app::CommandFailed(s.message());
  }
  if (!o.report.empty()) {
    nlohmann::json j;
    j["log"] = o.log;
    j["events"] = log->events.size();
    j["sections"] = st.sections.curves.size();
    j["vertices"] = st.model.vertices.size();
    j["faces"] = st.model.faces.size();
    const auto g = ps::check_guarantees(st.model);
    j["components"] = g.topology.components;
    j["genus"] = g.topology.genus;
    j["valid"] = g.valid();
    j["refused"] = nlohmann::json::array();
    for (const auto& m : driver.messages()) j["refused"].push_back({{"t", m.t}, {"message", m.text}});
    j["hints"] = st.hints;
    j["stroke_latency_ms"] = driver.stroke_latencies_ms();
    std::ofstream f(o.report);
    f << j.dump(2) << "\n";
    if (!f) throw ps::app::CommandFailed(o.report + ": cannot write report");
  }
}

void setup(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("replay", "Replay a stroke log headless and write the model (and a PNG)");
  cmd->add_option("log", o->log, "Stroke log (.jsonl)")->required();
  cmd->add_option("-o,--output", o->mesh, "Output mesh (.obj, .off, .ply, .stl)");
  cmd->add_option("--png", o->png, "Render the final scene to this PNG");
  cmd->add_option("--size", o->size, "PNG size WIDTHxHEIGHT (default 1280x800)");
  cmd->add_option("--report", o->report, "Write a JSON summary here");
  cmd->add_flag("-q,--quiet", o->quiet, "Less output");
  cmd->add_flag("--no-improve", o->no_improve, "Skip refinement and smoothing of the model");
  cmd->callback([o] { run(*o); });
}

}  // namespace

PLANESKETCH_COMMAND(10, setup);
