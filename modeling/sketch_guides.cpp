#include "modeling/sketch_guides.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <cmath>
#include <limits>

#include "modeling/curve_sewing.h"

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
  const double n = plane.normal.norm();
  if (!(n > 0.0) || !plane.normal.allFinite() || !std::isfinite(plane.offset))
    return R::error("the plane is degenerate (zero or non-finite normal or offset)");
  const Vec3 normal = plane.normal / n;
  const double offset = plane.offset / n;
  const std::size_t nv = model.vertices.size();
  // === Side of every vertex: a vertex on the plane counts as above it (a symbolic push up), so
  // every face the plane cuts has exactly two cut edges and the cuts chain into closed curves.
  std::vector<double> dist(nv);
  std::vector<char> above(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!model.vertices[v].allFinite()) return R::error("the model has a non-finite vertex");
    dist[v] = normal.dot(model.vertices[v]) - offset;
    above[v] = dist[v] >= 0.0 ? 1 : 0;
  }
  // === Cut edges (key: the ordered vertex pair) and the two faces across each.
  const auto key = [nv](int a, int b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
    return lo * nv + hi;
  };
  struct Cut {
    Vec3 point = Vec3::Zero();
    std::array<int, 2> faces{-1, -1};
    int count = 0;
    bool used = false;
  };
  std::unordered_map<std::uint64_t, Cut> cuts;
  std::vector<std::array<std::uint64_t, 2>> face_cuts(model.faces.size(), {0, 0});
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const Face& face = model.faces[f];
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = face[static_cast<std::size_t>(k)], b = face[static_cast<std::size_t>((k + 1) % 3)];
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= nv || static_cast<std::size_t>(b) >= nv)
        return R::error("the model has a face index out of range");
      const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
      if (above[ua] == above[ub]) continue;
      Cut& c = cuts[key(a, b)];
      if (c.count == 0) {  // the same bits from either face: interpolate from the lower index
        const std::size_t p = std::min(ua, ub), q = std::max(ua, ub);
        const double t = dist[p] / (dist[p] - dist[q]);
        c.point = model.vertices[p] + t * (model.vertices[q] - model.vertices[p]);
      }
      if (c.count < 2) c.faces[static_cast<std::size_t>(c.count)] = static_cast<int>(f);
      ++c.count;
      if (found < 2) face_cuts[f][static_cast<std::size_t>(found)] = key(a, b);
      ++found;
    }
  }
  for (const auto& [k, c] : cuts)
    if (c.count != 2)
      return R::error(std::string("the model is ") + (c.count < 2 ? "not closed" : "not manifold") +
                      " where the plane cuts it (an edge with " + std::to_string(c.count) + " faces)");
  // === Chain: from a cut edge, through the face across it, to that face's other cut edge.
  const double eps = bounding_box(model.vertices).diagonal() / 120.0;
  std::vector<std::vector<Vec3>> loops;
  for (auto& [k0, start] : cuts) {
    if (start.used) continue;
    std::vector<Vec3> loop;
    std::uint64_t k = k0;
    int face = start.faces[0];
    for (std::size_t steps = 0; steps <= cuts.size(); ++steps) {
      Cut& c = cuts.at(k);
      if (c.used) break;
      c.used = true;
      loop.push_back(c.point);
      const auto& fc = face_cuts[static_cast<std::size_t>(face)];
      k = fc[0] == k ? fc[1] : fc[0];
      const Cut& next = cuts.at(k);
      face = next.faces[0] == face ? next.faces[1] : next.faces[0];
    }
    // Points closer than 1/120 of the model's size to the last kept one are dropped: cuts
    // through a vertex or a sliver repeat a point, and the tiny wiggles a fine triangulation
    // makes next to a section curve would give a completed stroke extra rule-4 crossings.
    std::vector<Vec3> kept;
    for (const Vec3& p : loop)
      if (kept.empty() || (p - kept.back()).norm() > eps) kept.push_back(p);
    while (kept.size() > 1 && (kept.back() - kept.front()).norm() <= eps) kept.pop_back();
    if (kept.size() >= 3) loops.push_back(std::move(kept));
  }
  return loops;
}

}  // namespace ps
