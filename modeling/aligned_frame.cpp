#include "modeling/aligned_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include <Eigen/Geometry>

namespace ps {
namespace {

std::size_t uz(int i) { return static_cast<std::size_t>(i); }

// The sign-free key of a direction: the normal with its largest component made positive.
Vec3 sign_free(const Vec3& n) {
  Eigen::Index k = 0;
  n.cwiseAbs().maxCoeff(&k);
  return n[k] < 0.0 ? Vec3(-n) : n;
}

bool is_coordinate_axis(const Vec3& n) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(n[k]) == 1.0) return true;
  return false;
}

}  // namespace

std::optional<AlignedFrame> aligned_frame(const SectionSet& s) {
  // === Direction classes of the planes that hold a curve, from the sorted sign-free normals:
  // the first of a class (its smallest key) stands for it, so the classes depend on the set of
  // directions only.
  std::vector<char> used(s.planes.size(), 0);
  for (const auto& c : s.curves)
    if (c.plane >= 0 && uz(c.plane) < s.planes.size()) used[uz(c.plane)] = 1;
  std::vector<Vec3> normals;
  for (std::size_t i = 0; i < s.planes.size(); ++i)
    if (used[i]) {
      const Vec3& n = s.planes[i].normal;
      if (!n.allFinite() || !(std::abs(n.norm() - 1.0) < 1e-12)) return std::nullopt;
      normals.push_back(sign_free(n));
    }
  if (normals.empty()) return std::nullopt;
  std::sort(normals.begin(), normals.end(), [](const Vec3& a, const Vec3& b) {
    return std::make_tuple(a.x(), a.y(), a.z()) < std::make_tuple(b.x(), b.y(), b.z());
  });
  std::vector<Vec3> reps;
  for (const Vec3& n : normals) {
    bool found = false;
    for (const Vec3& r : reps)
      if (n.cross(r).norm() <= kAlignedDirectionTolerance) {
        found = true;
        break;
      }
    if (!found) {
      if (reps.size() == 3) return std::nullopt;
      reps.push_back(n);
    }
  }
  for (std::size_t i = 0; i < reps.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (std::abs(reps[i].dot(reps[j])) > kAlignedDirectionTolerance) return std::nullopt;
  if (std::all_of(reps.begin(), reps.end(), is_coordinate_axis)) return std::nullopt;

  // === Axes. Each class in turn takes the free coordinate axis its normal is nearest to (the
  // frame stays close to the world's); Gram-Schmidt makes the rows exactly orthonormal, and the
  // last row completes a right-handed frame.
  std::array<int, 3> axis_of{-1, -1, -1};  // per class
  std::array<bool, 3> taken{false, false, false};
  for (std::size_t c = 0; c < reps.size(); ++c) {
    int best = -1;
    for (int k = 0; k < 3; ++k)
      if (!taken[uz(k)] && (best < 0 || std::abs(reps[c][k]) > std::abs(reps[c][best]))) best = k;
    axis_of[c] = best;
    taken[uz(best)] = true;
  }
  std::array<Vec3, 3> row;
  std::array<bool, 3> set{false, false, false};
  // First class: its normal, signed so that its own axis component is positive.
  {
    const int k = axis_of[0];
    row[uz(k)] = reps[0][k] < 0.0 ? Vec3(-reps[0]) : reps[0];
    set[uz(k)] = true;
  }
  // Second row: the second class, or (one class only) the first free world axis, made
  // orthogonal to the first row.
  {
    int k = -1;
    Vec3 d;
    if (reps.size() >= 2) {
      k = axis_of[1];
      d = reps[1];
    } else {
      for (int a = 0; a < 3 && k < 0; ++a)
        if (!set[uz(a)]) k = a;
      d = Vec3::Unit(k);
    }
    const Vec3& first = row[uz(axis_of[0])];
    Vec3 e = d - d.dot(first) * first;
    if (!(e.norm() > 0.5)) return std::nullopt;  // cannot happen for the tolerances above
    e.normalize();
    if (e[k] < 0.0) e = -e;
    row[uz(k)] = e;
    set[uz(k)] = true;
  }
  int last = 0;
  while (set[uz(last)]) ++last;
  row[uz(last)] = row[uz((last + 1) % 3)].cross(row[uz((last + 2) % 3)]);
  if (reps.size() == 3 && !(std::abs(row[uz(last)].dot(reps[2])) >= 1.0 - 1e-6)) return std::nullopt;

  AlignedFrame f;
  for (int k = 0; k < 3; ++k) f.rotation.row(k) = row[uz(k)].transpose();
  return f;
}

SectionSet to_aligned_frame(const SectionSet& s, const AlignedFrame& frame) {
  SectionSet out;
  out.units = s.units;
  std::vector<int> index(s.planes.size(), -1);
  std::vector<int> axis;
  for (const auto& c : s.curves) {
    if (index[uz(c.plane)] >= 0) continue;
    const Plane& p = s.planes[uz(c.plane)];
    const Vec3 r = frame.to_frame(p.normal);
    Eigen::Index k = 0;
    r.cwiseAbs().maxCoeff(&k);
    Plane q;
    q.normal = Vec3::Unit(k);
    q.offset = r[k] < 0.0 ? -p.offset : p.offset;
    index[uz(c.plane)] = static_cast<int>(out.planes.size());
    out.planes.push_back(q);
    axis.push_back(static_cast<int>(k));
  }
  out.curves.reserve(s.curves.size());
  for (const auto& c : s.curves) {
    CrossSection d;
    d.plane = index[uz(c.plane)];
    const int k = axis[uz(d.plane)];
    const double offset = out.planes[uz(d.plane)].offset;
    d.points.reserve(c.points.size());
    for (const Vec3& p : c.points) {
      Vec3 q = frame.to_frame(p);
      q[k] = offset;
      d.points.push_back(q);
    }
    out.curves.push_back(std::move(d));
  }
  return out;
}

}  // namespace ps
