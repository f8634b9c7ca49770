#pragma once
// The body of `planesketch replay` and `planesketch recover`: replays a stroke log through a
// SessionDriver (the window's event path) and writes the model, a picture and a report.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "input/stroke_log.h"

namespace ps::app {

struct ReplayOptions {
  std::string mesh, png, size = "1280x800", report;
  std::string journal;   // journal the applied events here (StrokeRecorder; refuses an existing file)
  double pace_ms = 0.0;  // wall-clock sleep before each event; never changes the model
  std::string save_session;   // write the session file (modeling/session_io.h) here at the end
  std::string base_mesh;      // start from this mesh as an imported base (no sections)
  std::string start_session;  // start from this session file
  bool quiet = false;
  bool no_improve = false;
};

// Checks the options that do not need the log (size, mesh extension, pace); returns the PNG
// size. Throws CommandFailed.
std::pair<int, int> check_replay_options(const ReplayOptions& o);

// Replays `log` (called `name` in messages) and writes the outputs o asks for. `report_extra`
// fields are merged into the report. Every output is produced in memory before the first one
// is written, so a failure in replay or rendering leaves no output file. Throws CommandFailed.
void run_replay(const StrokeLog& log, const std::string& name, const ReplayOptions& o,
                const nlohmann::json& report_extra = nlohmann::json::object());

}  // namespace ps::app
