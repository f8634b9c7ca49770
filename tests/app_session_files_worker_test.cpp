// Session files through the window's path (app/preview_worker.h): a `save` action is carried out
// on the worker with the session as of the action (not a stale preview), loading and importing
// are queued in order with the other events, and a refused file is a message that changes
// nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <unistd.h>

#include "app/preview_worker.h"
#include "input/stroke_log_io.h"
#include "modeling/mesh_io.h"
#include "modeling/session_io.h"

namespace ps::app {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() /
                  ("ps_session_worker_" + std::to_string(::getpid()) + "_" +
                   std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& n) const { return (path / n).string(); }
};

SessionParams params() {
  SessionParams p;
  p.improve = false;
  return p;
}

TEST(SessionFilesWorker, SaveLoadAndImportGoThroughTheQueue) {
  auto log = read_stroke_log(std::string(PLANESKETCH_SOURCE_DIR) + "/assets/logs/demo.jsonl");
  ASSERT_TRUE(log) << log.message();
  TempDir dir;
  PreviewWorker worker(params());
  std::mutex m;
  std::vector<std::string> saved;  // paths the handler saved, with the model size it saw
  std::vector<std::size_t> saved_faces;
  worker.set_save_handler([&](const SketchSession& s, const std::string& path) {
    const Status st = save_session(path, s);
    std::lock_guard lk(m);
    saved.push_back(st ? path : "failed: " + st.message());
    saved_faces.push_back(s.state().model.faces.size());
  });
  StrokeReplayer(*log).replay_all(worker);
  const double t = log->events.back().t + 1.0;
  // Queued right behind the strokes: the save must see the last stroke's model.
  worker.on_action(TimedEvent{t, 0, Save{dir.file("s.json")}});
  worker.on_action(TimedEvent{t + 1, 0, Undo{}});
  worker.wait_idle();
  const auto after_undo = worker.latest();
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_EQ(saved[0], dir.file("s.json"));
  ASSERT_TRUE(after_undo->can_redo);

  SketchSession reference;
  SessionLoadReport r;
  ASSERT_TRUE(load_session(dir.file("s.json"), reference, &r));
  EXPECT_TRUE(r.mesh_matches) << r.mesh_problem;
  EXPECT_EQ(saved_faces[0], reference.state().model.faces.size());
  EXPECT_NE(after_undo->state.model.faces.size(), reference.state().model.faces.size());

  // Loading replaces the session (history cleared) with the saved one, bit for bit.
  worker.load_session(dir.file("s.json"), t + 2);
  worker.wait_idle();
  auto snap = worker.latest();
  EXPECT_EQ(snap->state.model.vertices, reference.state().model.vertices);
  EXPECT_EQ(snap->state.model.faces, reference.state().model.faces);
  EXPECT_FALSE(snap->can_undo);
  EXPECT_FALSE(snap->can_redo);
  const std::size_t messages = snap->messages.size();

  // A bad file, and an import into a session with sections: messages, nothing changed.
  std::ofstream(dir.file("bad.json")) << "{\"format\": \"planesketch-session\", \"version\": 1";
  worker.load_session(dir.file("bad.json"), t + 3);
  worker.import_mesh(dir.file("s.mesh.ply"), t + 4);
  worker.wait_idle();
  snap = worker.latest();
  ASSERT_EQ(snap->messages.size(), messages + 2);
  EXPECT_NE(snap->messages[messages].text.find("session not loaded: " + dir.file("bad.json") + ": not valid JSON"),
            std::string::npos)
      << snap->messages[messages].text;
  EXPECT_NE(snap->messages[messages + 1].text.find("mesh not imported"), std::string::npos)
      << snap->messages[messages + 1].text;
  EXPECT_EQ(snap->state.model.vertices, reference.state().model.vertices);

  // An import into a fresh session: the base is the mesh; a sketch stroke on it is refused.
  PreviewWorker fresh(params());
  fresh.on_header(log->header);
  fresh.import_mesh(dir.file("s.mesh.ply"));
  StrokeReplayer(*log).replay_all(fresh);
  fresh.wait_idle();
  const auto base = fresh.latest();
  EXPECT_EQ(base->state.model.vertices, reference.state().model.vertices);
  EXPECT_FALSE(base->state.base.empty());
  ASSERT_FALSE(base->messages.empty());
  EXPECT_NE(base->messages.back().text.find("imported mesh"), std::string::npos) << base->messages.back().text;
}

}  // namespace
}  // namespace ps::app
