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

ps::engine::Scene session_scene(const ps::app::SessionDriver& d, int w, int h) {
  using namespace ps::engine;
  Scene scene;
  const auto& st = d.session().state();
  ps::Box3 box = ps::bounding_box(st.model.vertices);
  for (const auto& p : st.sewn.all_points()) box.extend(p);
  if (box.empty()) box.extend(ps::Vec3::Constant(-1.0)), box.extend(ps::Vec3::Constant(1.0));
  // The picture looks from the log's initial viewing direction, framed on the model (the log's
  // last camera faces the last plane sketched on, which often shows the model edge-on).
  scene.camera = d.initial_camera();
  scene.camera.width = w;
  scene.camera.height = h;
  {
    const ps::Vec3 dir = (scene.camera.eye - scene.camera.target).normalized();
    const double radius = 0.5 * box.diagonal() * 1.25;
    const double half_fov = 0.5 * scene.camera.fov_y_deg * M_PI / 180.0 * std::min(1.0, scene.camera.aspect());
    scene.camera.target = box.center();
    scene.camera.eye = box.center() + dir * (radius / std::sin(half_fov));
    scene.camera.near_plane = 0.01 * radius;
    scene.camera.far_plane = 100.0 * radius;
  }
  const ps::Vec3 c = box.center();
  const double half = std::max(0.75 * box.size().maxCoeff(), 0.5);
  static const Rgba colors[3] = {{0.90f, 0.25f, 0.25f, 0.16f}, {0.25f, 0.75f, 0.30f, 0.16f},
                                 {0.25f, 0.40f, 0.95f, 0.16f}};
  const auto& planes = d.input().planes;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    PlaneVisual pv;
    pv.plane = planes[i];
    pv.center = planes[i].project(c);
    pv.half_size = half;
    const int axis = planes[i].axis();
    pv.color = colors[axis >= 0 ? axis : static_cast<int>(i % 3)];
    pv.selected = static_cast<int>(i) == d.input().selected_plane;
    scene.planes.push_back(pv);
  }
  for (const auto& cs : st.sewn.curves) {
    StrokeVisual sv;
    sv.points = cs.points;
    sv.closed = true;
    sv.color = Rgba{0.95f, 0.70f, 0.10f, 1.0f};
    sv.width_px = 3.0f;
    scene.strokes.push_back(std::move(sv));
  }
  if (!st.model.empty()) scene.solid = MeshVisual{st.model, Rgba{0.78f, 0.80f, 0.84f, 1.0f}, false};
  return scene;
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
    auto image = (*renderer)->render(session_scene(driver, w, h));
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
