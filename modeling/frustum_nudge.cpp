#include "modeling/frustum_nudge.h"

#include <algorithm>
#include <set>

namespace ps {
namespace {

// The plane that every bottom vertex lies on (the frustum's face), or -1.
int bottom_plane(const SnappedSolid& s) {
  const std::size_t half = s.mesh.vertices.size() / 2;
  if (half == 0 || s.tags.size() != s.mesh.vertices.size()) return -1;
  std::set<int> common(s.tags[0].begin(), s.tags[0].end());
  for (std::size_t i = 1; i < half; ++i) {
    std::set<int> here(s.tags[i].begin(), s.tags[i].end()), both;
    std::set_intersection(common.begin(), common.end(), here.begin(), here.end(), std::inserter(both, both.begin()));
    common = std::move(both);
  }
  common.erase(-1);
  return common.size() == 1 ? *common.begin() : -1;
}

std::array<int, 3> sorted_tags(std::array<int, 3> t) {
  std::sort(t.begin(), t.end());
  return t;
}

// Bottom vertices of `a` that are also bottom vertices of `b`.
std::vector<std::size_t> shared_bottoms(const SnappedSolid& a, const SnappedSolid& b, int pb, double tol) {
  std::vector<std::size_t> out;
  const std::size_t ha = a.mesh.vertices.size() / 2, hb = b.mesh.vertices.size() / 2;
  for (std::size_t i = 0; i < ha; ++i) {
    const auto ti = sorted_tags(a.tags[i]);
    if (std::find(ti.begin(), ti.end(), pb) == ti.end()) continue;  // not on the other face
    for (std::size_t j = 0; j < hb; ++j)
      if (sorted_tags(b.tags[j]) == ti && (a.mesh.vertices[i] - b.mesh.vertices[j]).norm() <= tol) {
        out.push_back(i);
        break;
      }
  }
  return out;
}

// Moves the free tops above `bottoms` a fraction of their distance towards `plane`.
bool nudge(SnappedSolid& s, const std::vector<std::size_t>& bottoms, const Plane& plane, double fraction) {
  const std::size_t half = s.mesh.vertices.size() / 2;
  bool moved = false;
  for (std::size_t i : bottoms) {
    const std::size_t top = i + half;
    if (s.tags[top][0] >= 0 || s.tags[top][1] >= 0 || s.tags[top][2] >= 0) continue;  // kept on a face
    Vec3& p = s.mesh.vertices[top];
    p -= fraction * plane.signed_distance(p) * plane.normal;
    moved = true;
  }
  return moved;
}

}  // namespace

std::vector<SnappedSolid> with_overlap_nudges(const std::vector<SnappedSolid>& frusta, const std::vector<Plane>& planes,
                                              int* nudged, PairUnionMemo* memo) {
  std::vector<SnappedSolid> out = frusta;
  int count = 0;
  Box3 box;
  for (const auto& f : frusta)
    for (const auto& v : f.mesh.vertices) box.extend(v);
  const double tol = 1e-9 * box.diagonal();
  std::vector<int> face(frusta.size());
  for (std::size_t i = 0; i < frusta.size(); ++i) face[i] = bottom_plane(frusta[i]);
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (std::size_t j = i + 1; j < out.size(); ++j) {
      const int pi = face[i], pj = face[j];
      if (pi < 0 || pj < 0 || pi == pj || pi >= static_cast<int>(planes.size()) || pj >= static_cast<int>(planes.size()))
        continue;
      const auto si = shared_bottoms(out[i], out[j], pj, tol);
      const auto sj = shared_bottoms(out[j], out[i], pi, tol);
      if (si.empty() || sj.empty()) continue;
      const bool fine = memo ? memo->unites(out[i], out[j]) : static_cast<bool>(union_snapped_solids({out[i], out[j]}, planes));
      if (fine) continue;  // this pair is fine
      for (double fraction : {0.02, 0.05}) {
        SnappedSolid a = out[i], b = out[j];
        const bool ma = nudge(a, si, planes[static_cast<std::size_t>(pj)], fraction);
        const bool mb = nudge(b, sj, planes[static_cast<std::size_t>(pi)], fraction);
        if (!ma && !mb) break;
        if (union_snapped_solids({a, b}, planes)) {
          out[i] = std::move(a);
          out[j] = std::move(b);
          ++count;
          break;
        }
      }
    }
  }
  if (nudged) *nudged = count;
  return out;
}

}  // namespace ps
