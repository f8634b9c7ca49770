// Smoothing by scratch-out (see sculpt_smooth.h).
#include "modeling/sculpt_smooth.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "modeling/gltf_export.h"
#include "modeling/halfedge_mesh.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_smooth.h"

namespace ps {
namespace {

double distance_to_polyline(const Vec2& p, const std::vector<Vec2>& s) {
  if (s.size() == 1) return (p - s[0]).norm();
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const Vec2 d = s[i + 1] - s[i];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - s[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (s[i] + t * d - p).norm());
  }
  return best;
}

}  // namespace

Result<TriMesh> smooth_by_scratch(const TriMesh& model, const std::vector<Vec2>& stroke, const Camera& cam,
                                  const ScratchSmoothOptions& o, ScratchSmoothReport* report) {
  if (stroke.empty()) return Result<TriMesh>::error("the scratch-out stroke is empty");
  for (std::size_t i = 0; i < stroke.size(); ++i)
    if (!stroke[i].allFinite())
      return Result<TriMesh>::error("scratch-out point " + std::to_string(i) + " is not finite");
  if (o.steps < 1) return Result<TriMesh>::error("smoothing needs at least one step");
  auto built = HalfedgeMesh::build(model);
  if (!built) return Result<TriMesh>::error("cannot smooth this mesh: " + built.message());

  Vec2 lo = stroke[0], hi = stroke[0];
  for (const auto& p : stroke) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double radius = o.radius_px > 0 ? o.radius_px : std::max(6.0, 0.2 * (hi - lo).maxCoeff());

  // === Region under the stroke
  const std::vector<Vec3> normals = vertex_normals(model);
  std::vector<std::uint8_t> fixed(model.vertices.size(), 1);
  int region = 0;
  for (std::size_t v = 0; v < model.vertices.size(); ++v) {
    const Vec3& p = model.vertices[v];
    const Vec3 to_eye = cam.orthographic ? Vec3(cam.eye - cam.target) : Vec3(cam.eye - p);
    if (!(normals[v].dot(to_eye) > 0)) continue;
    const auto w = cam.project(p);
    if (!w) continue;
    if (distance_to_polyline(Vec2(w->x(), w->y()), stroke) <= radius) {
      fixed[v] = 0;
      ++region;
    }
  }
  if (region == 0) return Result<TriMesh>::error("the scratch-out stroke is not over the model");

  // === Smooth; fewer steps when the result would intersect itself
  SmoothOptions so;
  so.flow = NormalFlow::kMeanCurvature;
  so.normal_step = o.normal_step;
  so.tangential_step = o.tangential_step;
  for (int steps = o.steps; steps >= 1; steps /= 2) {
    HalfedgeMesh m = *built;
    Smoother smoother(m, fixed, so);
    for (int k = 0; k < steps; ++k) smoother.step(m);
    TriMesh out = m.to_trimesh();
    if (!does_self_intersect(out)) {
      if (report) *report = ScratchSmoothReport{region, steps};
      return out;
    }
  }
  return Result<TriMesh>::error("smoothing this region would make the surface intersect itself");
}

}  // namespace ps
