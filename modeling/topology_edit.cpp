#include "modeling/topology_edit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "modeling/face_intersections.h"
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

bool top_inside(const TriMesh& m, const PrimitiveInfo& info, const Zone& z) {
  const int k = prism_axis(info);
  for (int i = info.bottom_count; i < 2 * info.bottom_count; ++i)
    for (int a = 0; a < 3; ++a) {
      if (a == k) continue;
      const double margin = 0.005 * z.extent(a);
      const double c = m.vertices[uz(i)][a];
      if (!(c > z.min[a] + margin && c < z.max[a] - margin)) return false;
    }
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

// === Join
Status join(const Partition& part, std::vector<ZonePrimitives>& prims, const TopologyEdit& e) {
  PrimRef a = nearest_body_prism(prims, e.stroke.front());
  PrimRef b = nearest_body_prism(prims, e.stroke.back());
  if (a.first < 0 || b.first < 0) return Status::error("join: there is no frustum of a body zone to join");
  if (a == b) return Status::error("join: both ends of the stroke select the same part");
  if (a.first != b.first)
    return Status::error(
        "join: the two parts lie in different zones; joining across zones (the zone chain of thesis 6.4) is not "
        "supported");
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
