#pragma once
// Analytic cross sections for the reconstruction tests and benchmark: ellipses on axis planes
// whose crossing points with the other section planes are inserted as exact, shared vertices,
// so stroke rule 4 holds by construction.
#include <algorithm>
#include <cmath>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/reconstruct.h"

namespace ps::testing {

// Reconstruction without the improvement (4.5.1): the initial mesh only, fast.
inline ReconstructOptions no_improve() {
  ReconstructOptions o;
  o.improve = false;
  return o;
}

// An ellipse on the axis plane x_k = offset, centre (cu, cv) in the plane's (u, v) coordinates
// (u = axis k+1, v = axis k+2), radii (ru, rv), n uniform samples plus `exact` points (3D points
// on the ellipse, inserted at their angle and used verbatim).
inline std::vector<Vec3> ellipse(int k, double offset, double cu, double cv, double ru, double rv, int n,
                                 const std::vector<Vec3>& exact = {}) {
  const int iu = (k + 1) % 3, iv = (k + 2) % 3;
  std::vector<std::pair<double, Vec3>> pts;
  auto angle_of = [&](const Vec3& p) {
    double a = std::atan2((p[iv] - cv) / rv, (p[iu] - cu) / ru);
    if (a < 0) a += 2 * M_PI;
    return a;
  };
  for (const auto& e : exact) pts.emplace_back(angle_of(e), e);
  // A phase per plane keeps the samples of different curves out of exact alignment (uniform
  // samples of similar ellipses line up and make the primitives' walls meet in degenerate ways
  // that no drawn input has).
  const double phase = 0.3719 + 0.5113 * k + 0.7727 * offset + 0.2311 * cu - 0.1717 * cv;
  for (int i = 0; i < n; ++i) {
    const double a = std::fmod(phase + 2 * M_PI * i / n, 2 * M_PI);
    bool near = false;
    for (const auto& e : exact) {
      double d = std::abs(angle_of(e) - a);
      d = std::min(d, 2 * M_PI - d);
      if (d < 0.3 * 2 * M_PI / n) near = true;
    }
    if (near) continue;
    Vec3 p;
    p[k] = offset;
    p[iu] = cu + ru * std::cos(a);
    p[iv] = cv + rv * std::sin(a);
    pts.emplace_back(a, p);
  }
  std::sort(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Vec3> out;
  for (const auto& [a, p] : pts) out.push_back(p);
  return out;
}

struct SliceSpec {
  int axis;
  double offset;
};

// Slices of the ellipsoid sum (x_i - c_i)^2 / r_i^2 = 1 by the given axis planes; every pair of
// slices shares its crossing points exactly.
inline SectionSet ellipsoid_slices(const Vec3& c, const Vec3& r, const std::vector<SliceSpec>& slices, int n = 48) {
  SectionSet s;
  for (const auto& sl : slices) {
    const int k = sl.axis;
    const double t = 1.0 - std::pow((sl.offset - c[k]) / r[k], 2);
    if (t <= 0) continue;
    const int iu = (k + 1) % 3, iv = (k + 2) % 3;
    std::vector<Vec3> exact;
    for (const auto& o : slices) {
      if (o.axis == k) continue;
      const int j = o.axis;
      const int free = 3 - k - j;
      const double rest = 1.0 - std::pow((sl.offset - c[k]) / r[k], 2) - std::pow((o.offset - c[j]) / r[j], 2);
      if (rest <= 1e-9) continue;
      for (double sign : {-1.0, 1.0}) {
        Vec3 p;
        p[k] = sl.offset;
        p[j] = o.offset;
        p[free] = c[free] + sign * r[free] * std::sqrt(rest);
        exact.push_back(p);
      }
    }
    Plane pl;
    pl.normal = Vec3::Unit(k);
    pl.offset = sl.offset;
    s.planes.push_back(pl);
    s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1,
                                    ellipse(k, sl.offset, c[iu], c[iv], r[iu] * std::sqrt(t), r[iv] * std::sqrt(t), n, exact)});
  }
  return s;
}

// A circle on an axis plane, as its own plane.
inline void add_circle(SectionSet& s, int k, double offset, double cu, double cv, double radius, int n = 40) {
  Plane pl;
  pl.normal = Vec3::Unit(k);
  pl.offset = offset;
  s.planes.push_back(pl);
  s.curves.push_back(CrossSection{static_cast<int>(s.planes.size()) - 1, ellipse(k, offset, cu, cv, radius, radius, n)});
}

// Slices of the torus around the z axis (major radius R, minor radius r) by z = 0 (two circles,
// a ring), x = 0 and y = 0 (two circles each); crossing points exact.
inline SectionSet torus_slices(double R, double r, int n = 48) {
  SectionSet s;
  auto plane = [&](int k) {
    Plane pl;
    pl.normal = Vec3::Unit(k);
    pl.offset = 0.0;
    s.planes.push_back(pl);
    return static_cast<int>(s.planes.size()) - 1;
  };
  const int pz = plane(2), px = plane(0), py = plane(1);
  // z = 0: circles of radius R +- r in (x, y); crossings with x = 0 and y = 0.
  for (double rad : {R - r, R + r}) {
    std::vector<Vec3> exact{Vec3(rad, 0, 0), Vec3(-rad, 0, 0), Vec3(0, rad, 0), Vec3(0, -rad, 0)};
    s.curves.push_back(CrossSection{pz, ellipse(2, 0.0, 0.0, 0.0, rad, rad, n, exact)});
  }
  // x = 0: circles centred at y = +-R in (y, z); crossings with z = 0.
  for (double cy : {-R, R}) {
    std::vector<Vec3> exact{Vec3(0, cy - r, 0), Vec3(0, cy + r, 0)};
    s.curves.push_back(CrossSection{px, ellipse(0, 0.0, cy, 0.0, r, r, n, exact)});
  }
  // y = 0: circles centred at x = +-R in (z, x) coordinates (u = z, v = x).
  for (double cx : {-R, R}) {
    std::vector<Vec3> exact{Vec3(cx - r, 0, 0), Vec3(cx + r, 0, 0)};
    s.curves.push_back(CrossSection{py, ellipse(1, 0.0, 0.0, cx, r, r, n, exact)});
  }
  return s;
}

// s with every plane and point turned by r and moved by t.
inline SectionSet moved_sections(const SectionSet& s, const Eigen::Matrix3d& r, const Vec3& t) {
  SectionSet out = s;
  for (auto& p : out.planes) {
    p.normal = r * p.normal;
    p.offset = p.normal.dot(t) + p.offset;
  }
  for (auto& c : out.curves)
    for (auto& p : c.points) p = r * p + t;
  return out;
}

}  // namespace ps::testing
