#include "modeling/sketch_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "modeling/curve_sewing.h"
#include "modeling/deform_tool.h"
#include "modeling/face_intersections.h"
#include "modeling/mesh_improve.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/progressive_reconstructor.h"
#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/sculpt_smooth.h"
#include "modeling/section_oversketch.h"
#include "modeling/section_validate.h"
#include "modeling/sketch_guides.h"

namespace ps {
namespace {

// Index of `plane` in `set.planes`, adding it when no plane there coincides with it
// (same unit normal up to sign and same offset, within 1e-12 relative).
int find_or_add_plane(SectionSet& set, const Plane& plane) {
  if (const int i = find_plane(set, plane); i >= 0) return i;
  const double n = plane.normal.norm();
  set.planes.push_back(Plane{plane.normal / n, plane.offset / n});
  return static_cast<int>(set.planes.size() - 1);
}

// Connected parts (face components) of a model; 0 for none.
int model_parts(const TriMesh& model) {
  std::vector<int> component;
  return model.faces.empty() ? 0 : face_components(model, component);
}

// Drop planes no curve uses, re-indexing the curves.
void compact_planes(SectionSet& set) {
  std::vector<int> remap(set.planes.size(), -1);
  std::vector<Plane> kept;
  for (auto& c : set.curves) {
    auto& r = remap[static_cast<std::size_t>(c.plane)];
    if (r < 0) {
      r = static_cast<int>(kept.size());
      kept.push_back(set.planes[static_cast<std::size_t>(c.plane)]);
    }
    c.plane = r;
  }
  set.planes = std::move(kept);
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool finite_camera(const Camera& c) {
  return c.eye.allFinite() && c.target.allFinite() && c.up.allFinite() && std::isfinite(c.fov_y_deg) &&
         std::isfinite(c.ortho_height) && c.width > 0 && c.height > 0 && (c.target - c.eye).norm() > 0.0;
}

// The stroke with a point at least every `step_px` pixels (the ray casts of a brush must not
// leave gaps between sparse pen samples).
std::vector<Vec2> densify(const std::vector<Vec2>& stroke, double step_px) {
  std::vector<Vec2> out;
  if (stroke.empty()) return out;
  out.push_back(stroke.front());
  for (std::size_t i = 1; i < stroke.size(); ++i) {
    const Vec2 a = stroke[i - 1], b = stroke[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_px)));
    for (int k = 1; k <= n; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / n));
  }
  return out;
}

// The vertices `sel` picks on `model` (kRadius around `handles`), excluding `handles`; sorted.
// `what` names the selection in messages ("the region of interest", "the stiffness region").
Result<std::vector<int>> select_vertices(const TriMesh& model, const VertexSelection& sel,
                                         const std::vector<int>& handles, const MeshRayCaster& caster,
                                         const std::string& what) {
  using R = Result<std::vector<int>>;
  const double diagonal = bounding_box(model.vertices).diagonal();
  if (sel.method != VertexSelection::Method::kLasso && !(sel.radius > 0.0 && std::isfinite(sel.radius)))
    return R::error(what + ": the " + selection_method_name(sel.method) +
                    " radius must be a positive fraction of the model's size (got " + std::to_string(sel.radius) + ")");
  std::vector<int> picked;
  switch (sel.method) {
    case VertexSelection::Method::kRadius:
      picked = roi_by_radius(model, handles, sel.radius * diagonal);
      break;
    case VertexSelection::Method::kLasso: {
      if (auto st = check_window_points(sel.stroke, 3, "the lasso stroke"); !st) return R::error(what + ": " + st.message());
      if (!finite_camera(sel.camera)) return R::error(what + ": the lasso's camera is not finite");
      picked = roi_by_lasso(model, sel.camera, sel.stroke, handles);
      break;
    }
    case VertexSelection::Method::kBrush: {
      if (auto st = check_window_points(sel.stroke, 1, "the brush stroke"); !st) return R::error(what + ": " + st.message());
      if (!finite_camera(sel.camera)) return R::error(what + ": the brush's camera is not finite");
      const std::vector<Vec3> under = project_stroke(caster, sel.camera, densify(sel.stroke, 2.0));
      if (under.empty()) return R::error(what + ": the brush stroke misses the model");
      picked = roi_by_brush(model, under, sel.radius * diagonal, handles);
      break;
    }
  }
  if (picked.empty())
    return R::error(what + " is empty: the " + selection_method_name(sel.method) + " selects no vertex" +
                    (handles.empty() ? "" : " besides the handle vertices"));
  return picked;
}

// Stiffness of `before` carried to `after`, the result of an operation on it: by index when the
// operation kept the connectivity, else by exact vertex position (unmatched vertices: NaN).
std::vector<double> carry_stiffness(const TriMesh& before, const std::vector<double>& stiffness, const TriMesh& after) {
  if (stiffness.empty()) return {};
  if (after.vertices.size() == before.vertices.size() && after.faces == before.faces) return stiffness;
  std::vector<int> order(before.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return less(before.vertices[static_cast<std::size_t>(a)], before.vertices[static_cast<std::size_t>(b)]);
  });
  std::vector<double> out(after.vertices.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t v = 0; v < after.vertices.size(); ++v) {
    const Vec3& p = after.vertices[v];
    const auto it = std::lower_bound(order.begin(), order.end(), p, [&](int a, const Vec3& q) {
      return less(before.vertices[static_cast<std::size_t>(a)], q);
    });
    if (it != order.end() && before.vertices[static_cast<std::size_t>(*it)] == p)
      out[v] = stiffness[static_cast<std::size_t>(*it)];
  }
  return out;
}

// Every ray through `stroke` meets `plane` at 5 degrees or more (see apply_deform).
Status check_facing(const std::vector<Vec2>& stroke, const Camera& camera, const Plane& plane, const char* what,
                    const char* plane_name) {
  const double min_sine = std::sin(5.0 * M_PI / 180.0);
  for (const Vec2& p : stroke) {
    const Ray ray = camera.ray(p.x(), p.y());
    if (std::abs(ray.direction.dot(plane.normal)) < min_sine)
      return Status::error(std::string(what) + ": the " + plane_name + " is seen edge-on at " + format_window_point(p) +
                           " (turn the view towards it, or turn the plane)");
  }
  return Status::ok();
}

// One operation of the session's list applied to (model, stiffness); both unchanged on refusal.
Status apply_op(TriMesh& model, std::vector<double>& stiffness, const SessionOp& op) {
  if (const auto* s = std::get_if<SculptOp>(&op)) {
    auto out = apply_sculpt(model, *s);
    if (!out) return out.status();
    stiffness = carry_stiffness(model, stiffness, *out);
    model = std::move(*out);
  } else if (const auto* d = std::get_if<DeformOp>(&op)) {
    auto out = apply_deform(model, stiffness, *d);
    if (!out) return out.status();
    model = std::move(*out);
  } else {
    auto out = apply_stiffness(model, stiffness, std::get<StiffnessOp>(op));
    if (!out) return out.status();
    stiffness = std::move(*out);
  }
  return Status::ok();
}

}  // namespace

const char* selection_method_name(VertexSelection::Method method) {
  switch (method) {
    case VertexSelection::Method::kRadius: return "radius";
    case VertexSelection::Method::kLasso: return "lasso";
    case VertexSelection::Method::kBrush: return "brush";
  }
  return "?";
}

const char* session_op_name(const SessionOp& op) {
  if (const auto* s = std::get_if<SculptOp>(&op)) return sculpt_kind_name(s->kind);
  return std::holds_alternative<DeformOp>(op) ? "deform" : "stiffness";
}

Result<TriMesh> apply_deform(const TriMesh& model, const std::vector<double>& stiffness, const DeformOp& op,
                             DeformOpReport* report) {
  using R = Result<TriMesh>;
  const auto t0 = std::chrono::steady_clock::now();
  if (model.faces.empty()) return R::error("there is no model to deform: sketch cross sections first");
  if (auto st = check_window_points(op.handle, 2, "the handle stroke"); !st) return st;
  if (auto st = check_window_points(op.target, 2, "the target stroke"); !st) return st;
  if (!finite_camera(op.handle_camera)) return R::error("the handle stroke's camera is not finite");
  if (!finite_camera(op.target_camera)) return R::error("the target stroke's camera is not finite");
  if (!(op.lambda >= 0.0 && op.lambda <= 1.0)) return R::error("lambda must lie in [0, 1]");
  if (!std::isfinite(op.plane_rotation)) return R::error("the base plane's rotation is not finite");
  if (!stiffness.empty() && stiffness.size() != model.vertices.size())
    return R::error("the stiffness field has " + std::to_string(stiffness.size()) + " values for " +
                    std::to_string(model.vertices.size()) + " vertices");
  // === Handle curve, reference planes, target curve (3.3.3)
  const MeshRayCaster caster(model);
  auto handle = project_handle_stroke(model, caster, op.handle_camera, op.handle);
  if (!handle) return handle.status();
  auto planes = reference_planes(handle->points, op.plane_rotation);
  if (!planes) return R::error("handle stroke: " + planes.message());
  // A ray grazing the base plane lifts a pixel's jitter to a long way off: the target must be
  // drawn with the plane in view (at least 5 degrees between the rays and the plane); the same
  // for the shadow and the projection plane.
  if (auto st = check_facing(op.target, op.target_camera, planes->base, "target stroke", "base plane"); !st) return st;
  std::vector<Vec2> shadow_px;
  if (!op.shadow.empty()) {
    if (auto st = check_window_points(op.shadow, 2, "the shadow stroke"); !st) return st;
    if (!finite_camera(op.shadow_camera)) return R::error("the shadow stroke's camera is not finite");
    if (auto st = check_facing(op.shadow, op.shadow_camera, planes->projection, "shadow stroke", "projection plane"); !st)
      return st;
    shadow_px = smooth_polyline(filter_close_points(op.shadow, 4.0), false);
    if (shadow_px.size() < 2) return R::error("shadow stroke: it is shorter than 4 pixels");
  }
  // Pen jitter would become bumps of the target curve: drop samples closer than 4 px, then one
  // pass of Eq. 3.1 smoothing (ends kept).
  const std::vector<Vec2> target_px = smooth_polyline(filter_close_points(op.target, 4.0), false);
  if (target_px.size() < 2) return R::error("target stroke: it is shorter than 4 pixels");
  auto target = target_curve(op.target_camera, target_px, op.shadow_camera, shadow_px, *planes);
  if (!target) return target.status();
  const std::vector<Vec3> targets = map_handles_to_target(model, *handle, *target);
  // === Region of interest (3.2.2): every other vertex is static
  auto roi = select_vertices(model, op.roi, handle->vertices, caster, "the region of interest");
  if (!roi) return roi.status();
  const double select_ms = ms_since(t0);
  // === Solve (chapter 5): global lambda, painted stiffness where painted
  DeformParameters params;
  params.lambda = op.lambda;
  params.vertex_lambda = stiffness;
  EdgeGraphDeformer deformer;
  if (auto st = deformer.set_mesh(model); !st) return R::error("deformation: " + st.message());
  if (auto st = deformer.set_region(*roi, handle->vertices, params); !st) return R::error("deformation: " + st.message());
  if (auto st = deformer.deform(targets); !st) return R::error("deformation: " + st.message());
  TriMesh out = deformer.result();
  // === The result must stay free of self-intersections; only faces at moved vertices can
  // have made a new one.
  const auto t1 = std::chrono::steady_clock::now();
  std::vector<char> moved(model.vertices.size(), 0);
  for (int v : *roi) moved[static_cast<std::size_t>(v)] = 1;
  for (int v : handle->vertices) moved[static_cast<std::size_t>(v)] = 1;
  std::vector<int> query;
  for (std::size_t f = 0; f < out.faces.size(); ++f)
    if (moved[static_cast<std::size_t>(out.faces[f][0])] || moved[static_cast<std::size_t>(out.faces[f][1])] ||
        moved[static_cast<std::size_t>(out.faces[f][2])])
      query.push_back(static_cast<int>(f));
  for (const Vec3& p : out.vertices)
    if (!p.allFinite()) return R::error("deformation: the solver produced a non-finite vertex");
  const auto pairs = intersecting_face_pairs(out.vertices, out.faces, query);
  if (!pairs.empty())
    return R::error("the deformed surface would intersect itself (faces " + std::to_string(pairs.front()[0]) + " and " +
                    std::to_string(pairs.front()[1]) + "): move the target less far or widen the region");
  if (report) {
    report->handles = handle->vertices;
    report->roi = std::move(*roi);
    report->targets = targets;
    report->select_ms = select_ms;
    report->check_ms = ms_since(t1);
    report->solver = deformer.stats();
  }
  return out;
}

Result<std::vector<double>> apply_stiffness(const TriMesh& model, const std::vector<double>& stiffness,
                                            const StiffnessOp& op) {
  using R = Result<std::vector<double>>;
  if (model.faces.empty()) return R::error("there is no model to paint: sketch cross sections first");
  if (!(op.value >= 0.0 && op.value <= 1.0))
    return R::error("the stiffness value must lie in [0, 1] (got " + std::to_string(op.value) + ")");
  if (op.region.method == VertexSelection::Method::kRadius)
    return R::error("stiffness is painted with a lasso or a brush, not a radius");
  if (!stiffness.empty() && stiffness.size() != model.vertices.size())
    return R::error("the stiffness field has " + std::to_string(stiffness.size()) + " values for " +
                    std::to_string(model.vertices.size()) + " vertices");
  const MeshRayCaster caster(model);
  auto picked = select_vertices(model, op.region, {}, caster, "the stiffness region");
  if (!picked) return picked.status();
  std::vector<double> out = stiffness;
  if (out.empty()) out.assign(model.vertices.size(), std::numeric_limits<double>::quiet_NaN());
  for (int v : *picked) out[static_cast<std::size_t>(v)] = op.value;
  return out;
}

const char* sculpt_kind_name(SculptOp::Kind kind) {
  switch (kind) {
    case SculptOp::Kind::kCut: return "cut";
    case SculptOp::Kind::kTunnel: return "tunnel";
    case SculptOp::Kind::kSmooth: return "smooth";
    case SculptOp::Kind::kExtrude: return "extrude";
  }
  return "?";
}

Result<TriMesh> apply_sculpt(const TriMesh& model, const SculptOp& op) {
  if (model.faces.empty()) return Result<TriMesh>::error("there is no model to sculpt: sketch cross sections first");
  switch (op.kind) {
    case SculptOp::Kind::kCut: return cut_by_stroke(model, op.stroke, op.side, op.camera);
    case SculptOp::Kind::kTunnel: return tunnel_by_stroke(model, op.stroke, op.camera);
    case SculptOp::Kind::kSmooth: return smooth_by_scratch(model, op.stroke, op.camera);
    case SculptOp::Kind::kExtrude: {
      ExtrudeOptions eo;
      eo.silhouette_camera = op.silhouette_camera;
      eo.spin = op.spin;
      eo.tilt = op.tilt;
      return extrude_by_strokes(model, op.stroke, op.silhouette, op.camera, eo);
    }
  }
  return Result<TriMesh>::error("unknown sculpting operation");
}

SketchSession::SketchSession(SessionParams params) : params_(std::move(params)) {}

Status SketchSession::sculpt(const SculptOp& op) {
  auto out = apply_sculpt(state_.model, op);
  if (!out) return Status::error(std::string(sculpt_kind_name(op.kind)) + ": " + out.message());
  SessionState next = state_;
  next.ops.push_back(op);
  next.stiffness = carry_stiffness(state_.model, state_.stiffness, *out);
  next.model = std::move(*out);
  push(std::move(next));
  return Status::ok();
}

Status SketchSession::topology_edit(TopologyEditKind kind, const std::vector<Vec2>& window_points,
                                   const Camera& camera) {
  const std::string name = topology_edit_name(kind);
  if (!state_.base.empty()) return Status::error(name + ": an imported mesh has no reconstruction to edit");
  if (state_.model.empty()) return Status::error(name + ": there is no model yet");
  for (const auto& p : window_points)
    if (!p.allFinite()) return Status::error(name + ": the stroke has a NaN or infinite point");
  const MeshRayCaster caster(state_.model);
  std::vector<Vec3> hits;
  for (const auto& p : window_points)
    if (auto h = caster.first_hit(camera.ray(p.x(), p.y()))) hits.push_back(h->point);
  if (hits.size() < 2)
    return Status::error(name + (kind == TopologyEditKind::kJoin ? ": the stroke must start and end on the model"
                                                                  : ": the stroke must cross the model"));
  TopologyEdit e{kind, kind == TopologyEditKind::kJoin ? std::vector<Vec3>{hits.front(), hits.back()} : hits};
  SessionState next = state_;
  next.edits.push_back(std::move(e));
  return commit(std::move(next));
}

Status SketchSession::deform(DeformOp op) {
  op.lambda = params_.lambda;
  auto out = apply_deform(state_.model, state_.stiffness, op);
  if (!out) return Status::error("deform: " + out.message());
  SessionState next = state_;
  next.ops.push_back(std::move(op));
  next.model = std::move(*out);
  push(std::move(next));
  return Status::ok();
}

Status SketchSession::paint_stiffness(const StiffnessOp& op) {
  auto out = apply_stiffness(state_.model, state_.stiffness, op);
  if (!out) return Status::error("stiffness: " + out.message());
  SessionState next = state_;
  next.ops.push_back(op);
  next.stiffness = std::move(*out);
  push(std::move(next));
  return Status::ok();
}

namespace {
const char* const kImportedNoSections =
    "the model is an imported mesh: it has no cross sections to add or delete (sculpt or deform it, or sketch in a new session)";
}  // namespace

void SketchSession::push(SessionState next) {
  undo_.push_back(std::move(state_));
  redo_.clear();
  state_ = std::move(next);
}

Status SketchSession::add_window_stroke(const std::vector<Vec2>& window_points,
                                        const Camera& camera, const Plane& plane, StrokeEdit* edit) {
  if (!state_.base.empty()) return Status::error(kImportedNoSections);
  auto lifted = prepare_plane_stroke(window_points, camera, plane, params_.stroke);
  if (!lifted) return lifted.status();
  StrokeEdit e;
  e.parts_before = model_parts(state_.model);
  if (lifted->closed) {
    if (auto st = add_section(plane, lifted->points); !st) return st;
    e.section = static_cast<int>(state_.sections.curves.size()) - 1;
  } else if (auto st = edit_by_open_stroke(lifted->window_points, lifted->points, camera, plane, e); !st) {
    return st;
  }
  e.parts_after = model_parts(state_.model);
  if (edit) *edit = e;
  return Status::ok();
}

Status SketchSession::edit_by_open_stroke(const std::vector<Vec2>& window_points, const std::vector<Vec3>& points,
                                          const Camera& camera, const Plane& plane, StrokeEdit& edit) {
  std::ostringstream why;
  why << "the stroke is open: a cross section must be a closed curve (end where you began); an open stroke edits a "
         "section only when both its ends come within "
      << params_.oversketch_snap_px << " px of a section on this plane or of the model's outline on it";
  if (!(plane.normal.norm() > 0.0) || !std::isfinite(plane.offset))
    return Status::error("the plane is degenerate (zero normal or non-finite offset)");
  // The plane of the session's set when it holds curves (its frame is theirs), else this one.
  const int on = find_plane(state_.sections, plane);
  const Plane pl = on >= 0 ? state_.sections.planes[static_cast<std::size_t>(on)]
                           : Plane{plane.normal / plane.normal.norm(), plane.offset / plane.normal.norm()};
  const PlaneFrame frame = plane_frame(pl);
  // The snapping distance on the plane: the pixels at the stroke's ends lifted onto it.
  double pixel = 0.0;
  for (const Vec2& w : {window_points.front(), window_points.back()}) {
    const auto a = camera.lift(w.x(), w.y(), pl), b = camera.lift(w.x() + 1.0, w.y(), pl),
               c = camera.lift(w.x(), w.y() + 1.0, pl);
    if (!a || !b || !c) return Status::error(why.str());
    pixel = std::max({pixel, (*b - *a).norm(), (*c - *a).norm()});
  }
  const double snap = params_.oversketch_snap_px * pixel;
  std::vector<Vec2> stroke;
  for (const Vec3& p : points) stroke.push_back(frame.to_2d(p));
  // The closed curve of `curves` both ends of the stroke come nearest to (within `snap`), in 2D.
  const auto nearest_curve = [&](const std::vector<const std::vector<Vec3>*>& curves, std::vector<Vec2>& best_2d) {
    int best = -1;
    double best_d = snap;
    for (std::size_t i = 0; i < curves.size(); ++i) {
      std::vector<Vec2> c;
      for (const Vec3& p : *curves[i]) c.push_back(frame.to_2d(p));
      if (c.size() < 3) continue;
      const double d = std::max(nearest_on_closed(c, stroke.front()).distance, nearest_on_closed(c, stroke.back()).distance);
      if (d <= best_d) {
        best_d = d;
        best = static_cast<int>(i);
        best_2d = std::move(c);
      }
    }
    return best;
  };
  const auto to_3d = [&](const std::vector<Vec2>& q) {
    std::vector<Vec3> out;
    for (const Vec2& p : q) out.push_back(pl.project(frame.to_3d(p)));
    return out;
  };
  // === Oversketch: a section the user drew on this plane.
  std::vector<const std::vector<Vec3>*> own;
  std::vector<int> own_index;
  for (std::size_t i = 0; i < state_.sections.curves.size(); ++i)
    if (on >= 0 && state_.sections.curves[i].plane == on) {
      own.push_back(&state_.sections.curves[i].points);
      own_index.push_back(static_cast<int>(i));
    }
  std::vector<Vec2> curve;
  if (const int k = nearest_curve(own, curve); k >= 0) {
    const int index = own_index[static_cast<std::size_t>(k)];
    const std::string what = "oversketch of section " + std::to_string(index) + ": ";
    auto spliced = splice_open_stroke(curve, stroke, snap);
    if (!spliced) return Status::error(what + spliced.message());
    SessionState next = state_;
    next.sections.curves[static_cast<std::size_t>(index)].points = to_3d(spliced->curve);
    if (auto st = commit(std::move(next)); !st) return Status::error(what + st.message());
    edit.kind = StrokeEdit::Kind::kOversketch;
    edit.section = index;
    return Status::ok();
  }
  // === Completion: a curve of the model's own cross section by the plane.
  if (!state_.model.faces.empty()) {
    auto loops = model_section(state_.model, pl);
    if (!loops) return Status::error(why.str() + " (" + loops.message() + ")");
    std::vector<const std::vector<Vec3>*> computed;
    for (const auto& l : *loops) computed.push_back(&l);
    if (nearest_curve(computed, curve) >= 0) {
      auto spliced = splice_open_stroke(curve, stroke, snap);
      if (!spliced) return Status::error("completing the stroke from the model's cross section: " + spliced.message());
      if (auto st = add_section(pl, to_3d(spliced->curve)); !st)
        return Status::error("the completed stroke: " + st.message());
      edit.kind = StrokeEdit::Kind::kCompletion;
      edit.section = static_cast<int>(state_.sections.curves.size()) - 1;
      return Status::ok();
    }
  }
  // === Nothing under its ends: a stroke on one side of its chord is closed by its mirror image.
  if (const auto closed = mirror_about_chord(stroke)) {
    if (auto st = add_section(pl, to_3d(*closed)); !st) return Status::error("the stroke mirrored about its chord: " + st.message());
    edit.kind = StrokeEdit::Kind::kMirrored;
    edit.section = static_cast<int>(state_.sections.curves.size()) - 1;
    return Status::ok();
  }
  why << ", or when it lies on one side of the line between its ends (it is then mirrored about that line)";
  return Status::error(why.str());
}

Status SketchSession::add_section(const Plane& plane, const std::vector<Vec3>& points) {
  if (!state_.base.empty()) return Status::error(kImportedNoSections);
  if (!(plane.normal.norm() > 0.0) || !std::isfinite(plane.offset))
    return Status::error("the plane is degenerate (zero normal or non-finite offset)");
  if (points.size() < 3) return Status::error("a cross section needs at least 3 points");
  for (const auto& p : points)
    if (!p.allFinite()) return Status::error("the curve has a non-finite coordinate");
  SessionState next = state_;
  CrossSection c;
  c.plane = find_or_add_plane(next.sections, plane);
  const Plane& pl = next.sections.planes[static_cast<std::size_t>(c.plane)];
  c.points.reserve(points.size());
  for (const auto& p : points) c.points.push_back(pl.project(p));
  next.sections.curves.push_back(std::move(c));
  return commit(std::move(next));
}

Status SketchSession::delete_section(int index) {
  if (!state_.base.empty()) return Status::error(kImportedNoSections);
  if (index < 0 || static_cast<std::size_t>(index) >= state_.sections.curves.size()) {
    std::ostringstream m;
    m << "no section " << index << " to delete (there are " << state_.sections.curves.size() << ")";
    return Status::error(m.str());
  }
  SessionState next = state_;
  next.sections.curves.erase(next.sections.curves.begin() + index);
  compact_planes(next.sections);
  return commit(std::move(next));
}

int SketchSession::pick_section(const Vec2& window_point, const Camera& camera,
                                double radius_px) const {
  int best = -1;
  double best_d = radius_px;
  for (std::size_t ci = 0; ci < state_.sections.curves.size(); ++ci) {
    const auto& pts = state_.sections.curves[ci].points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto a = camera.project(pts[i]);
      const auto b = camera.project(pts[(i + 1) % pts.size()]);
      if (!a || !b) continue;
      const Vec2 pa = a->head<2>(), pb = b->head<2>();
      const Vec2 ab = pb - pa;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((window_point - pa).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const double d = (pa + t * ab - window_point).norm();
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(ci);
      }
    }
  }
  return best;
}

Status SketchSession::set_parameter(const std::string& name, double value) {
  if (!std::isfinite(value)) return Status::error("parameter " + name + " must be a finite number");
  if (name == "lambda") {
    if (value < 0.0 || value > 1.0) return Status::error("lambda must lie in [0, 1]");
    params_.lambda = value;
    return Status::ok();
  }
  if (name == "filter_px") {
    if (!(value > 0.0)) return Status::error("filter_px must be positive");
    params_.stroke.min_spacing_px = value;
    return Status::ok();
  }
  if (name == "improve") {
    params_.improve = value != 0.0;
    return Status::ok();
  }
  return Status::error("unknown parameter '" + name + "' (known: lambda, filter_px, improve)");
}

Status SketchSession::undo() {
  if (undo_.empty()) return Status::error("nothing to undo");
  redo_.push_back(std::move(state_));
  state_ = std::move(undo_.back());
  undo_.pop_back();
  return Status::ok();
}

Status SketchSession::redo() {
  if (redo_.empty()) return Status::error("nothing to redo");
  undo_.push_back(std::move(state_));
  state_ = std::move(redo_.back());
  redo_.pop_back();
  return Status::ok();
}

Status SketchSession::build(const SessionParams& params, SessionState& next, ReconstructReport& report) {
  next.hints.clear();
  if (!next.base.empty()) {
    // An imported base: no sections; the operations apply to the mesh itself.
    if (!next.sections.curves.empty())
      return Status::error("a session with an imported base mesh has no cross sections");
    TriMesh mesh = next.base;
    std::vector<double> stiffness;
    for (std::size_t k = 0; k < next.ops.size(); ++k)
      if (auto st = apply_op(mesh, stiffness, next.ops[k]); !st)
        return Status::error("operation " + std::to_string(k + 1) + " (" + session_op_name(next.ops[k]) +
                             ") does not apply to the imported mesh: " + st.message());
    next.sewn = SectionSet{};
    next.model = std::move(mesh);
    next.stiffness = std::move(stiffness);
    return Status::ok();
  }
  if (next.sections.curves.empty()) {
    if (!next.edits.empty())
      return Status::error("the model has topology edits; deleting its last section would lose them (undo them first)");
    if (!next.ops.empty())
      return Status::error("the model has been sculpted; deleting its last section would lose that work (undo the sculpting first)");
    next.sewn = next.sections;
    next.model = TriMesh{};
    next.stiffness.clear();
    return Status::ok();
  }
  SewingReport sewing;
  auto sewn = sew_curves(next.sections, SewingParams{}, &sewing);
  if (!sewn) return Status::error("stroke rule 4: " + sewn.message());
  ReconstructOptions ro;
  ro.improve = false;  // improved below, within the interactive budget
  // The session keeps the input's own axes (not yet the canonical ones of the command line): the
  // bundled deform log's strokes were drawn on those models, and one of its deformations would
  // cross the surface of the canonical-axis model; re-recording it is left for later.
  ro.canonical_axes = false;
  ProgressiveReconstructor reconstructor(ro);
  auto mesh = reconstructor.update(*sewn, next.edits, &report);
  if (!mesh) return mesh.status();
  if (params.improve) {
    if (mesh->faces.size() <= params.improve_max_faces) {
      auto improved = improve_mesh(*mesh, report.curve_vertex, report.curve_edges);
      if (improved)
        *mesh = std::move(*improved);
      else
        report.warnings.push_back("mesh improvement failed, initial surface kept: " + improved.message());
    } else {
      report.warnings.push_back("the model has " + std::to_string(mesh->faces.size()) +
                                " faces: shown without refinement and smoothing");
    }
  }
  // Sculpting, deformation and painting done on the previous model are applied again to the
  // new reconstruction, in order.
  std::vector<double> stiffness;
  for (std::size_t k = 0; k < next.ops.size(); ++k) {
    if (auto st = apply_op(*mesh, stiffness, next.ops[k]); !st)
      return Status::error("the new sections would undo operation " + std::to_string(k + 1) + " (" +
                           session_op_name(next.ops[k]) + "): " + st.message());
  }
  next.sewn = std::move(*sewn);
  next.model = std::move(*mesh);
  next.stiffness = std::move(stiffness);
  next.hints = report.warnings;
  return Status::ok();
}

Status SketchSession::commit(SessionState next) {
  ReconstructReport report;
  if (auto st = build(params_, next, report); !st) return st;
  push(std::move(next));
  report_ = std::move(report);
  return Status::ok();
}

Status check_base_mesh(const TriMesh& mesh) {
  if (mesh.faces.empty()) return Status::error("the mesh has no faces");
  for (const Vec3& p : mesh.vertices)
    if (!p.allFinite()) return Status::error("the mesh has a non-finite coordinate");
  for (const Face& f : mesh.faces)
    for (int v : f)
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        return Status::error("the mesh has a face index out of range");
  const MeshGuarantees g = check_guarantees(mesh);
  if (!g.valid()) {
    std::string why = g.problem();
    if (why.empty() && !(g.topology.signed_volume > 0.0))
      why = "it is oriented inwards (negative volume)";
    return Status::error("the mesh cannot be a base: " + (why.empty() ? std::string("not a valid solid") : why) +
                         " (a base must be closed, manifold, oriented outwards and free of self-intersections)");
  }
  return Status::ok();
}

Status SketchSession::import_base(TriMesh mesh) {
  if (!state_.base.empty()) return Status::error("the session already has an imported base mesh (start a new session)");
  if (!state_.sections.curves.empty() || !state_.ops.empty())
    return Status::error("a mesh is imported into an empty session; this one has " +
                         std::to_string(state_.sections.curves.size()) + " sections and " +
                         std::to_string(state_.ops.size()) + " operations");
  if (auto st = check_base_mesh(mesh); !st) return st;
  SessionState next;
  next.base = std::move(mesh);
  ReconstructReport report;
  if (auto st = build(params_, next, report); !st) return st;
  push(std::move(next));
  report_ = std::move(report);
  return Status::ok();
}

Status SketchSession::load(SessionParams params, const SessionState& saved) {
  if (!saved.base.empty())
    if (auto st = check_base_mesh(saved.base); !st) return Status::error("base: " + st.message());
  SessionState next;
  next.base = saved.base;
  next.sections = saved.sections;
  next.ops = saved.ops;
  next.edits = saved.edits;
  ReconstructReport report;
  if (auto st = build(params, next, report); !st) return st;
  params_ = std::move(params);
  state_ = std::move(next);
  undo_.clear();
  redo_.clear();
  report_ = std::move(report);
  return Status::ok();
}

}  // namespace ps
