#pragma once
// The session journal: the stroke log an app writes as it runs, for crash recovery
// (docs/session.md, "Journal and crash recovery"; format in docs/stroke-log.md).
//
// A journal is *finished* when its last line is the session-end marker {"type":"end"}, which
// StrokeRecorder::finish writes on a clean exit. A journal without it belongs to a session that
// died (crash, SIGKILL, power cut) or is still running; `planesketch recover` replays it.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "input/stroke_recorder.h"
#include "input/stroke_replayer.h"

namespace ps::app {

// $XDG_STATE_HOME/planesketch, else $HOME/.local/state/planesketch (not created here).
std::filesystem::path journal_dir();
// A new journal name in `dir` (created if missing): journal-<unix seconds>-<pid>.jsonl.
std::string new_journal_path(const std::filesystem::path& dir);

struct JournalInfo {
  std::filesystem::path path;
  std::filesystem::file_time_type mtime;
  bool finished = false;  // the last non-blank line is the end marker
  bool in_use = false;    // a live recorder holds its lock (a running session)
};

// The journal-*.jsonl files in `dir`, newest (by modification time, then name) first. Only the
// tail of each file is read to decide `finished`. A missing directory gives an empty list.
std::vector<JournalInfo> list_journals(const std::filesystem::path& dir);
// True when the file's last non-blank line is the end marker (reads at most its last 4 KiB).
bool journal_finished(const std::filesystem::path& path);
// True when another open file description holds the recorder's flock on it (a live session).
bool journal_in_use(const std::filesystem::path& path);
// The newest journal in `dir` that is neither finished nor in use.
std::optional<JournalInfo> newest_unfinished_journal(const std::filesystem::path& dir);

// FNV-1a 64 of the file's bytes as 16 lower-case hex digits (the `digest` of an `open`
// event, docs/stroke-log.md); refused, naming the file, when it cannot be read.
Result<std::string> file_digest(const std::string& path);
// The `open` event for opening `path` as `kind` ("session" or "mesh"): absolute path, digest.
Result<OpenFile> open_file_event(const std::string& kind, const std::string& path);

// An EventSink that journals every event through a StrokeRecorder before passing it on to
// `next`: the headless counterpart of the window's journal (same recorder, so the same fsync
// points: every pen-up and every action). A failed write throws CommandFailed: a journal that
// silently stops would defeat its purpose.
class JournalingSink : public EventSink {
 public:
  JournalingSink(StrokeRecorder& recorder, EventSink& next) : rec_(recorder), next_(next) {}
  void on_header(const LogHeader& header) override { next_.on_header(header); }
  void on_pen_sample(const PenSample& sample) override;
  void on_action(const TimedEvent& event) override;
  void on_stroke(const Stroke& stroke) override { next_.on_stroke(stroke); }
  void on_end() override { next_.on_end(); }

 private:
  StrokeRecorder& rec_;
  EventSink& next_;
};

}  // namespace ps::app
