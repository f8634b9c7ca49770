// planesketch recover [JOURNAL] [-o MESH] [--png FILE] [--size WxH] [--report R.json]
//                     [--dir DIR] [--list] [--no-improve]
// (also spelled `planesketch --recover [JOURNAL] ...`, see main.cpp)
// Crash recovery: replays a session journal through the same path as `planesketch replay`, so
// the recovered model is the one the dead session had built from the events it journaled.
// Without JOURNAL it takes the newest unfinished journal (no end marker, not locked by a live
// session) in the journal directory. The journal itself is only read, never changed.
#include <chrono>
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "app/journal.h"
#include "app/replay_run.h"
#include "input/stroke_log_io.h"

namespace {

namespace fs = std::filesystem;

struct Options {
  ps::app::ReplayOptions replay;
  std::string journal, dir;
  bool list = false;
};

void list(const fs::path& dir) {
  const auto all = ps::app::list_journals(dir);
  if (all.empty()) {
    std::cout << "no journals in " << dir.string() << "\n";
    return;
  }
  for (const auto& j : all)
    std::cout << (j.finished ? "finished  " : j.in_use ? "in use    " : "unfinished") << "  " << j.path.string() << "\n";
}

void run(Options o) {
  (void)ps::app::check_replay_options(o.replay);
  const fs::path dir = o.dir.empty() ? ps::app::journal_dir() : fs::path(o.dir);
  if (o.list) {
    list(dir);
    return;
  }
  std::string path = o.journal;
  if (path.empty()) {
    const auto j = ps::app::newest_unfinished_journal(dir);
    if (!j) throw ps::app::CommandFailed("recover: no unfinished journal in " + dir.string() + " (nothing to recover)", 3);
    path = j->path.string();
    std::cerr << "planesketch: recovering " << path << "\n";
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw ps::app::CommandFailed(path + ": is a directory, not a journal");
  std::vector<std::string> warnings;
  auto log = ps::read_stroke_log(path, &warnings);
  if (!log) throw ps::app::CommandFailed(log.message());
  bool torn = false;
  for (const auto& w : warnings) {
    std::cerr << "planesketch: warning: " << w << "\n";
    if (w.find("truncated last line dropped") != std::string::npos) torn = true;
  }
  if (log->end_t && !o.replay.quiet)
    std::cerr << "planesketch: " << path << ": the session ended cleanly (end marker); replaying it anyway\n";

  nlohmann::json extra;
  extra["journal"] = path;
  extra["finished"] = log->end_t.has_value();
  extra["torn_last_line_dropped"] = torn;
  extra["warnings"] = warnings;
  ps::app::run_replay(*log, path, o.replay, extra);
  if (!o.replay.quiet) {
    std::cerr << "planesketch: recovered " << log->events.size() << " events from " << path << "\n";
    std::cerr << "planesketch: continue the session with: planesketch window --replay " << path << "\n";
  }
}

void setup(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand("recover", "Recover a crashed session from its journal (default: the newest unfinished one)");
  cmd->add_option("journal", o->journal, "Journal (.jsonl); default: newest unfinished journal in --dir");
  cmd->add_option("--dir", o->dir, "Journal directory (default: $XDG_STATE_HOME/planesketch or ~/.local/state/planesketch)");
  cmd->add_flag("--list", o->list, "List the journals in --dir with their state and exit");
  cmd->add_option("-o,--output", o->replay.mesh, "Write the recovered mesh (.obj, .off, .ply, .stl)");
  cmd->add_option("--png", o->replay.png, "Render the recovered scene to this PNG");
  cmd->add_option("--size", o->replay.size, "PNG size WIDTHxHEIGHT (default 1280x800)");
  cmd->add_option("--report", o->replay.report, "Write a JSON summary here");
  cmd->add_flag("-q,--quiet", o->replay.quiet, "Less output");
  cmd->add_flag("--no-improve", o->replay.no_improve, "Skip refinement and smoothing of the model");
  cmd->callback([o] { run(*o); });
}

}  // namespace

PLANESKETCH_COMMAND(11, setup);
