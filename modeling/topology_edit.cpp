#include "modeling/topology_edit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "modeling/face_intersections.h"
#include "modeling/mesh_topology.h"
#include "modeling/point_triangle_distance.h"

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

using PrimRef = std::pair<int, int>;  // (zone, index into that zone's solids)

// === Point queries on small closed meshes (a prism has ~100 triangles). Hand-written: CGAL's
// AABB tree and side-of-mesh test would bring CGAL headers into this file for a few hundred
// triangles.

// Generalized winding number: the solid angles of the faces seen from p over 4 pi (1 inside a
// closed outward mesh, 0 outside), each by the Van Oosterom-Strackee formula.
bool inside(const TriMesh& m, const Vec3& p) {
  double sum = 0;
  for (const auto& f : m.faces) {
    const Vec3 a = m.vertices[uz(f[0])] - p, b = m.vertices[uz(f[1])] - p, c = m.vertices[uz(f[2])] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    sum += 2.0 * std::atan2(num, den);
  }
  return sum > 2.0 * std::numbers::pi;  // winding number > 1/2
}

// 0 inside the solid, else the distance to its surface.
double distance_to_solid(const TriMesh& m, const Vec3& p) {
  if (inside(m, p)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : m.faces)
    best = std::min(best, point_triangle_distance2(p, m.vertices[uz(f[0])], m.vertices[uz(f[1])], m.vertices[uz(f[2])]));
  return std::sqrt(best);
}

// The two solids share interior points: their surfaces cross, or one holds a vertex of the other.
bool overlap(const TriMesh& a, const TriMesh& b) {
  for (const auto& v : a.vertices)
    if (inside(b, v)) return true;
  for (const auto& v : b.vertices)
    if (inside(a, v)) return true;
  std::vector<Vec3> pts = a.vertices;
  pts.insert(pts.end(), b.vertices.begin(), b.vertices.end());
  std::vector<Face> faces = a.faces;
  const int nv = static_cast<int>(a.vertices.size()), nf = static_cast<int>(a.faces.size());
  for (const auto& f : b.faces) faces.push_back({f[0] + nv, f[1] + nv, f[2] + nv});
  std::vector<int> query(a.faces.size());
  for (int i = 0; i < nf; ++i) query[uz(i)] = i;
  for (const auto& pr : intersecting_face_pairs(pts, faces, query))
    if ((pr[0] < nf) != (pr[1] < nf)) return true;
  return false;
}

// === Prism geometry (layout of PrimitiveInfo: bottom vertices, then the top ones).

int prism_axis(const PrimitiveInfo& info) { return info.face / 2; }

double bottom_coordinate(const TriMesh& m, const PrimitiveInfo& info) {
  return m.vertices.front()[prism_axis(info)];
}

// The bottom lies strictly inside its zone face: no wall of the prism is in a side face.
bool interior(const TriMesh& m, const PrimitiveInfo& info, const Zone& z) {
  const int k = prism_axis(info);
  for (int i = 0; i < info.bottom_count; ++i)
    for (int a = 0; a < 3; ++a)
      if (a != k && !(m.vertices[uz(i)][a] > z.min[a] && m.vertices[uz(i)][a] < z.max[a])) return false;
  return true;
}

void shear_top(TriMesh& m, const PrimitiveInfo& info, const Vec3& d) {
  for (int i = info.bottom_count; i < 2 * info.bottom_count; ++i) m.vertices[uz(i)] += d;
}

void shrink_top(TriMesh& m, const PrimitiveInfo& info, double s) {
  const int k = prism_axis(info);
  const double c0 = bottom_coordinate(m, info);
  for (int i = info.bottom_count; i < 2 * info.bottom_count; ++i) {
    double& c = m.vertices[uz(i)][k];
    c = c0 + s * (c - c0);
  }
}

// q lies inside zone z by 0.5% of the zone's extent along every axis but `skip` (-1: none).
bool inside_by_margin(const Vec3& q, const Zone& z, int skip) {
  for (int a = 0; a < 3; ++a) {
    if (a == skip) continue;
    const double margin = 0.005 * z.extent(a);
    if (!(q[a] > z.min[a] + margin && q[a] < z.max[a] - margin)) return false;
  }
  return true;
}

bool top_inside(const TriMesh& m, const PrimitiveInfo& info, const Zone& z) {
  for (int i = info.bottom_count; i < 2 * info.bottom_count; ++i)
    if (!inside_by_margin(m.vertices[uz(i)], z, prism_axis(info))) return false;
  return true;
}

Vec3 centroid(const std::vector<Vec3>& v, std::size_t from, std::size_t to) {
  Vec3 c = Vec3::Zero();
  for (std::size_t i = from; i < to; ++i) c += v[i];
  return c / static_cast<double>(to - from);
}

// The body prism nearest p over all zones; {-1, -1} when there is none.
PrimRef nearest_body_prism(const std::vector<ZonePrimitives>& prims, const Vec3& p, int only_zone = -1) {
  PrimRef best{-1, -1};
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t z = 0; z < prims.size(); ++z) {
    if (only_zone >= 0 && static_cast<int>(z) != only_zone) continue;
    for (std::size_t i = 0; i < prims[z].solids.size(); ++i) {
      if (i >= prims[z].info.size() || !prims[z].info[i].body) continue;
      const double d = distance_to_solid(prims[z].solids[i], p);
      if (d < best_d) {
        best_d = d;
        best = {static_cast<int>(z), static_cast<int>(i)};
      }
    }
  }
  return best;
}

// Prisms that must change with `start` so that zone faces keep matching: the continuations of
// its walls lying in side faces that carry no section (the same plane's piece in the neighbour
// zone, sharing bottom points on that face), transitively.
Result<std::vector<PrimRef>> linked_prisms(const Partition& part, const std::vector<ZonePrimitives>& prims,
                                           PrimRef start) {
  const double tol = 1e-12 * part.grid.box.diagonal();
  std::set<PrimRef> seen{start};
  std::vector<PrimRef> order{start};
  for (std::size_t q = 0; q < order.size(); ++q) {
    const auto [zi, pi] = order[q];
    const Zone& z = part.zones[uz(zi)];
    const TriMesh& m = prims[uz(zi)].solids[uz(pi)];
    const PrimitiveInfo& info = prims[uz(zi)].info[uz(pi)];
    const int k = prism_axis(info);
    const int plane = part.pieces[uz(info.piece)].plane;
    for (int a = 0; a < 3; ++a) {
      if (a == k) continue;
      for (int side = 0; side < 2; ++side) {
        const int sf = 2 * a + side;
        const double c = side == 0 ? z.min[a] : z.max[a];
        std::vector<Vec3> touching;
        for (int i = 0; i < info.bottom_count; ++i)
          if (m.vertices[uz(i)][a] == c) touching.push_back(m.vertices[uz(i)]);
        if (touching.empty() || z.face_has_section(sf) || z.on_box[uz(sf)]) continue;
        std::array<int, 3> cell = z.cell;
        cell[uz(a)] += side == 0 ? -1 : 1;
        const int ni = part.grid.index(cell);
        const ZonePrimitives& np = prims[uz(ni)];
        bool found = false;
        for (std::size_t j = 0; j < np.solids.size() && !found; ++j) {
          const PrimitiveInfo& nj = np.info[j];
          if (nj.face != info.face || part.pieces[uz(nj.piece)].plane != plane) continue;
          for (int v = 0; v < nj.bottom_count && !found; ++v)
            for (const auto& t : touching)
              if ((np.solids[j].vertices[uz(v)] - t).norm() <= tol) {
                found = true;
                break;
              }
          if (!found) continue;
          if (!nj.body)
            return Result<std::vector<PrimRef>>::error(
                "the part continues into an end zone (its prism there is stretched through empty zones), so it "
                "cannot be changed");
          const PrimRef r{ni, static_cast<int>(j)};
          if (seen.insert(r).second) order.push_back(r);
        }
        if (!found)
          return Result<std::vector<PrimRef>>::error("the part's continuation in the neighbour zone was not found");
      }
    }
  }
  return order;
}

Status check_stroke(const TopologyEdit& e) {
  const char* name = topology_edit_name(e.kind);
  if (e.stroke.size() < 2) return Status::error(std::string(name) + " stroke needs at least 2 points");
  for (const auto& p : e.stroke)
    if (!p.allFinite()) return Status::error(std::string(name) + " stroke has a NaN or infinite point");
  return Status::ok();
}

// === Join across zones (thesis 6.4.1, figure 6.8)
//
// The zones between the two parts: a walk through face-adjacent grid cells along the segment
// from the first prism's top to the middle of the second prism (a 3D DDA; where the segment meets
// an edge or a corner of cells, one axis is crossed at a time, x before y before z). Each step
// crosses one common face G_i between zones Z_(i-1) and Z_i, at the point `through[i]` where the
// segment meets its plane (through[0] is `from`).
std::vector<int> zone_chain(const Partition& part, const Vec3& from, const Vec3& to, int first, int last,
                            std::vector<Vec3>& through) {
  const ZoneGrid& g = part.grid;
  std::array<int, 3> cell = part.zones[uz(first)].cell;
  const std::array<int, 3> goal = part.zones[uz(last)].cell;
  std::vector<int> chain{first};
  through.assign(1, from);
  const Vec3 d = to - from;
  const int limit = g.cells(0) + g.cells(1) + g.cells(2);
  while (cell != goal && static_cast<int>(chain.size()) <= limit) {
    // The axis whose next cell boundary the segment reaches first; an axis already at the goal's
    // cell does not move.
    int axis = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (cell[uz(k)] == goal[uz(k)]) continue;
      const int step = goal[uz(k)] > cell[uz(k)] ? 1 : -1;
      const double plane = g.coords[uz(k)][uz(cell[uz(k)] + (step > 0 ? 1 : 0))];
      const double t = d[k] != 0.0 ? (plane - from[k]) / d[k] : std::numeric_limits<double>::infinity();
      if (axis < 0 || t < best) {
        best = t;
        axis = k;
      }
    }
    cell[uz(axis)] += goal[uz(axis)] > cell[uz(axis)] ? 1 : -1;
    chain.push_back(g.index(cell));
    through.push_back(from + std::clamp(best, 0.0, 1.0) * d);
  }
  return chain;
}

// The coordinate of face `f` (0..5 = -x,+x,-y,+y,-z,+z) of zone `z` along its axis f / 2.
double face_coordinate(const Zone& z, int f) { return f % 2 == 0 ? z.min[f / 2] : z.max[f / 2]; }

// The face of zone `z` shared with the face-adjacent zone `n`: index 0..5 (-x,+x,-y,+y,-z,+z).
int shared_face(const Zone& z, const Zone& n) {
  for (int k = 0; k < 3; ++k)
    if (n.cell[uz(k)] != z.cell[uz(k)]) return 2 * k + (n.cell[uz(k)] > z.cell[uz(k)] ? 1 : 0);
  return -1;
}

// Points `from[0..n)` projected along `d` onto the plane x_j = c of face `f` (j = f / 2), then
// shrunk towards their centroid in that plane until they lie inside the face by 0.5% of its
// extent (100% down to 30% in steps of 10%). Nothing when a point is not ahead of the plane
// along d, or when no shrink fits.
std::optional<std::vector<Vec3>> project_onto_face(const std::vector<Vec3>& from, const Vec3& d, const Zone& z, int f) {
  const int j = f / 2;
  const double c = face_coordinate(z, f);
  const double floor_s = 1e-9 * z.extent(j);
  std::vector<Vec3> out;
  for (const Vec3& p : from) {
    const double s = d[j] != 0.0 ? (c - p[j]) / d[j] : -1.0;
    if (!(s * d.norm() > floor_s)) return std::nullopt;
    Vec3 q = p + s * d;
    q[j] = c;
    out.push_back(q);
  }
  const Vec3 centre = centroid(out, 0, out.size());
  for (int step = 10; step >= 3; --step) {
    const double f_scale = step / 10.0;
    std::vector<Vec3> shrunk = out;
    bool inside_face = true;
    for (auto& q : shrunk) {
      q = centre + f_scale * (q - centre);
      q[j] = c;
      inside_face = inside_face && inside_by_margin(q, z, j);
    }
    if (inside_face) return shrunk;
  }
  return std::nullopt;
}

// A prism-shaped solid (the layout of PrimitiveInfo) is a valid operand: positive volume and no
// two faces crossing.
// The volume about one of its vertices: about the origin, a solid far from it loses the volume's
// sign to rounding.
bool valid_solid(const TriMesh& m) {
  return !m.vertices.empty() && signed_volume(m, m.vertices.front()) > 0.0 && self_intersecting_pairs(m).empty();
}

// Whether a primitive other than `skip` of zone `zi` has a vertex on the plane of face `f`,
// within that face: material there would meet the new cap.
bool face_touched(const Partition& part, const std::vector<ZonePrimitives>& prims, int zi, int f, int skip) {
  const Zone& z = part.zones[uz(zi)];
  const int j = f / 2;
  const double c = face_coordinate(z, f);
  const auto& zp = prims[uz(zi)];
  for (std::size_t i = 0; i < zp.solids.size(); ++i) {
    if (static_cast<int>(i) == skip) continue;
    for (const auto& v : zp.solids[i].vertices) {
      if (v[j] != c) continue;
      bool within = true;
      for (int a = 0; a < 3; ++a)
        if (a != j && !(v[a] >= z.min[a] && v[a] <= z.max[a])) within = false;
      if (within) return true;
    }
  }
  return false;
}

Status join_across_zones(const Partition& part, std::vector<ZonePrimitives>& prims, PrimRef a, PrimRef b) {
  const Zone& za = part.zones[uz(a.first)];
  const TriMesh& ma = prims[uz(a.first)].solids[uz(a.second)];
  const PrimitiveInfo& ia = prims[uz(a.first)].info[uz(a.second)];
  if (!interior(ma, ia, za))
    return Status::error("join: the first part reaches a side of its zone (its walls continue in the neighbour "
                         "zone), so it cannot be extended; start the stroke on the other part");
  const auto n = uz(ia.bottom_count);
  const TriMesh& mb = prims[uz(b.first)].solids[uz(b.second)];
  const Vec3 b_middle = centroid(mb.vertices, 0, mb.vertices.size());
  std::vector<Vec3> through;
  const std::vector<int> chain =
      zone_chain(part, centroid(ma.vertices, n, 2 * n), b_middle, a.first, b.first, through);
  if (chain.back() != b.first) return Status::error("join: no chain of zones leads from one part to the other");
  // What the chain may cross: faces without sections, zones between the two without material,
  // and no other primitive of the two end zones on the faces the new frusta cross.
  for (std::size_t i = 1; i < chain.size(); ++i) {
    const Zone& prev = part.zones[uz(chain[i - 1])];
    const Zone& next = part.zones[uz(chain[i])];
    const int f = shared_face(prev, next);
    if (prev.face_has_section(f))
      return Status::error("join: the way between the parts crosses a zone face that holds a section");
    if (i + 1 < chain.size() && !prims[uz(chain[i])].solids.empty())
      return Status::error("join: the way between the parts crosses a zone that holds other parts");
    if (i == 1 && face_touched(part, prims, chain[0], f, a.second))
      return Status::error("join: another frustum of the first part's zone lies on the face the join crosses");
    if (i + 1 == chain.size() && face_touched(part, prims, chain[i], f ^ 1, -1))
      return Status::error("join: another frustum of the second part's zone lies on the face the join crosses");
  }
  // The first frustum's top: its bottom projected onto the first common face along the direction
  // from the bottom's centre to where the segment between the parts crosses that face (the thesis
  // aims at the face's centre, which on a large face leads the tube away from the parts; the
  // crossing, kept 10% of the face's extent inside it, follows them); then frustum by frustum
  // through the chain.
  std::vector<Vec3> bottom(ma.vertices.begin(), ma.vertices.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<std::pair<int, TriMesh>> changed;  // (zone, solid); the first replaces a's prism
  std::vector<int> faces;                        // per new frustum: its bottom face in its zone
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    const Zone& z = part.zones[uz(chain[i])];
    const int f = shared_face(z, part.zones[uz(chain[i + 1])]);
    const Vec3 c = centroid(bottom, 0, bottom.size());
    Vec3 aim = through[i + 1];
    for (int k = 0; k < 3; ++k)
      aim[k] = k == f / 2 ? face_coordinate(z, f)
                          : std::clamp(aim[k], z.min[k] + 0.1 * z.extent(k), z.max[k] - 0.1 * z.extent(k));
    auto top = project_onto_face(bottom, aim - c, z, f);
    if (!top)
      return Status::error("join: the frustum cannot be carried across zone " + std::to_string(chain[i]) +
                           (i == 0 ? " (the other part lies behind its section)" : " (its top does not fit the face)"));
    TriMesh m = ma;
    for (std::size_t v = 0; v < n; ++v) {
      m.vertices[v] = bottom[v];
      m.vertices[n + v] = (*top)[v];
    }
    if (!valid_solid(m))
      return Status::error("join: the frustum carried across zone " + std::to_string(chain[i]) + " would fold");
    changed.emplace_back(chain[i], std::move(m));
    if (i > 0) faces.push_back(shared_face(z, part.zones[uz(chain[i - 1])]));
    bottom = std::move(*top);
  }
  // The last zone: the carried section translated towards the middle of the second part (the
  // thesis: its top; the middle keeps the tube inside the zone where the top lies near a face)
  // until the two overlap, plus two steps of margin (a touching union is fragile), inside the
  // zone.
  const Zone& zb = part.zones[uz(b.first)];
  const int fb = shared_face(zb, part.zones[uz(chain[chain.size() - 2])]);
  const Vec3 d = b_middle - centroid(bottom, 0, bottom.size());
  constexpr int kSteps = 20, kMargin = 2;
  auto frustum = [&](int step) -> std::optional<TriMesh> {
    TriMesh m = ma;
    for (std::size_t v = 0; v < n; ++v) {
      m.vertices[v] = bottom[v];
      m.vertices[n + v] = bottom[v] + (static_cast<double>(step) / kSteps) * d;
      if (!inside_by_margin(m.vertices[n + v], zb, -1)) return std::nullopt;
    }
    return m;
  };
  // (The first steps may leave the top within the margin of the face it rises from.)
  bool was_inside = false;
  for (int step = 1; step <= kSteps; ++step) {
    auto m = frustum(step);
    if (!m) {
      if (was_inside) break;
      continue;
    }
    was_inside = true;
    if (!overlap(*m, mb)) continue;
    for (int s = std::min(step + kMargin, kSteps); s >= step; --s) {
      auto last = frustum(s);
      if (!last || !valid_solid(*last)) continue;
      // Commit: the first part's prism becomes the first frustum (not a body prism of Eq. 4.1
      // any more: later edits leave it alone), the others are added to their zones.
      auto& pa = prims[uz(a.first)];
      pa.solids[uz(a.second)] = std::move(changed.front().second);
      pa.info[uz(a.second)].body = false;
      pa.info[uz(a.second)].verified = false;
      changed.emplace_back(b.first, std::move(*last));
      faces.push_back(fb);
      for (std::size_t c = 1; c < changed.size(); ++c) {
        auto& zp = prims[uz(changed[c].first)];
        PrimitiveInfo info = ia;
        info.face = faces[c - 1];
        info.body = false;
        info.verified = false;
        zp.solids.push_back(std::move(changed[c].second));
        zp.info.push_back(info);
      }
      return Status::ok();
    }
  }
  return Status::error("join: the carried frustum does not reach the second part within its zone");
}

// === Join
Status join(const Partition& part, std::vector<ZonePrimitives>& prims, const TopologyEdit& e) {
  PrimRef a = nearest_body_prism(prims, e.stroke.front());
  PrimRef b = nearest_body_prism(prims, e.stroke.back());
  if (a.first < 0 || b.first < 0) return Status::error("join: there is no frustum of a body zone to join");
  if (a == b) return Status::error("join: both ends of the stroke select the same part");
  if (a.first != b.first) return join_across_zones(part, prims, a, b);
  const Zone& z = part.zones[uz(a.first)];
  auto& zp = prims[uz(a.first)];
  if (!interior(zp.solids[uz(a.second)], zp.info[uz(a.second)], z)) std::swap(a, b);
  if (!interior(zp.solids[uz(a.second)], zp.info[uz(a.second)], z))
    return Status::error("join: both parts reach a side of their zone (their walls continue in the neighbour zone), "
                         "so neither can be moved");
  const TriMesh& ma = zp.solids[uz(a.second)];
  const TriMesh& mb = zp.solids[uz(b.second)];
  const PrimitiveInfo& ia = zp.info[uz(a.second)];
  const int k = prism_axis(ia);
  const auto n = uz(ia.bottom_count);
  Vec3 d = centroid(mb.vertices, 0, mb.vertices.size()) - centroid(ma.vertices, n, 2 * n);
  d[k] = 0;
  if (!(d.norm() > 1e-9 * part.grid.box.diagonal()))
    return Status::error("join: the parts are aligned along the zone's axis; there is no direction to move in");
  constexpr int kSteps = 20, kMargin = 2;
  for (int step = 1; step <= kSteps; ++step) {
    TriMesh moved = ma;
    shear_top(moved, ia, (static_cast<double>(step) / kSteps) * d);
    if (!top_inside(moved, ia, z)) break;
    if (!overlap(moved, mb)) continue;
    // Some margin beyond first contact (a touching union is fragile), as far as the zone allows.
    for (int s = std::min(step + kMargin, kSteps); s >= step; --s) {
      TriMesh final_mesh = ma;
      shear_top(final_mesh, ia, (static_cast<double>(s) / kSteps) * d);
      if (!top_inside(final_mesh, ia, z)) continue;
      zp.solids[uz(a.second)] = std::move(final_mesh);
      zp.info[uz(a.second)].verified = false;  // moved: the union tests it again
      return Status::ok();
    }
  }
  return Status::error("join: the parts do not meet when one is moved within its zone");
}

// === Split
Status split(const Partition& part, std::vector<ZonePrimitives>& prims, const TopologyEdit& e) {
  // The stroke's middle by arc length.
  double len = 0;
  for (std::size_t i = 1; i < e.stroke.size(); ++i) len += (e.stroke[i] - e.stroke[i - 1]).norm();
  Vec3 mid = e.stroke.front();
  double run = 0;
  for (std::size_t i = 1; i < e.stroke.size(); ++i) {
    const double l = (e.stroke[i] - e.stroke[i - 1]).norm();
    if (run + l >= 0.5 * len && l > 0) {
      mid = e.stroke[i - 1] + (0.5 * len - run) / l * (e.stroke[i] - e.stroke[i - 1]);
      break;
    }
    run += l;
  }
  int zone = -1;
  for (std::size_t zi = 0; zi < part.zones.size() && zone < 0; ++zi) {
    const Zone& z = part.zones[zi];
    if (z.type == ZoneType::kBody && (mid.array() >= z.min.array()).all() && (mid.array() <= z.max.array()).all())
      zone = static_cast<int>(zi);
  }
  if (zone < 0) return Status::error("split: the middle of the stroke is over no body zone");
  auto& zp = prims[uz(zone)];
  const PrimRef seed = nearest_body_prism(prims, mid, zone);
  if (seed.first < 0) return Status::error("split: the stroke's zone has no frustum");
  // The local part: prisms of the zone connected to the seed by overlap.
  std::vector<int> group{seed.second};
  std::vector<char> in(zp.solids.size(), 0);
  in[uz(seed.second)] = 1;
  for (std::size_t q = 0; q < group.size(); ++q)
    for (std::size_t j = 0; j < zp.solids.size(); ++j)
      if (!in[j] && j < zp.info.size() && zp.info[j].body && overlap(zp.solids[uz(group[q])], zp.solids[j])) {
        in[j] = 1;
        group.push_back(static_cast<int>(j));
      }
  if (group.size() < 2) return Status::error("split: the stroke is over a part made of a single frustum; nothing to split");
  std::set<PrimRef> change;
  for (int g : group) {
    auto linked = linked_prisms(part, prims, {zone, g});
    if (!linked) return Status::error("split: " + linked.message());
    change.insert(linked->begin(), linked->end());
  }
  for (double s = 0.8; s >= 0.1; s *= 0.8) {
    std::vector<TriMesh> shrunk;
    for (int g : group) {
      shrunk.push_back(zp.solids[uz(g)]);
      shrink_top(shrunk.back(), zp.info[uz(g)], s);
    }
    bool apart = true;
    for (std::size_t i = 0; i < shrunk.size() && apart; ++i)
      for (std::size_t j = i + 1; j < shrunk.size() && apart; ++j) apart = !overlap(shrunk[i], shrunk[j]);
    if (!apart) continue;
    for (const auto& [zi, pi] : change) {
      shrink_top(prims[uz(zi)].solids[uz(pi)], prims[uz(zi)].info[uz(pi)], s);
      prims[uz(zi)].info[uz(pi)].verified = false;  // moved: the union tests it again
    }
    return Status::ok();
  }
  return Status::error("split: the frusta do not separate even when shrunk to a tenth of their height");
}

}  // namespace

const char* topology_edit_name(TopologyEditKind kind) { return kind == TopologyEditKind::kJoin ? "join" : "split"; }

Result<TopologyEdit> topology_edit_from_json(const nlohmann::json& e, std::string* where) {
  using R = Result<TopologyEdit>;
  auto fail = [&](std::string field, std::string what) {
    if (where) *where = std::move(field);
    return R::error(std::move(what));
  };
  if (!e.is_object() || !e.contains("kind") || !e["kind"].is_string())
    return fail("", "expected an object with a string \"kind\"");
  TopologyEdit te;
  const std::string kind = e["kind"].get<std::string>();
  if (kind == "join")
    te.kind = TopologyEditKind::kJoin;
  else if (kind == "split")
    te.kind = TopologyEditKind::kSplit;
  else
    return fail("kind", "\"" + kind + "\" is neither \"join\" nor \"split\"");
  if (!e.contains("stroke") || !e["stroke"].is_array()) return fail("", "expected an array \"stroke\"");
  for (std::size_t k = 0; k < e["stroke"].size(); ++k) {
    const auto& p = e["stroke"][k];
    const std::string at = "stroke[" + std::to_string(k) + "]";
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      return fail(at, "expected [x, y, z]");
    te.stroke.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    if (!te.stroke.back().allFinite()) return fail(at, "not a finite point");
  }
  if (Status st = check_stroke(te); !st) return fail("", st.message());
  return te;
}

nlohmann::json topology_edit_to_json(const TopologyEdit& e) {
  nlohmann::json stroke = nlohmann::json::array();
  for (const auto& p : e.stroke) stroke.push_back({p.x(), p.y(), p.z()});
  return {{"kind", topology_edit_name(e.kind)}, {"stroke", std::move(stroke)}};
}

Result<std::vector<TopologyEdit>> parse_topology_edits(const std::string& text) {
  using R = Result<std::vector<TopologyEdit>>;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax, or a number out of range
    return R::error(std::string("edits: not JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("edits") || !j["edits"].is_array())
    return R::error("edits: expected an object with an array \"edits\"");
  std::vector<TopologyEdit> out;
  for (std::size_t i = 0; i < j["edits"].size(); ++i) {
    std::string field;
    auto e = topology_edit_from_json(j["edits"][i], &field);
    if (!e)
      return R::error("edits[" + std::to_string(i) + "]" + (field.empty() ? "" : "." + field) + ": " + e.message());
    out.push_back(std::move(*e));
  }
  return out;
}

std::string format_topology_edits(const std::vector<TopologyEdit>& edits) {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& e : edits) arr.push_back(topology_edit_to_json(e));
  return nlohmann::json{{"edits", arr}}.dump(2) + "\n";
}

// join and split write to `prims` only once they have succeeded, so a refusal leaves it as it was.
Status apply_topology_edit(const Partition& part, std::vector<ZonePrimitives>& prims, const TopologyEdit& edit) {
  if (Status s = check_stroke(edit); !s) return s;
  return edit.kind == TopologyEditKind::kJoin ? join(part, prims, edit) : split(part, prims, edit);
}

}  // namespace ps
