#include "modeling/sketch_session.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "modeling/curve_sewing.h"
#include "modeling/mesh_improve.h"
#include "modeling/sculpt_cut.h"
#include "modeling/sculpt_extrude.h"
#include "modeling/sculpt_smooth.h"

namespace ps {
namespace {

// Index of `plane` in `set.planes`, adding it when no plane there coincides with it
// (same unit normal up to sign and same offset, within 1e-12 relative).
int find_or_add_plane(SectionSet& set, const Plane& plane) {
  Plane p = plane;
  const double n = p.normal.norm();
  p.normal /= n;
  p.offset /= n;
  for (std::size_t i = 0; i < set.planes.size(); ++i) {
    const Plane& q = set.planes[i];
    const double scale = 1.0 + std::abs(q.offset) + std::abs(p.offset);
    if ((q.normal - p.normal).norm() < 1e-12 && std::abs(q.offset - p.offset) < 1e-12 * scale)
      return static_cast<int>(i);
    if ((q.normal + p.normal).norm() < 1e-12 && std::abs(q.offset + p.offset) < 1e-12 * scale)
      return static_cast<int>(i);
  }
  set.planes.push_back(p);
  return static_cast<int>(set.planes.size() - 1);
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

}  // namespace

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
  next.model = std::move(*out);
  undo_.push_back(std::move(state_));
  redo_.clear();
  state_ = std::move(next);
  return Status::ok();
}

Status SketchSession::add_window_stroke(const std::vector<Vec2>& window_points,
                                        const Camera& camera, const Plane& plane) {
  auto lifted = prepare_plane_stroke(window_points, camera, plane, params_.stroke);
  if (!lifted) return lifted.status();
  if (!lifted->closed)
    return Status::error("the stroke is open: a cross section must be a closed curve (end where you began)");
  return add_section(plane, lifted->points);
}

Status SketchSession::add_section(const Plane& plane, const std::vector<Vec3>& points) {
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

Status SketchSession::commit(SessionState next) {
  next.hints.clear();
  ReconstructReport report;
  if (next.sections.curves.empty()) {
    if (!next.ops.empty())
      return Status::error("the model has been sculpted; deleting its last section would lose that work (undo the sculpting first)");
    next.sewn = next.sections;
    next.model = TriMesh{};
  } else {
    SewingReport sewing;
    auto sewn = sew_curves(next.sections, SewingParams{}, &sewing);
    if (!sewn) return Status::error("stroke rule 4: " + sewn.message());
    ReconstructOptions ro;
    ro.improve = false;  // improved below, within the interactive budget
    auto mesh = reconstruct(*sewn, ro, &report);
    if (!mesh) return mesh.status();
    if (params_.improve) {
      if (mesh->faces.size() <= params_.improve_max_faces) {
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
    // Sculpting done on the previous model is applied again to the new reconstruction.
    for (std::size_t k = 0; k < next.ops.size(); ++k) {
      auto sculpted = apply_sculpt(*mesh, next.ops[k]);
      if (!sculpted)
        return Status::error("the new sections would undo sculpting operation " + std::to_string(k + 1) + " (" +
                             sculpt_kind_name(next.ops[k].kind) + "): " + sculpted.message());
      *mesh = std::move(*sculpted);
    }
    next.sewn = std::move(*sewn);
    next.model = std::move(*mesh);
    next.hints = report.warnings;
  }
  undo_.push_back(std::move(state_));
  redo_.clear();
  state_ = std::move(next);
  report_ = std::move(report);
  return Status::ok();
}

}  // namespace ps
