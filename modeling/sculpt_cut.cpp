// Cutting and tunnelling by strokes (see sculpt_cut.h).
#include "modeling/sculpt_cut.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "modeling/mesh_boolean.h"
#include "modeling/polygon_triangulate.h"
#include "modeling/polyline_crossing.h"
#include "modeling/stroke_preprocess.h"
#include "modeling/view_extrusion.h"

namespace ps {
namespace {

// Depths that enclose the whole model with a margin, or a refusal when the eye is inside its range.
Result<DepthRange> sweep_depths(const TriMesh& model, const Camera& cam) {
  const DepthRange d = depth_range(model, cam);
  const double margin = 0.05 * (d.max - d.min) + 1e-9 * std::max(std::abs(d.max), 1.0);
  DepthRange out{d.min - margin, d.max + margin};
  if (!cam.orthographic) {
    if (!(d.min > 0)) return Result<DepthRange>::error("the camera is inside or behind the model; move it back to sculpt through the screen");
    out.min = std::max(out.min, 0.5 * d.min);
  }
  return out;
}

// Where the ray from p in direction d leaves the rectangle [lo, hi] (p inside it), and the
// perimeter parameter of that point (0..4, counter-clockwise in window pixels from lo, y down).
struct Exit {
  Vec2 point;
  double s;
};
double perimeter_param(const Vec2& q, const Vec2& lo, const Vec2& hi) {
  const Vec2 size = hi - lo;
  if (q.y() == lo.y()) return (q.x() - lo.x()) / size.x();            // top edge, left to right
  if (q.x() == hi.x()) return 1.0 + (q.y() - lo.y()) / size.y();      // right edge, downwards
  if (q.y() == hi.y()) return 2.0 + (hi.x() - q.x()) / size.x();      // bottom edge, right to left
  return 3.0 + (hi.y() - q.y()) / size.y();                            // left edge, upwards
}
Exit leave_rectangle(const Vec2& p, const Vec2& d, const Vec2& lo, const Vec2& hi) {
  double t = 1e300;
  for (int a = 0; a < 2; ++a) {
    if (d[a] > 0) t = std::min(t, (hi[a] - p[a]) / d[a]);
    if (d[a] < 0) t = std::min(t, (lo[a] - p[a]) / d[a]);
  }
  Vec2 q = p + t * d;
  // Put the point exactly on the border it reached (the parameter needs equality).
  for (int a = 0; a < 2; ++a) {
    if (std::abs(q[a] - hi[a]) <= 1e-9 * (hi[a] - lo[a])) q[a] = hi[a];
    if (std::abs(q[a] - lo[a]) <= 1e-9 * (hi[a] - lo[a])) q[a] = lo[a];
    q[a] = std::clamp(q[a], lo[a], hi[a]);
  }
  return {q, perimeter_param(q, lo, hi)};
}

// The rectangle corners met walking the perimeter from parameter s0 to s1 in increasing s.
void corners_between(double s0, double s1, const Vec2& lo, const Vec2& hi, std::vector<Vec2>& out) {
  const Vec2 corner[4] = {Vec2(hi.x(), lo.y()), Vec2(hi.x(), hi.y()), Vec2(lo.x(), hi.y()), Vec2(lo.x(), lo.y())};
  if (s1 <= s0) s1 += 4.0;
  for (int k = 1; k <= 8; ++k) {
    const double c = static_cast<double>(k);  // corner k sits at parameter k (mod 4)
    if (c > s0 && c < s1) out.push_back(corner[(k - 1) % 4]);
  }
}

// model minus the polygon swept along the viewing rays. Rounding the exact result to doubles can
// fold a sliver where the tool's wall passes within rounding distance of a model vertex; the
// stroke is a pen gesture, so the tool is then shifted by a few hundredths of a pixel (fixed
// offsets: deterministic) and the subtraction redone.
Result<TriMesh> subtract_swept(const TriMesh& model, const std::vector<Vec2>& polygon, const Camera& cam,
                               const DepthRange& depths, const char* what) {
  if (Status s = check_solid(model, "the model"); !s) return s;
  Result<TriMesh> out = Result<TriMesh>::error("");
  for (int attempt = 0; attempt < 5; ++attempt) {
    std::vector<Vec2> p = polygon;
    const Vec2 shift = static_cast<double>(attempt) * Vec2(0.031, 0.017);
    for (auto& q : p) q += shift;
    auto tool = extrude_window_polygon(p, cam, depths.min, depths.max);
    if (!tool) return Result<TriMesh>::error(std::string("the ") + what + " cannot be swept: " + tool.message());
    out = mesh_boolean(model, *tool, BooleanOp::kDifference, /*checked_a=*/true);
    if (out || out.message().find("rounded result") == std::string::npos) break;
  }
  if (!out) return Result<TriMesh>::error(std::string(what) + " failed: " + out.message());
  if (out->faces.empty()) return Result<TriMesh>::error(std::string("the ") + what + " would remove the whole model");
  return out;
}

}  // namespace

// === Silhouette
SilhouetteTest::SilhouetteTest(const TriMesh& m, const Camera& cam) {
  std::vector<std::optional<Vec2>> px(m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    if (auto p = cam.project(m.vertices[v])) {
      px[v] = Vec2(p->x(), p->y());
      lo_ = lo_.cwiseMin(*px[v]);
      hi_ = hi_.cwiseMax(*px[v]);
    }
  for (const auto& f : m.faces) {
    const auto& a = px[static_cast<std::size_t>(f[0])];
    const auto& b = px[static_cast<std::size_t>(f[1])];
    const auto& c = px[static_cast<std::size_t>(f[2])];
    if (a && b && c) tris_.push_back({*a, *b, *c});
  }
}

bool SilhouetteTest::covers(const Vec2& p) const {
  if ((p.array() < lo_.array()).any() || (p.array() > hi_.array()).any()) return false;
  for (const auto& t : tris_) {
    const double d0 = (t[1] - t[0]).x() * (p - t[0]).y() - (t[1] - t[0]).y() * (p - t[0]).x();
    const double d1 = (t[2] - t[1]).x() * (p - t[1]).y() - (t[2] - t[1]).y() * (p - t[1]).x();
    const double d2 = (t[0] - t[2]).x() * (p - t[2]).y() - (t[0] - t[2]).y() * (p - t[2]).x();
    if (d0 == 0 && d1 == 0 && d2 == 0) continue;  // a triangle seen edge-on
    if ((d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0)) return true;
  }
  return false;
}

bool on_silhouette(const TriMesh& model, const Camera& camera, const Vec2& px) {
  return SilhouetteTest(model, camera).covers(px);
}

// === Cutting
Result<TriMesh> cut_by_stroke(const TriMesh& model, const std::vector<Vec2>& stroke_px, const Vec2& remove_side_px,
                              const Camera& cam) {
  if (Status s = check_window_points(stroke_px, 2, "the cutting stroke"); !s) return s;
  if (!remove_side_px.allFinite()) return Result<TriMesh>::error("the side mark is not finite");
  auto depths = sweep_depths(model, cam);
  if (!depths) return depths.status();
  const SilhouetteTest sil(model, cam);
  if (sil.covers(stroke_px.front()) || sil.covers(stroke_px.back()))
    return Result<TriMesh>::error("the cutting stroke must start and end off the model (it has to cross it)");
  if (std::none_of(stroke_px.begin(), stroke_px.end(), [&](const Vec2& p) { return sil.covers(p); }))
    return Result<TriMesh>::error("the cutting stroke does not pass over the model");
  if (auto x = first_self_crossing_open(stroke_px))
    return Result<TriMesh>::error("the cutting stroke crosses itself at (" + std::to_string(x->x()) + ", " +
                                  std::to_string(x->y()) + ")");

  // Frame: the box of the silhouette, the stroke and the side mark, grown by a tenth of its size.
  Vec2 lo = sil.lo().cwiseMin(remove_side_px), hi = sil.hi().cwiseMax(remove_side_px);
  for (const auto& p : stroke_px) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 grow = 0.1 * (hi - lo) + Vec2::Constant(8.0);
  lo -= grow;
  hi += grow;
  // Extend both ends straight along their end segments to the frame.
  auto direction = [](const Vec2& from, const Vec2& to) -> std::optional<Vec2> {
    const Vec2 d = to - from;
    if (!(d.norm() > 0)) return std::nullopt;
    return Vec2(d.normalized());
  };
  std::size_t i1 = 1;
  while (i1 < stroke_px.size() && stroke_px[i1] == stroke_px[0]) ++i1;
  std::size_t j1 = stroke_px.size() - 2;
  while (j1 > 0 && stroke_px[j1] == stroke_px.back()) --j1;
  const auto d_start = i1 < stroke_px.size() ? direction(stroke_px[i1], stroke_px[0]) : std::nullopt;
  const auto d_end = direction(stroke_px[j1], stroke_px.back());
  if (!d_start || !d_end) return Result<TriMesh>::error("the cutting stroke has zero length");
  const Exit a = leave_rectangle(stroke_px.front(), *d_start, lo, hi);
  const Exit b = leave_rectangle(stroke_px.back(), *d_end, lo, hi);

  // The two sides: A, stroke, B, then the frame back to A one way or the other.
  std::vector<Vec2> path{a.point};
  path.insert(path.end(), stroke_px.begin(), stroke_px.end());
  path.push_back(b.point);
  std::vector<Vec2> side1 = path, side2 = path;
  corners_between(b.s, a.s, lo, hi, side1);
  std::vector<Vec2> back;
  corners_between(a.s, b.s, lo, hi, back);
  side2.insert(side2.end(), back.rbegin(), back.rend());
  std::vector<Vec2>* remove = nullptr;
  if (point_in_polygon_2d(remove_side_px, side1)) remove = &side1;
  else if (point_in_polygon_2d(remove_side_px, side2)) remove = &side2;
  if (!remove) return Result<TriMesh>::error("the side mark lies on the cutting stroke; mark the side to remove away from it");
  if (std::abs(signed_area_2d(side1)) <= 0 || std::abs(signed_area_2d(side2)) <= 0)
    return Result<TriMesh>::error("the cutting stroke leaves no model on one side");

  return subtract_swept(model, *remove, cam, *depths, "cut");
}

// === Tunnelling
Result<TriMesh> tunnel_by_stroke(const TriMesh& model, const std::vector<Vec2>& stroke_px, const Camera& cam) {
  if (Status s = check_window_points(stroke_px, 3, "the tunnel stroke"); !s) return s;
  auto depths = sweep_depths(model, cam);
  if (!depths) return depths.status();
  const SilhouetteTest sil(model, cam);
  for (std::size_t i = 0; i < stroke_px.size(); ++i)
    if (!sil.covers(stroke_px[i]))
      return Result<TriMesh>::error("the tunnel stroke leaves the model at point " + std::to_string(i) +
                                    "; draw it inside the silhouette");
  return subtract_swept(model, stroke_px, cam, *depths, "tunnel");
}

}  // namespace ps
