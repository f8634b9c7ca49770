#pragma once
// Drives a SketchSession from input events: the one code path shared by the live window and
// headless replay (the replayer and the window both call this EventSink).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "input/input_state.h"
#include "input/stroke_replayer.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/sketch_session.h"

namespace ps::app {

// Defaults of the deformation tool's parameters (`parameter` events): the region's radius around
// the handle and the brush radius, fractions of the model's bounding-box diagonal.
inline constexpr double kDefaultRoiRadius = 0.2;
inline constexpr double kDefaultBrushRadius = 0.05;

struct DriverMessage {
  double t = 0.0;  // ms, log time
  int line = 0;    // source line in the log (0 when unknown)
  std::string text;
};

class SessionDriver : public EventSink {
 public:
  explicit SessionDriver(SessionParams params = {});

  void on_header(const LogHeader& header) override;
  void on_pen_sample(const PenSample& sample) override;
  void on_action(const TimedEvent& event) override;
  void on_stroke(const Stroke& stroke) override;

  const SketchSession& session() const { return session_; }
  SketchSession& session() { return session_; }
  const InputState& input() const { return input_; }
  // The camera of the log's header (the view the session started from).
  const Camera& initial_camera() const { return initial_camera_; }
  // Refused strokes and actions, in order (the model was left unchanged for each).
  const std::vector<DriverMessage>& messages() const { return messages_; }
  // Accepted sketch strokes that deserve a word, in order: an open stroke that oversketched a
  // section, was completed from the model's cross section or was mirrored about its chord,
  // and a section that made a new separate part of the model (thesis 4.4: "a hint will be
  // given to the user").
  const std::vector<DriverMessage>& notices() const { return notices_; }
  // Wall time from pen-up to the rebuilt model, per accepted sketch stroke (ms).
  const std::vector<double>& stroke_latencies_ms() const { return latencies_; }
  // The automatic reference plane of an extrusion whose base stroke waits for its silhouette,
  // turned by the current extrude_spin / extrude_tilt parameters (what the window shows); none
  // when no extrusion is half-drawn.
  std::optional<ExtrudePlane> pending_extrusion_plane() const;
  // Called after every change of the model (accepted stroke, delete, undo, redo).
  std::function<void(const SketchSession&)> on_model_changed;
  // Called for a save action with its path (the live app saves; replay leaves it unset).
  std::function<void(const std::string& path)> on_save;

  // Session files (modeling/session_io.h). Loading replaces the session (history cleared) and
  // drops half-drawn two-stroke operations; importing makes a mesh file the base of the (empty)
  // session. A refusal is reported as a message at log time `t` and changes nothing; a loaded
  // session whose rebuilt model differs from its saved mesh is loaded and the difference
  // reported as a message too.
  Status load_session(double t, const std::string& path);
  Status import_mesh(double t, const std::string& path);
  // A journaled `open` event (also what on_action does with one): the file is loaded or
  // imported as above only when its content still has the event's digest; otherwise it is
  // refused with a message (the journal would rebuild a different model from it).
  Status open_file(double t, int line, const OpenFile& file);

 private:
  void report(double t, int line, const std::string& text);
  void sculpt_stroke(double t, const std::vector<Vec2>& pts);
  void start_extrusion(double t, const std::vector<Vec2>& pts);
  Result<ExtrudePlane> pending_plane_for(const std::vector<Vec2>& base, const Camera& camera) const;
  void deform_stroke(double t, const std::vector<Vec2>& pts);
  void stiffness_stroke(double t, const std::vector<Vec2>& pts);
  // A lasso (closed stroke) or brush (open stroke) selection from a stroke under the current camera.
  VertexSelection selection_from(const std::vector<Vec2>& pts) const;
  double parameter(const std::string& name, double fallback) const;
  void changed();
  void drop_pending();

  SketchSession session_;
  InputState input_;
  Camera initial_camera_;
  std::vector<DriverMessage> messages_;
  std::vector<DriverMessage> notices_;
  std::vector<double> latencies_;
  std::vector<Vec2> pending_cut_;  // a cutting stroke waiting for the stroke that marks the side
  std::vector<Vec2> pending_base_;  // an extrusion's base stroke waiting for its silhouette
  Camera pending_base_camera_;
  std::vector<Vec2> pending_handle_;  // a deformation's handle stroke waiting for its target
  Camera pending_handle_camera_;
  std::vector<Vec2> pending_target_;  // its target, waiting for the shadow (deform_shadow = 1)
  Camera pending_target_camera_;
  // The region of interest drawn in "roi" mode for the next deformation (none: a radius).
  std::optional<VertexSelection> pending_roi_;
};

}  // namespace ps::app
