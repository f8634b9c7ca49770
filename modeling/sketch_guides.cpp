#include "modeling/sketch_guides.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "modeling/curve_sewing.h"
#include "modeling/mesh_slicer.h"

namespace ps {
namespace {

double distance_to_closed(const std::vector<Vec3>& poly, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3 a = poly[i], ab = poly[(i + 1) % poly.size()] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

}  // namespace

int find_plane(const SectionSet& set, const Plane& plane, double rel_tol) {
  const double n = plane.normal.norm();
  if (!(n > 0.0)) return -1;
  const Vec3 normal = plane.normal / n;
  const double offset = plane.offset / n;
  for (std::size_t i = 0; i < set.planes.size(); ++i) {
    const Plane& q = set.planes[i];
    const double scale = 1.0 + std::abs(q.offset) + std::abs(offset);
    for (const double sign : {1.0, -1.0})
      if ((q.normal - sign * normal).norm() < rel_tol && std::abs(q.offset - sign * offset) < rel_tol * scale)
        return static_cast<int>(i);
  }
  return -1;
}

std::vector<CrossingHint> crossing_hints(const SectionSet& sections, const Plane& plane) {
  std::vector<CrossingHint> out;
  const double tol = 1e-6 * bounding_box(sections.all_points()).diagonal();
  const int on = find_plane(sections, plane, 1e-9);
  for (const Vec3& p : required_crossings(sections, plane)) {
    CrossingHint h;
    h.point = p;
    if (on >= 0)
      for (const auto& c : sections.curves)
        if (c.plane == on && distance_to_closed(c.points, p) <= tol) h.met = true;
    out.push_back(h);
  }
  return out;
}

Result<std::vector<std::vector<Vec3>>> model_section(const TriMesh& model, const Plane& plane) {
  using R = Result<std::vector<std::vector<Vec3>>>;
  if (model.faces.empty()) return R::error("there is no model to slice");
  std::vector<std::string> warnings;  // a plane moved off a vertex, a tiny loop dropped: harmless here
  auto set = slice_mesh(model, {plane}, SliceOptions{}, &warnings);
  if (!set) return R::error("the model's cross section: " + set.message());
  std::vector<std::vector<Vec3>> loops;
  for (auto& c : set->curves) loops.push_back(std::move(c.points));
  return loops;
}

}  // namespace ps
