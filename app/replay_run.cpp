#include "app/replay_run.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <thread>

#include "app/commands.h"
#include "app/journal.h"
#include "app/session_driver.h"
#include "app/session_scene.h"
#include "engine/image.h"
#include "engine/renderer.h"
#include "engine/scene.h"
#include "input/stroke_recorder.h"
#include "input/stroke_replayer.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/session_io.h"

namespace ps::app {

namespace {

std::pair<int, int> parse_size(const std::string& s) {
  static const std::regex re(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw CommandFailed("--size " + s + ": expected WIDTHxHEIGHT, e.g. 1280x800");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 16 || h < 16 || w > 8192 || h > 8192) throw CommandFailed("--size " + s + ": each side must lie in [16, 8192]");
  return {w, h};
}

void replay_all_paced(const StrokeLog& log, EventSink& sink, const StrokeReplayer::PaceFn& pace) {
  StrokeReplayer replayer(log);
  replayer.replay_all(sink, pace);
}

}  // namespace

std::pair<int, int> check_replay_options(const ReplayOptions& o) {
  const auto size = parse_size(o.size);
  if (!o.mesh.empty() && !is_export_extension(o.mesh))
    throw CommandFailed(o.mesh + ": unknown mesh extension (expected .obj, .off, .ply, .stl or .glb)");
  if (!o.base_mesh.empty() && !o.start_session.empty())
    throw CommandFailed("--base and --session both give the session's start: choose one");
  if (!std::isfinite(o.pace_ms) || o.pace_ms < 0.0 || o.pace_ms > 10000.0)
    throw CommandFailed("--pace-ms must lie in [0, 10000]");
  return size;
}

void run_replay(const StrokeLog& log, const std::string& name, const ReplayOptions& o,
                const nlohmann::json& report_extra) {
  const auto [w, h] = check_replay_options(o);

  SessionParams params;
  params.improve = !o.no_improve;
  SessionDriver driver(params);
  // The session's start: an imported mesh or a saved session (refused: nothing is replayed).
  // A journal records it first, as the `open` event recovery replays.
  std::optional<Result<OpenFile>> opened;
  if (!o.base_mesh.empty()) {
    if (auto st = driver.import_mesh(0.0, o.base_mesh); !st) throw CommandFailed(st.message());
    opened = open_file_event("mesh", o.base_mesh);
  }
  // (A loaded session brings its own parameters, --no-improve included.)
  if (!o.start_session.empty()) {
    if (auto st = driver.load_session(0.0, o.start_session); !st) throw CommandFailed(st.message());
    opened = open_file_event("session", o.start_session);
  }

  // Pacing only decides when events arrive (docs/stroke-log.md, "Replay").
  StrokeReplayer::PaceFn pace;
  if (o.pace_ms > 0.0) {
    const auto d = std::chrono::duration<double, std::milli>(o.pace_ms);
    pace = [d](double) { std::this_thread::sleep_for(d); };
  }
  if (!o.journal.empty()) {
    // The journal continues the replayed log: same header, the events as they are applied.
    auto rec = StrokeRecorder::open(o.journal, log.header);
    if (!rec) throw CommandFailed("cannot open the journal: " + rec.message());
    if (opened) {
      if (!*opened) throw CommandFailed("cannot journal the opened file: " + opened->message());
      if (auto st = rec->record(0.0, **opened); !st) throw CommandFailed("cannot write the journal: " + st.message());
    }
    JournalingSink sink(*rec, driver);
    replay_all_paced(log, sink, pace);
    if (auto st = rec->finish(log.events.empty() ? 0.0 : log.events.back().t); !st)
      throw CommandFailed("cannot finish the journal: " + st.message());
  } else {
    replay_all_paced(log, driver, pace);
  }

  for (const auto& m : driver.messages())
    std::cerr << "planesketch: " << name << ": t=" << m.t << " ms: " << m.text << "\n";
  if (!o.quiet)
    for (const auto& m : driver.notices())
      std::cerr << "planesketch: " << name << ": t=" << m.t << " ms: note: " << m.text << "\n";
  const auto& st = driver.session().state();
  if (!o.quiet)
    std::cerr << "planesketch: replayed " << log.events.size() << " events: " << st.sections.curves.size()
              << " sections, model " << st.model.vertices.size() << " vertices / " << st.model.faces.size()
              << " faces\n";
  for (const auto& hint : st.hints) std::cerr << "planesketch: hint: " << hint << "\n";

  if (!o.mesh.empty() && st.model.empty())
    throw CommandFailed(name + ": the log built no model (no accepted cross section)");

  std::optional<engine::Image> image;
  if (!o.png.empty()) {
    engine::RendererOptions ro;
    ro.width = w;
    ro.height = h;
    ro.validation = engine::validation_requested_by_environment();
    auto renderer = engine::create_offscreen_renderer(ro);
    if (!renderer) throw CommandFailed("cannot create a renderer: " + renderer.message());
    auto img = (*renderer)->render(session_scene(driver, framed_camera(driver, w, h)));
    if (!img) throw CommandFailed("rendering failed: " + img.message());
    image = std::move(*img);
  }
  std::string report_text;
  if (!o.report.empty()) {
    nlohmann::json j;
    j["log"] = name;
    j["events"] = log.events.size();
    j["sections"] = st.sections.curves.size();
    j["vertices"] = st.model.vertices.size();
    j["faces"] = st.model.faces.size();
    const auto g = check_guarantees(st.model);
    j["components"] = g.topology.components;
    j["genus"] = g.topology.genus;
    j["valid"] = g.valid();
    j["refused"] = nlohmann::json::array();
    for (const auto& m : driver.messages()) j["refused"].push_back({{"t", m.t}, {"message", m.text}});
    j["hints"] = st.hints;
    j["notices"] = nlohmann::json::array();
    for (const auto& m : driver.notices()) j["notices"].push_back({{"t", m.t}, {"message", m.text}});
    j["stroke_latency_ms"] = driver.stroke_latencies_ms();
    for (const auto& [k, v] : report_extra.items()) j[k] = v;
    report_text = j.dump(2) + "\n";
  }

  if (!o.mesh.empty())
    if (auto s = export_model(o.mesh, st.model); !s) throw CommandFailed(s.message());
  if (!o.save_session.empty())
    if (auto s = save_session(o.save_session, driver.session()); !s) throw CommandFailed(s.message());
  if (image)
    if (auto s = engine::write_png(o.png, *image); !s) throw CommandFailed(s.message());
  if (!o.report.empty()) {
    std::ofstream f(o.report);
    f << report_text;
    if (!f) throw CommandFailed(o.report + ": cannot write report");
  }
}

}  // namespace ps::app
