#include "app/session_driver.h"

#include <chrono>
#include <cmath>
#include <type_traits>
#include <variant>

#include "app/journal.h"
#include "modeling/mesh_io.h"
#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/session_io.h"
#include "modeling/stroke_classify.h"
#include "modeling/stroke_preprocess.h"

namespace ps::app {

SessionDriver::SessionDriver(SessionParams params) : session_(std::move(params)) {}

void SessionDriver::on_header(const LogHeader& header) {
  input_ = InputState::from_header(header);
  initial_camera_ = header.camera;
}

void SessionDriver::on_pen_sample(const PenSample&) {
  // Whole strokes arrive through on_stroke; single samples only matter to the live preview.
}

void SessionDriver::report(double t, int line, const std::string& text) {
  messages_.push_back(DriverMessage{t, line, text});
}

void SessionDriver::changed() {
  if (on_model_changed) on_model_changed(session_);
}

void SessionDriver::on_action(const TimedEvent& e) {
  std::visit(
      [&](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, Undo>) {
          if (auto st = session_.undo(); !st) report(e.t, e.line, st.message());
          else changed();
        } else if constexpr (std::is_same_v<T, Redo>) {
          if (auto st = session_.redo(); !st) report(e.t, e.line, st.message());
          else changed();
        } else if constexpr (std::is_same_v<T, DeleteSection>) {
          if (auto st = session_.delete_section(a.section); !st) report(e.t, e.line, st.message());
          else changed();
        } else if constexpr (std::is_same_v<T, SetParameter>) {
          // Parameters the session knows; the rest (e.g. view settings) belong to the input state.
          if (a.name == "lambda" || a.name == "filter_px" || a.name == "improve") {
            if (auto st = session_.set_parameter(a.name, a.value); !st) report(e.t, e.line, st.message());
          }
          // The deformation tool's own parameters, checked here so a bad value is reported when
          // it is set (and not kept) rather than at the next stroke.
          if ((a.name == "deform_radius" || a.name == "brush_radius") && !(a.value > 0.0 && std::isfinite(a.value))) {
            report(e.t, e.line, a.name + " must be a positive fraction of the model's size; kept " +
                                    std::to_string(parameter(a.name, a.name == "brush_radius" ? kDefaultBrushRadius : kDefaultRoiRadius)));
            return;
          }
          if (a.name == "stiffness" && !(a.value >= 0.0 && a.value <= 1.0)) {
            report(e.t, e.line, "stiffness must lie in [0, 1]; kept " + std::to_string(parameter("stiffness", 1.0)));
            return;
          }
          // The extrusion's reference plane rotations (radians), read when the silhouette completes it.
          if (a.name == "extrude_spin" || a.name == "extrude_tilt") {
            const bool spin = a.name == "extrude_spin";
            if (auto st = check_plane_rotation(spin ? a.value : 0.0, spin ? 0.0 : a.value); !st) {
              report(e.t, e.line, st.message() + "; kept " + std::to_string(parameter(a.name, 0.0)));
              return;
            }
          }
          if (auto st = input_.apply(e.event); !st) report(e.t, e.line, st.message());
        } else if constexpr (std::is_same_v<T, Save>) {
          if (on_save) on_save(a.path);
        } else if constexpr (std::is_same_v<T, OpenFile>) {
          (void)open_file(e.t, e.line, a);
        } else if constexpr (std::is_same_v<T, PenSample>) {
          on_pen_sample(a);
        } else if constexpr (std::is_same_v<T, SetToolMode>) {
          // A two-stroke operation (cut, extrusion, deformation) left half-way is dropped with the
          // old mode; a region of interest drawn in "roi" mode waits for "deform".
          pending_cut_.clear();
          pending_base_.clear();
          pending_handle_.clear();
          pending_target_.clear();
          if (a.mode != "deform" && a.mode != "roi") pending_roi_.reset();
          if (auto st = input_.apply(e.event); !st) report(e.t, e.line, st.message());
        } else {
          if (auto st = input_.apply(e.event); !st) report(e.t, e.line, st.message());
        }
      },
      e.event);
}

void SessionDriver::drop_pending() {
  pending_cut_.clear();
  pending_base_.clear();
  pending_handle_.clear();
  pending_target_.clear();
  pending_roi_.reset();
}

Status SessionDriver::load_session(double t, const std::string& path) {
  SessionLoadReport r;
  if (auto st = ps::load_session(path, session_, &r); !st) {
    report(t, 0, "session not loaded: " + st.message());
    return st;
  }
  drop_pending();
  if (!r.mesh_problem.empty()) report(t, 0, "warning: " + path + ": " + r.mesh_problem);
  changed();
  return Status::ok();
}

Status SessionDriver::import_mesh(double t, const std::string& path) {
  auto mesh = read_mesh(path);
  Status st = mesh ? session_.import_base(std::move(*mesh)) : mesh.status();
  if (!st) {
    st = Status::error("mesh not imported: " + (mesh ? path + ": " : std::string()) + st.message());
    report(t, 0, st.message());
    return st;
  }
  drop_pending();
  changed();
  return Status::ok();
}

Status SessionDriver::open_file(double t, int line, const OpenFile& file) {
  const std::string refused = file.kind == "mesh" ? "mesh not imported: " : "session not loaded: ";
  auto digest = file_digest(file.path);
  Status st = digest ? Status::ok() : digest.status();
  if (digest && *digest != file.digest)
    st = Status::error(file.path + ": the file changed since the session opened it (digest " + file.digest + " then, " +
                       *digest + " now): it would not give the same model");
  if (!st) {
    report(t, line, refused + st.message());
    return Status::error(refused + st.message());
  }
  return file.kind == "mesh" ? import_mesh(t, file.path) : load_session(t, file.path);
}

void SessionDriver::on_stroke(const Stroke& stroke) {
  if (stroke.samples.empty()) return;
  const double t = stroke.samples.front().t;
  std::vector<Vec2> pts;
  pts.reserve(stroke.samples.size());
  for (const auto& s : stroke.samples) pts.emplace_back(s.x, s.y);

  if (stroke.tool == Tool::kEraser) {
    // The eraser end deletes the section it touches.
    int hit = -1;
    for (const auto& p : pts) {
      hit = session_.pick_section(p, input_.camera, 12.0);
      if (hit >= 0) break;
    }
    if (hit < 0) {
      report(t, 0, "eraser touched no section");
      return;
    }
    if (auto st = session_.delete_section(hit); !st) report(t, 0, st.message());
    else changed();
    return;
  }
  if (input_.mode == "cut" || input_.mode == "tunnel" || input_.mode == "smooth" || input_.mode == "extrude" ||
      input_.mode == "sculpt") {
    sculpt_stroke(t, pts);
    return;
  }
  if (input_.mode == "deform") {
    deform_stroke(t, pts);
    return;
  }
  if (input_.mode == "roi") {
    pending_roi_ = selection_from(pts);
    return;
  }
  if (input_.mode == "stiffness") {
    stiffness_stroke(t, pts);
    return;
  }
  if (input_.mode == "join" || input_.mode == "split") {
    // Topology editing (thesis 6.4): a stroke from one part to another, or across a part.
    const auto kind = input_.mode == "join" ? TopologyEditKind::kJoin : TopologyEditKind::kSplit;
    if (auto st = session_.topology_edit(kind, pts, input_.camera); !st)
      report(t, 0, st.message());
    else
      changed();
    return;
  }
  pending_cut_.clear();
  pending_base_.clear();
  pending_handle_.clear();
  pending_target_.clear();
  if (input_.mode != "sketch") {
    report(t, 0, "stroke in '" + input_.mode +
                     "' mode ignored: modes are sketch, sculpt, cut, tunnel, smooth, extrude, deform, roi, stiffness, join and split");
    return;
  }
  const auto plane = input_.current_plane();
  if (!plane) {
    report(t, 0, "stroke refused: no reference plane is selected");
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  StrokeEdit edit;
  if (auto st = session_.add_window_stroke(pts, input_.camera, *plane, &edit); !st) {
    report(t, 0, "stroke refused: " + st.message());
    return;
  }
  latencies_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  const std::string section = "section " + std::to_string(edit.section);
  if (edit.kind == StrokeEdit::Kind::kOversketch)
    notices_.push_back(DriverMessage{t, 0, "the stroke oversketched " + section + " (the part it runs along was replaced)"});
  if (edit.kind == StrokeEdit::Kind::kCompletion)
    notices_.push_back(DriverMessage{t, 0, "the stroke was completed from the model's cross section into " + section});
  if (edit.kind == StrokeEdit::Kind::kMirrored)
    notices_.push_back(DriverMessage{t, 0, "the open stroke was closed by its mirror image about the line between its ends: " + section});
  if (edit.parts_after > edit.parts_before && edit.parts_before > 0)
    notices_.push_back(DriverMessage{t, 0, section + " makes a separate part: the model now has " +
                                               std::to_string(edit.parts_after) +
                                               " parts (a section through the marked crossing points joins them)"});
  changed();
}

// === Sculpting strokes (thesis 3.2.2). Explicit modes name the operation; in "sculpt" mode the
// stroke is recognised (modeling/stroke_classify.h): closed -> extrusion, scratch-out ->
// smoothing, open across the silhouette -> cut. A cut takes two strokes: the cutting stroke, then
// a stroke whose first point marks the side to remove. An extrusion takes two: the closed base
// stroke on the surface, then the silhouette on the automatic reference plane (possibly after
// the view was turned: each stroke keeps the camera it was drawn under). Tunnels have their own
// mode.
void SessionDriver::sculpt_stroke(double t, const std::vector<Vec2>& pts) {
  if (!pending_handle_.empty()) {
    deform_stroke(t, pts);  // a recognised deformation stroke's target
    return;
  }
  SculptOp op;
  op.camera = input_.camera;
  if (!pending_base_.empty()) {
    op.kind = SculptOp::Kind::kExtrude;
    op.stroke = std::move(pending_base_);
    op.camera = pending_base_camera_;
    pending_base_.clear();
    op.silhouette = pts;
    op.silhouette_camera = input_.camera;
    op.spin = parameter("extrude_spin", 0.0);
    op.tilt = parameter("extrude_tilt", 0.0);
  } else if (input_.mode == "extrude") {
    start_extrusion(t, pts);
    return;
  } else if (!pending_cut_.empty()) {
    op.kind = SculptOp::Kind::kCut;
    op.stroke = std::move(pending_cut_);
    pending_cut_.clear();
    op.side = pts.front();
  } else if (input_.mode == "cut") {
    pending_cut_ = pts;
    return;
  } else if (input_.mode == "tunnel" || input_.mode == "smooth") {
    op.kind = input_.mode == "tunnel" ? SculptOp::Kind::kTunnel : SculptOp::Kind::kSmooth;
    op.stroke = pts;
  } else {
    const SilhouetteTest silhouette(session_.state().model, input_.camera);
    auto c = classify_stroke(pts, [&](const Vec2& p) { return silhouette.covers(p); });
    if (!c) {
      report(t, 0, "stroke refused: " + c.message());
      return;
    }
    switch (c->cls) {
      case StrokeClass::kClosed:
        start_extrusion(t, pts);
        return;
      case StrokeClass::kScratchOut: op.kind = SculptOp::Kind::kSmooth; break;
      case StrokeClass::kOpenCutting:
        pending_cut_ = pts;
        return;
      case StrokeClass::kOpenDeformation:  // the handle; the next stroke is its target
        deform_stroke(t, pts);
        return;
      case StrokeClass::kOpenMiss:
        report(t, 0, "the stroke misses the model; model unchanged");
        return;
    }
    op.stroke = pts;
  }
  if (auto st = session_.sculpt(op); !st) {
    report(t, 0, "stroke refused: " + st.message());
    return;
  }
  changed();
}

// An extrusion's base stroke is checked at once (closed, on the model: the reference plane can
// be built), so a stroke that misses the model is refused when it is drawn, not after the
// silhouette; it then waits for the silhouette.
void SessionDriver::start_extrusion(double t, const std::vector<Vec2>& pts) {
  if (auto plane = pending_plane_for(pts, input_.camera); !plane) {
    report(t, 0, "stroke refused: extrude: " + plane.message());
    return;
  }
  pending_base_ = pts;
  pending_base_camera_ = input_.camera;
}

Result<ExtrudePlane> SessionDriver::pending_plane_for(const std::vector<Vec2>& base, const Camera& camera) const {
  ExtrudeOptions o;
  o.spin = parameter("extrude_spin", 0.0);
  o.tilt = parameter("extrude_tilt", 0.0);
  return extrusion_reference_plane(session_.state().model, base, camera, o);
}

std::optional<ExtrudePlane> SessionDriver::pending_extrusion_plane() const {
  if (pending_base_.empty()) return std::nullopt;
  auto plane = pending_plane_for(pending_base_, pending_base_camera_);
  if (!plane) return std::nullopt;
  return std::move(*plane);
}

// === Deformation (thesis 3.2.2, 3.3.3, chapter 5). Two strokes: the handle over the model, then
// the target on the base plane fitted to the handle (the view may turn in between: each keeps
// its camera). The region of interest is the selection last drawn in "roi" mode (a closed
// stroke is a lasso, an open one a brush of `brush_radius`), else every vertex within
// `deform_radius` of the handle. Radii are fractions of the model's bounding-box diagonal;
// `deform_rotation` (radians) turns the base plane about its axis; lambda is the session's. With
// `deform_shadow` = 1 a third stroke follows the target: its shadow on the projection plane.
void SessionDriver::deform_stroke(double t, const std::vector<Vec2>& pts) {
  if (pending_handle_.empty()) {
    pending_handle_ = pts;
    pending_handle_camera_ = input_.camera;
    return;
  }
  const bool with_shadow = parameter("deform_shadow", 0.0) != 0.0;
  if (with_shadow && pending_target_.empty()) {
    pending_target_ = pts;
    pending_target_camera_ = input_.camera;
    return;
  }
  DeformOp op;
  op.handle = std::move(pending_handle_);
  op.handle_camera = pending_handle_camera_;
  pending_handle_.clear();
  if (with_shadow) {
    op.target = std::move(pending_target_);
    op.target_camera = pending_target_camera_;
    pending_target_.clear();
    op.shadow = pts;
    op.shadow_camera = input_.camera;
  } else {
    op.target = pts;
    op.target_camera = input_.camera;
  }
  if (pending_roi_) {
    op.roi = *pending_roi_;
  } else {
    op.roi.method = VertexSelection::Method::kRadius;
    op.roi.radius = parameter("deform_radius", kDefaultRoiRadius);
  }
  op.plane_rotation = parameter("deform_rotation", 0.0);
  if (auto st = session_.deform(op); !st) {
    report(t, 0, "stroke refused: " + st.message());
    return;
  }
  pending_roi_.reset();
  changed();
}

// === Stiffness painting (thesis 5.4): a closed stroke paints the lasso's vertices, an open one
// brushes; the value is the `stiffness` parameter (default 1, rigid).
void SessionDriver::stiffness_stroke(double t, const std::vector<Vec2>& pts) {
  StiffnessOp op;
  op.region = selection_from(pts);
  op.value = parameter("stiffness", 1.0);
  if (auto st = session_.paint_stiffness(op); !st) {
    report(t, 0, "stroke refused: " + st.message());
    return;
  }
  changed();
}

VertexSelection SessionDriver::selection_from(const std::vector<Vec2>& pts) const {
  VertexSelection sel;
  const auto filtered = filter_close_points(pts, session_.params().stroke.min_spacing_px);
  sel.method = filtered.size() >= 3 && is_closed_stroke(filtered, session_.params().stroke) ? VertexSelection::Method::kLasso
                                                                                          : VertexSelection::Method::kBrush;
  sel.radius = parameter("brush_radius", kDefaultBrushRadius);
  sel.stroke = pts;
  sel.camera = input_.camera;
  return sel;
}

double SessionDriver::parameter(const std::string& name, double fallback) const {
  const auto it = input_.parameters.find(name);
  return it == input_.parameters.end() ? fallback : it->second;
}

}  // namespace ps::app
