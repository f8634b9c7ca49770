#pragma once
// The sketching session (thesis 3.2.1): the cross sections sketched so far, the model
// reconstructed after every accepted stroke, and undo/redo over both. The reference planes and
// the camera belong to the caller (input/InputState): a stroke arrives with the camera it was
// drawn under and the plane it was drawn on.
//
// Every operation either succeeds or returns a Status with the reason and leaves the session
// exactly as it was (sections, model, undo history).
//
// Geometry as values: the state is a plain value (SessionState); undo/redo keep snapshots of it,
// so an undo restores the identical model, bit for bit. The stored curves are the user's own
// (lifted, preprocessed) curves; curve sewing (rule 4) runs on the whole set at every rebuild,
// so the model is a function of the set of curves, not of the order they were drawn in.
#include <string>
#include <variant>
#include <vector>

#include "modeling/camera.h"
#include "modeling/cross_section.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh.h"
#include "modeling/reconstruct.h"
#include "modeling/status.h"
#include "modeling/stroke_preprocess.h"
#include "modeling/topology_edit.h"

namespace ps {

struct SessionParams {
  StrokeParams stroke;  // preprocessing of cross-section strokes (15 px filter, thesis-facts)
  bool improve = true;  // refinement + smoothing of the preview (4.5.1)
  // Above this many faces in the initial union the preview is shown unimproved (with a hint):
  // the improvement's exact self-intersection checks would stall the interactive loop.
  std::size_t improve_max_faces = 6000;
  double lambda = 0.5;  // deformation balance (thesis 5.4), recorded with each DeformOp
  // An open sketch stroke edits a section (modeling/section_oversketch.h) when both its ends
  // come within this many window pixels of it.
  double oversketch_snap_px = 20.0;
};

// What an accepted sketch stroke did (SketchSession::add_window_stroke).
struct StrokeEdit {
  enum class Kind {
    kNewSection,  // a closed stroke: a new section
    kOversketch,  // an open stroke replaced the part of section `section` it runs along
    kCompletion,  // an open stroke completed from the model's cross section: new section `section`
    kMirrored,    // an open stroke with nothing under its ends, closed by its mirror image in its chord
  };
  Kind kind = Kind::kNewSection;
  int section = -1;                       // index of the new or edited section
  int parts_before = 0, parts_after = 0;  // connected parts of the model before and after
};

// A sculpting operation by stroke (thesis 3.2.2; modeling/sculpt_cut.h, sculpt_smooth.h), kept
// with the camera it was drawn under so it can be applied again.
struct SculptOp {
  enum class Kind { kCut, kTunnel, kSmooth, kExtrude };
  Kind kind = Kind::kCut;
  std::vector<Vec2> stroke;  // window pixels (kExtrude: the closed base stroke on the surface)
  Vec2 side = Vec2::Zero();  // kCut: a window point on the side to remove
  Camera camera;
  // kExtrude: the silhouette stroke on the automatic reference plane, and its camera.
  std::vector<Vec2> silhouette;
  Camera silhouette_camera;
  // kExtrude: the reference plane's rotations (ExtrudeOptions::spin, tilt; radians).
  double spin = 0.0;
  double tilt = 0.0;
};
const char* sculpt_kind_name(SculptOp::Kind kind);

// The operation applied to a model (refusals name the reason; the model is a value).
Result<TriMesh> apply_sculpt(const TriMesh& model, const SculptOp& op);

// Vertices chosen by stroke (thesis 3.2.2 "Deformation tool", 5.4): the region of interest of a
// deformation, or the vertices a stiffness value is painted on. Radii are fractions of the
// model's bounding-box diagonal, so a log means the same at every model scale.
struct VertexSelection {
  enum class Method {
    kRadius,  // vertices within `radius` of a handle vertex (deformation ROI only)
    kLasso,   // vertices whose window projection lies inside the closed `stroke` (any depth)
    kBrush,   // vertices within `radius` of the surface points under `stroke`
  };
  Method method = Method::kRadius;
  double radius = 0.2;       // kRadius, kBrush
  std::vector<Vec2> stroke;  // kLasso, kBrush: window pixels
  Camera camera;             // kLasso, kBrush: the camera `stroke` was drawn under
};
const char* selection_method_name(VertexSelection::Method method);

// A deformation by strokes (thesis 3.2.2, 3.3.3, chapter 5; modeling/deform_tool.h and
// edge_graph_deformer.h): the handle stroke drawn over the model, the target stroke drawn on the
// base plane fitted to the handle (each with its own camera: the view may turn in between), the
// region of interest, and the global balance lambda. Vertices neither in the ROI nor handles are
// static and keep their bits.
struct DeformOp {
  std::vector<Vec2> handle;  // window pixels, over the model
  Camera handle_camera;
  std::vector<Vec2> target;  // window pixels, lifted onto the base plane
  Camera target_camera;
  // Optional: the target's shadow on the projection plane (thesis 3.3.3, P_i = P_i^b + V_i),
  // which makes the target a space curve; empty for a planar target.
  std::vector<Vec2> shadow;
  Camera shadow_camera;
  VertexSelection roi;
  double plane_rotation = 0.0;  // radians: turns the base plane about its axis (reference_planes)
  double lambda = 0.5;          // set by SketchSession::deform from SessionParams::lambda
};

// Stiffness painting (thesis 5.4): `value` in [0, 1] becomes the per-vertex lambda of the
// selected vertices (a lasso or a brush) for the deformations that follow.
struct StiffnessOp {
  VertexSelection region;  // kLasso or kBrush
  double value = 1.0;
};

// What apply_deform did (for the bench and the app).
struct DeformOpReport {
  std::vector<int> handles, roi;   // handle vertices and free vertices
  std::vector<Vec3> targets;       // per handle vertex
  double select_ms = 0.0;          // ray casting, planes, target curve, ROI
  double check_ms = 0.0;           // the self-intersection test of the result
  DeformStats solver;              // set_mesh + set_region + deform
};

// The deformation applied to a model whose painted stiffness is `stiffness` (#V values, NaN
// where none was painted, or empty). Refused, naming the reason: no model, a stroke with fewer
// than 2 points or a non-finite one, a handle stroke that misses the model, a target (shadow)
// stroke seen (nearly) edge-on on the base (projection) plane, an empty ROI, a bad radius or lambda, a solver
// refusal, or a result that intersects itself.
Result<TriMesh> apply_deform(const TriMesh& model, const std::vector<double>& stiffness, const DeformOp& op,
                             DeformOpReport* report = nullptr);
// The stiffness field after painting `op` on `model` (input: #V values or empty = unpainted).
// Refused: a value outside [0, 1], the radius method, a bad stroke or radius, nothing selected.
Result<std::vector<double>> apply_stiffness(const TriMesh& model, const std::vector<double>& stiffness,
                                            const StiffnessOp& op);

// Every operation the session applies after reconstructing its sections, in order.
using SessionOp = std::variant<SculptOp, DeformOp, StiffnessOp>;
// "cut", "tunnel", "smooth", "extrude", "deform" or "stiffness".
const char* session_op_name(const SessionOp& op);

// Whether `mesh` can be the base of a session: faces with indices in range, finite
// coordinates, closed, manifold, oriented outwards, free of self-intersections; else the reason.
Status check_base_mesh(const TriMesh& mesh);

struct SessionState {
  // An imported base mesh (import_base): when non-empty the model is this mesh followed by
  // `ops`, and there are no sections (section edits are refused). Empty: the model is the
  // reconstruction of the sections.
  TriMesh base;
  SectionSet sections;  // the user's curves (before sewing)
  SectionSet sewn;      // the curves the model interpolates (after sewing)
  // Sculpting, deformation and stiffness painting, applied in order to the reconstruction of
  // `sewn`. Editing the sections rebuilds the reconstruction and applies them again; a section
  // edit that makes one of them fail is refused (the sculpted model is never silently lost).
  std::vector<SessionOp> ops;
  // Topology edits (thesis 6.4, modeling/topology_edit.h) of the reconstruction, before `ops`:
  // their strokes in model coordinates. A section edit under which one no longer applies is
  // refused, like an operation.
  std::vector<TopologyEdit> edits;
  TriMesh model;        // reconstruction of `sewn`, then `ops` (empty when there are no sections)
  // Painted stiffness per vertex of `model` (NaN: not painted, the global lambda applies);
  // empty while nothing is painted. A deformation keeps the vertices, so it keeps the field; a
  // sculpting operation that rebuilds the mesh keeps the values of the vertices it keeps
  // exactly (Booleans keep their input vertices), new vertices are unpainted.
  std::vector<double> stiffness;
  std::vector<std::string> hints;  // e.g. "the model has 2 separate parts"
};

class SketchSession {
 public:
  explicit SketchSession(SessionParams params = {});

  const SessionState& state() const { return state_; }
  const SessionParams& params() const { return params_; }

  // A window-space stroke (pixels) drawn under `camera` on `plane`: preprocessed (3.3.1),
  // lifted onto the plane, checked against the stroke rules (3.3.2), sewn (rule 4), then the
  // model is rebuilt. Refused strokes leave everything unchanged.
  // A closed stroke is a new section. An open stroke (thesis 3.2.1, 4.6) whose two ends come
  // within `oversketch_snap_px` of a section on the same plane oversketches it: the part it
  // runs along is replaced, the section keeps its index. Otherwise, when both ends come that
  // close to one curve of the model's cross section by the plane, the stroke is completed by
  // the rest of that curve into a new section. Otherwise, when it lies on one side of its
  // chord, it is closed by its mirror image in the chord (modeling/section_oversketch.h);
  // otherwise it is refused as open. `edit`, when given, says what an accepted stroke did.
  Status add_window_stroke(const std::vector<Vec2>& window_points, const Camera& camera,
                           const Plane& plane, StrokeEdit* edit = nullptr);
  // A closed curve given in 3D on `plane` (points are projected onto it).
  Status add_section(const Plane& plane, const std::vector<Vec3>& points);
  Status delete_section(int index);
  // Applies a sculpting operation to the current model (undoable like every other change).
  Status sculpt(const SculptOp& op);
  // Deforms the current model (op.lambda is replaced by the session's lambda, which is recorded
  // with the operation), or paints stiffness on it. Undoable; refusals change nothing.
  Status deform(DeformOp op);
  Status paint_stiffness(const StiffnessOp& op);
  // Join (a stroke from one part of the model to another) or split (a stroke across a part) of
  // the reconstruction (thesis 6.4): the window stroke drawn under `camera` is cast onto the
  // model (a join keeps the first and last points that hit it, a split every hit) and the edit
  // rebuilds the model. Refused, naming the reason: an imported base mesh, no model, too few
  // points on the model, or an edit that does not apply (topology_edit.h). Undoable.
  Status topology_edit(TopologyEditKind kind, const std::vector<Vec2>& window_points, const Camera& camera);
  // Makes `mesh` the base of an empty session (no sections, no operations, no base yet), to
  // sculpt or deform without sections; undoable. Refused, naming the reason, unless the mesh is
  // closed, manifold, consistently oriented outwards (positive volume) and free of
  // self-intersections (check_guarantees). Afterwards adding or deleting sections is refused.
  Status import_base(TriMesh mesh);
  // Replaces the whole session by `params` and the state given by `saved.base`,
  // `saved.sections`, `saved.edits` and `saved.ops` (the other fields are ignored): the model is rebuilt from
  // them exactly as the session builds it, so the result is the model the saved session had.
  // The undo and redo history is cleared. On a refusal (a section set that does not
  // reconstruct, an operation that no longer applies) the session is left untouched.
  Status load(SessionParams params, const SessionState& saved);
  // The section whose window-space polyline passes nearest to `window_point`, within
  // `radius_px`; -1 if none.
  int pick_section(const Vec2& window_point, const Camera& camera, double radius_px) const;

  // Parameters by name: "lambda" in [0, 1], "improve" (0 or 1), "filter_px" > 0.
  Status set_parameter(const std::string& name, double value);
  Status undo();
  Status redo();
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }

  // Last reconstruction's report (timings, zones, warnings).
  const ReconstructReport& last_report() const { return report_; }

 private:
  // Builds `next.sewn`, `next.model`, `next.stiffness` and `next.hints` from `next.base` or
  // `next.sections`, then `next.ops`, with `params`.
  static Status build(const SessionParams& params, SessionState& next, ReconstructReport& report);
  // Rebuild `next` (sew + reconstruct); on success commit it, pushing the old state on the undo
  // stack; on failure leave everything unchanged.
  Status commit(SessionState next);
  // Pushes the current state on the undo stack and makes `next` current.
  void push(SessionState next);
  // An open lifted stroke: oversketch or completion (add_window_stroke).
  Status edit_by_open_stroke(const std::vector<Vec2>& window_points, const std::vector<Vec3>& points,
                             const Camera& camera, const Plane& plane, StrokeEdit& edit);

  SessionParams params_;
  SessionState state_;
  std::vector<SessionState> undo_;
  std::vector<SessionState> redo_;
  ReconstructReport report_;
};

}  // namespace ps
