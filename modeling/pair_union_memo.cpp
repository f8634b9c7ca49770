// Remembered pair unions: see the header.
#include "modeling/pair_union_memo.h"

#include <cstring>

namespace ps {

bool same_solid(const SnappedSolid& a, const SnappedSolid& b) {
  if (a.mesh.vertices.size() != b.mesh.vertices.size() || a.mesh.faces.size() != b.mesh.faces.size() ||
      a.tags != b.tags || a.mesh.faces != b.mesh.faces)
    return false;
  for (std::size_t i = 0; i < a.mesh.vertices.size(); ++i)
    if (a.mesh.vertices[i].x() != b.mesh.vertices[i].x() || a.mesh.vertices[i].y() != b.mesh.vertices[i].y() ||
        a.mesh.vertices[i].z() != b.mesh.vertices[i].z())
      return false;
  return true;
}

bool PairUnionMemo::unites(const SnappedSolid& a, const SnappedSolid& b) {
  for (const Entry& e : entries_)
    if (same_solid(e.a, a) && same_solid(e.b, b)) {
      ++hits_;
      return e.ok;
    }
  const bool ok = static_cast<bool>(union_snapped_solids({a, b}, planes_));
  entries_.push_back(Entry{a, b, ok});
  return ok;
}

namespace {

// FNV-1a over the bytes of the solid and the planes (candidates only: equality decides).
std::uint64_t content_hash(const SnappedSolid& s, const std::vector<Plane>& planes) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  auto mix_double = [&](double d) {
    if (d == 0.0) d = 0.0;  // -0 and +0 compare equal: hash them alike
    mix(&d, sizeof d);
  };
  for (const Vec3& v : s.mesh.vertices) {
    mix_double(v.x());
    mix_double(v.y());
    mix_double(v.z());
  }
  for (const Face& f : s.mesh.faces) mix(f.data(), sizeof(int) * 3);
  for (const auto& t : s.tags) mix(t.data(), sizeof(int) * 3);
  for (const Plane& p : planes) {
    mix_double(p.normal.x());
    mix_double(p.normal.y());
    mix_double(p.normal.z());
    mix_double(p.offset);
  }
  return h;
}

bool same_planes(const std::vector<Plane>& a, const std::vector<Plane>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].normal.x() != b[i].normal.x() || a[i].normal.y() != b[i].normal.y() || a[i].normal.z() != b[i].normal.z() ||
        a[i].offset != b[i].offset)
      return false;
  return true;
}

}  // namespace

int SolidVerdicts::find(const SnappedSolid& s, const std::vector<Plane>& planes) const {
  const std::uint64_t h = content_hash(s, planes);
  for (const Entry& e : entries_)
    if (e.hash == h && same_solid(e.solid, s) && same_planes(e.planes, planes)) return e.verdict ? 1 : 0;
  return -1;
}

void SolidVerdicts::add(const SnappedSolid& s, const std::vector<Plane>& planes, bool verdict) {
  if (capacity_ == 0) return;
  if (entries_.size() >= capacity_) entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(capacity_ / 2 + 1));
  entries_.push_back(Entry{content_hash(s, planes), s, planes, verdict});
}

}  // namespace ps
