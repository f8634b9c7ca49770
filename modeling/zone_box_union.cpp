// The union of a zone filled by six whole-face prisms: the zone's box (see the header for why).
#include "modeling/zone_box_union.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "modeling/mesh_topology.h"

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

// The prism on zone face f when it fills its share of the zone: 4 bottom vertices exactly at the
// face rectangle's corners, 4 top vertices at one depth t >= 1/2 of the zone (normalised), each
// moved inward from its bottom vertex by at most t (normalised) along both side axes; 12
// triangles. Appends its bottom cap (the triangles on the face) to `caps`.
bool fills_its_share(const Zone& zone, int f, const TriMesh& m, const PrimitiveInfo& info,
                     std::vector<std::array<Vec3, 3>>& caps) {
  if (info.bottom_count != 4 || m.vertices.size() != 8 || m.faces.size() != 12) return false;
  const int k = f / 2;
  const bool max_side = f % 2 == 1;
  const double base = max_side ? zone.max[k] : zone.min[k];
  const double inward = max_side ? -1.0 : 1.0;
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  std::array<bool, 4> corner_seen{};
  double depth = -1.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3& p = m.vertices[i];
    const Vec3& q = m.vertices[i + 4];
    if (p[k] != base) return false;
    const bool at_a_max = p[a] == zone.max[a], at_b_max = p[b] == zone.max[b];
    if (!(at_a_max || p[a] == zone.min[a]) || !(at_b_max || p[b] == zone.min[b])) return false;
    const std::size_t corner = (at_a_max ? 1u : 0u) + (at_b_max ? 2u : 0u);
    if (corner_seen[corner]) return false;
    corner_seen[corner] = true;
    const double t = inward * (q[k] - base) / zone.extent(k);
    if (i == 0) depth = t;
    if (!(t == depth && t >= 0.5 && t <= 1.0)) return false;
    // Inward moves along the side axes, normalised, within [0, t] (and at most a quarter: the
    // 4.3 pull is a few percent, so anything larger is not a prism of Eq. 4.1).
    const double move_a = (at_a_max ? p[a] - q[a] : q[a] - p[a]) / zone.extent(a);
    const double move_b = (at_b_max ? p[b] - q[b] : q[b] - p[b]) / zone.extent(b);
    const double limit = std::min(t, 0.25);
    if (!(move_a >= 0.0 && move_a <= limit && move_b >= 0.0 && move_b <= limit)) return false;
  }
  int cap_triangles = 0;
  for (const Face& tri : m.faces) {
    if (tri[0] < 0 || tri[1] < 0 || tri[2] < 0 || tri[0] > 7 || tri[1] > 7 || tri[2] > 7) return false;
    if (tri[0] < 4 && tri[1] < 4 && tri[2] < 4) {
      caps.push_back({m.vertices[uz(tri[0])], m.vertices[uz(tri[1])], m.vertices[uz(tri[2])]});
      ++cap_triangles;
    }
  }
  return cap_triangles == 2;
}

}  // namespace

std::optional<TriMesh> filled_zone_union(const Zone& zone, const ZonePrimitives& primitives) {
  if (primitives.solids.size() != 6 || primitives.info.size() != 6) return std::nullopt;
  for (int k = 0; k < 3; ++k)
    if (!(zone.extent(k) > 0.0)) return std::nullopt;
  std::array<bool, 6> face_seen{};
  std::vector<std::array<Vec3, 3>> caps;
  caps.reserve(12);
  for (std::size_t i = 0; i < 6; ++i) {
    const PrimitiveInfo& info = primitives.info[i];
    if (info.face < 0 || info.face > 5 || face_seen[uz(info.face)]) return std::nullopt;
    face_seen[uz(info.face)] = true;
    if (!fills_its_share(zone, info.face, primitives.solids[i], info, caps)) return std::nullopt;
  }
  // The box: the eight corners (exact doubles, shared by three caps each) and the caps.
  TriMesh box;
  box.vertices.reserve(8);
  auto index_of = [&](const Vec3& p) {
    for (std::size_t v = 0; v < box.vertices.size(); ++v)
      if (box.vertices[v] == p) return static_cast<int>(v);
    box.vertices.push_back(p);
    return static_cast<int>(box.vertices.size() - 1);
  };
  for (const auto& c : caps) box.faces.push_back({index_of(c[0]), index_of(c[1]), index_of(c[2])});
  // The caps of a prism face away from it, so out of the zone; checked anyway: a closed,
  // consistently oriented box of 8 vertices, or the exact union decides.
  const MeshTopology topo = mesh_topology(box);
  if (box.vertices.size() != 8 || !topo.closed || !topo.manifold() || !topo.consistently_oriented) return std::nullopt;
  if (!(signed_volume(box, zone.min) > 0.0)) return std::nullopt;
  return box;
}

}  // namespace ps
