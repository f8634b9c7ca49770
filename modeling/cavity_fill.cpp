// Empty pockets between primitives, filled (see the header).
#include "modeling/cavity_fill.h"

#include <cstddef>

#include "modeling/mesh_topology.h"
#include "modeling/zone_stitch.h"

namespace ps {
namespace {
std::size_t uz(int i) { return static_cast<std::size_t>(i); }
}  // namespace

int fill_curveless_cavities(TriMesh& mesh, const std::vector<bool>& on_curve, double& volume) {
  std::vector<int> comp;
  const int n = face_components(mesh, comp);
  volume = 0.0;
  if (n <= 1) return 0;
  std::vector<double> vol(uz(n), 0.0);
  std::vector<int> anchor(uz(n), -1);
  std::vector<char> curve(uz(n), 0);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto c = uz(comp[f]);
    const Face& t = mesh.faces[f];
    if (anchor[c] < 0) anchor[c] = t[0];
    const Vec3 o = mesh.vertices[uz(anchor[c])];
    const Vec3 a = mesh.vertices[uz(t[0])] - o, b = mesh.vertices[uz(t[1])] - o, d = mesh.vertices[uz(t[2])] - o;
    vol[c] += a.dot(b.cross(d)) / 6.0;
    for (int v : t)
      if (uz(v) < on_curve.size() && on_curve[uz(v)]) curve[c] = 1;
  }
  std::vector<char> drop(uz(n), 0);
  int dropped = 0;
  for (std::size_t c = 0; c < uz(n); ++c)
    if (vol[c] < 0.0 && !curve[c]) drop[c] = 1, ++dropped, volume -= vol[c];
  if (dropped == 0) return 0;
  TriMesh out;
  std::vector<int> map(mesh.vertices.size(), -1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (drop[uz(comp[f])]) continue;
    Face g{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& m = map[uz(mesh.faces[f][k])];
      if (m < 0) {
        m = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[uz(mesh.faces[f][k])]);
      }
      g[k] = m;
    }
    out.faces.push_back(g);
  }
  canonicalize(out);
  mesh = std::move(out);
  return dropped;
}

}  // namespace ps
