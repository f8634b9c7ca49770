// planesketch replay LOG [-o MESH] [--png FILE] [--size WxH] [--report R.json] [--journal J]
//                        [--pace-ms N] [--no-improve] [--save-session S.json] [--base MESH | --session S.json]
// Replays a stroke log headless through the same event path as the window (SessionDriver),
// using the log's own timestamps, then writes the model and a picture of it. With --journal
// the events are journaled as they are applied, exactly as the window journals live input
// (docs/session.md), so a headless session can be killed and recovered.
#include <iostream>

#include "app/commands.h"
#include "app/replay_run.h"
#include "input/stroke_log_io.h"

namespace {

void run(const ps::app::ReplayOptions& o, const std::string& path) {
  (void)ps::app::check_replay_options(o);
  std::vector<std::string> warnings;
  auto log = ps::read_stroke_log(path, &warnings);
  if (!log) throw ps::app::CommandFailed(log.message());
  for (const auto& w : warnings) std::cerr << "planesketch: warning: " << w << "\n";
  ps::app::run_replay(*log, path, o);
}

void setup(CLI::App& root) {
  auto o = std::make_shared<ps::app::ReplayOptions>();
  auto log = std::make_shared<std::string>();
  auto* cmd = root.add_subcommand("replay", "Replay a stroke log headless and write the model (and a PNG)");
  cmd->add_option("log", *log, "Stroke log (.jsonl)")->required();
  cmd->add_option("-o,--output", o->mesh, "Output mesh (.obj, .off, .ply, .stl)");
  cmd->add_option("--png", o->png, "Render the final scene to this PNG");
  cmd->add_option("--size", o->size, "PNG size WIDTHxHEIGHT (default 1280x800)");
  cmd->add_option("--report", o->report, "Write a JSON summary here");
  cmd->add_option("--journal", o->journal, "Journal the applied events to this new file, as the window does");
  cmd->add_option("--pace-ms", o->pace_ms, "Sleep this many wall-clock ms before each event (model unchanged)");
  cmd->add_option("--save-session", o->save_session, "Save the session (JSON, the mesh beside it) here at the end");
  cmd->add_option("--base", o->base_mesh, "Start from this mesh as an imported base (sculpt or deform it)");
  cmd->add_option("--session", o->start_session, "Start from this saved session");
  cmd->add_flag("-q,--quiet", o->quiet, "Less output");
  cmd->add_flag("--no-improve", o->no_improve, "Skip refinement and smoothing of the model");
  cmd->callback([o, log] { run(*o, *log); });
}

}  // namespace

PLANESKETCH_COMMAND(10, setup);
