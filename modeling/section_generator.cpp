// Random cross sections of implicit unions of ellipsoids and tori (see section_generator.h).
#include "modeling/section_generator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "modeling/mesh_slicer.h"
#include "modeling/section_validate.h"

namespace ps {
namespace {

double area2(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return a;
}

std::vector<Vec3> resample_closed(const std::vector<Vec3>& pts, std::size_t count) {
  const std::size_t n = pts.size();
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + (pts[(i + 1) % n] - pts[i]).norm();
  const double total = cum[n];
  std::vector<Vec3> out;
  std::size_t seg = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double s = total * static_cast<double>(k) / static_cast<double>(count);
    while (seg + 1 < n && cum[seg + 1] <= s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double t = len > 0 ? (s - cum[seg]) / len : 0.0;
    out.push_back((1 - t) * pts[seg] + t * pts[(seg + 1) % n]);
  }
  return out;
}

Eigen::Matrix3d random_rotation(SeededRandom& rng) {
  // Random axis, random angle (not Haar-uniform, which these tests do not need).
  const Vec3 axis = rng.unit_vector();
  const double angle = rng.uniform(0.0, 2.0 * M_PI);
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// Newton steps within the plane towards the zero set (numerical in-plane gradient), each step
// at most half a cell; the point is left where it is if the steps do not reduce |f|.
Vec3 snap_to_surface(const ImplicitUnion& shape, const Plane& pl, Vec3 q, double cell) {
  Vec3 u, v;
  pl.basis(u, v);
  const double h = 1e-7 * cell / 0.01;
  double f = shape.value(q);
  for (int it = 0; it < 6 && std::abs(f) > 1e-12 * cell; ++it) {
    const Vec2 g((shape.value(q + h * u) - shape.value(q - h * u)) / (2 * h),
                 (shape.value(q + h * v) - shape.value(q - h * v)) / (2 * h));
    const double g2 = g.squaredNorm();
    if (!(g2 > 1e-12)) break;
    Vec2 step = -f * g / g2;
    if (step.norm() > 0.5 * cell) step *= 0.5 * cell / step.norm();
    const Vec3 next = q + step.x() * u + step.y() * v;
    const double fn = shape.value(next);
    if (!(std::abs(fn) < std::abs(f))) break;
    q = next;
    f = fn;
  }
  return q;
}

}  // namespace

// === Implicit union
double ImplicitUnion::value(const Vec3& p) const {
  double f = std::numeric_limits<double>::infinity();
  for (const auto& e : ellipsoids) {
    const Vec3 q = e.rotation.transpose() * (p - e.center);
    const double r = q.cwiseQuotient(e.radii).norm();
    f = std::min(f, (r - 1.0) * e.radii.minCoeff());
  }
  for (const auto& t : tori) {
    const Vec3 q = t.rotation.transpose() * (p - t.center);
    const double rho = std::hypot(q.x(), q.y());
    f = std::min(f, std::hypot(rho - t.major, q.z()) - t.minor);
  }
  return f;
}

Box3 ImplicitUnion::bounds() const {
  Box3 b;
  for (const auto& e : ellipsoids) {
    const double r = e.radii.maxCoeff();
    b.extend(e.center - Vec3::Constant(r));
    b.extend(e.center + Vec3::Constant(r));
  }
  for (const auto& t : tori) {
    const double r = t.major + t.minor;
    b.extend(t.center - Vec3::Constant(r));
    b.extend(t.center + Vec3::Constant(r));
  }
  return b;
}

double ImplicitUnion::smallest_feature() const {
  double s = std::numeric_limits<double>::infinity();
  for (const auto& e : ellipsoids) s = std::min(s, e.radii.minCoeff());
  for (const auto& t : tori) s = std::min(s, t.minor);
  return s;
}

ImplicitUnion random_union(std::uint64_t seed, int min_primitives, int max_primitives, double torus_probability) {
  SeededRandom rng(seed);
  ImplicitUnion u;
  const int n = rng.integer(std::max(1, min_primitives), std::max(min_primitives, max_primitives));
  Vec3 prev_center = Vec3::Zero();
  double prev_size = 0;
  for (int i = 0; i < n; ++i) {
    // Each primitive overlaps the previous one, so the union is usually connected.
    const Vec3 c = i == 0 ? Vec3::Zero() : Vec3(prev_center + rng.unit_vector() * rng.uniform(0.4, 0.8) * prev_size);
    if (rng.uniform() < torus_probability) {
      Torus t;
      t.center = c;
      t.rotation = random_rotation(rng);
      t.major = rng.uniform(0.6, 1.0);
      t.minor = t.major * rng.uniform(0.25, 0.45);
      u.tori.push_back(t);
      prev_size = t.major + t.minor;
    } else {
      Ellipsoid e;
      e.center = c;
      e.rotation = random_rotation(rng);
      e.radii = Vec3(rng.uniform(0.4, 1.0), rng.uniform(0.4, 1.0), rng.uniform(0.4, 1.0));
      u.ellipsoids.push_back(e);
      prev_size = e.radii.maxCoeff();
    }
    prev_center = c;
  }
  return u;
}

// === Marching squares
std::vector<std::vector<Vec3>> contour_plane(const ImplicitUnion& shape, const Plane& plane, double cell) {
  std::vector<std::vector<Vec3>> loops;
  const Box3 b = shape.bounds();
  if (b.empty() || !(cell > 0)) return loops;
  Vec3 u, v;
  plane.basis(u, v);
  const Vec3 origin = plane.normal * plane.offset;
  // 2D extent: the box's corners projected, padded by two cells so the grid border is outside.
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p((k & 1) ? b.max.x() : b.min.x(), (k & 2) ? b.max.y() : b.min.y(), (k & 4) ? b.max.z() : b.min.z());
    x0 = std::min(x0, p.dot(u)), x1 = std::max(x1, p.dot(u));
    y0 = std::min(y0, p.dot(v)), y1 = std::max(y1, p.dot(v));
  }
  x0 -= 2 * cell, y0 -= 2 * cell, x1 += 2 * cell, y1 += 2 * cell;
  const std::size_t nx = static_cast<std::size_t>(std::ceil((x1 - x0) / cell));
  const std::size_t ny = static_cast<std::size_t>(std::ceil((y1 - y0) / cell));
  if (nx * ny > 16'000'000) return loops;
  auto pos = [&](double x, double y) { return Vec3(origin + u * x + v * y); };
  auto node = [&](std::size_t i, std::size_t j) { return j * (nx + 1) + i; };
  std::vector<double> f((nx + 1) * (ny + 1));
  for (std::size_t j = 0; j <= ny; ++j)
    for (std::size_t i = 0; i <= nx; ++i) {
      double val = shape.value(pos(x0 + static_cast<double>(i) * cell, y0 + static_cast<double>(j) * cell));
      if (val == 0.0) val = std::numeric_limits<double>::min();  // exact zeros count as outside
      f[node(i, j)] = val;
    }
  // Edge keys: horizontal edge from node (i,j) to (i+1,j) is 2*node, vertical (i,j)-(i,j+1) 2*node+1.
  auto crossing = [&](std::size_t key) {
    const std::size_t nd = key / 2;
    const std::size_t i = nd % (nx + 1), j = nd / (nx + 1);
    const std::size_t other = (key % 2 == 0) ? node(i + 1, j) : node(i, j + 1);
    const double fa = f[nd], fb = f[other];
    const double t = fa / (fa - fb);
    const double x = x0 + (static_cast<double>(i) + (key % 2 == 0 ? t : 0.0)) * cell;
    const double y = y0 + (static_cast<double>(j) + (key % 2 == 1 ? t : 0.0)) * cell;
    return pos(x, y);
  };
  // Segments with the inside on their left: walking each cell's border counter-clockwise,
  // a segment runs from an inside->outside crossing to an outside->inside crossing.
  std::unordered_map<std::size_t, std::size_t> next;  // start edge key -> end edge key
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const std::array<std::size_t, 4> corner = {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
      const std::array<std::size_t, 4> edge = {2 * node(i, j), 2 * node(i + 1, j) + 1, 2 * node(i, j + 1), 2 * node(i, j) + 1};
      std::array<std::pair<std::size_t, bool>, 4> cross{};  // (edge key, is start)
      std::size_t nc = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        const bool a_in = f[corner[k]] < 0, b_in = f[corner[(k + 1) % 4]] < 0;
        if (a_in != b_in) cross[nc++] = {edge[k], a_in};
      }
      if (nc == 2) {
        const auto& s = cross[0].second ? cross[0] : cross[1];
        const auto& e = cross[0].second ? cross[1] : cross[0];
        next[s.first] = e.first;
      } else if (nc == 4) {
        const double centre = shape.value(pos(x0 + (static_cast<double>(i) + 0.5) * cell, y0 + (static_cast<double>(j) + 0.5) * cell));
        const bool joined = centre < 0;  // inside corners connect through the centre
        for (std::size_t k = 0; k < 4; ++k) {
          if (!cross[k].second) continue;
          const std::size_t partner = joined ? (k + 1) % 4 : (k + 3) % 4;
          next[cross[k].first] = cross[partner].first;
        }
      }
    }
  // Chain into loops, in a deterministic order (smallest start key first).
  std::vector<std::size_t> starts;
  starts.reserve(next.size());
  for (const auto& kv : next) starts.push_back(kv.first);
  std::sort(starts.begin(), starts.end());
  std::unordered_map<std::size_t, bool> used;
  for (std::size_t s : starts) {
    if (used[s]) continue;
    std::vector<Vec3> loop;
    std::size_t k = s;
    bool closed = false;
    while (true) {
      used[k] = true;
      loop.push_back(crossing(k));
      const auto it = next.find(k);
      if (it == next.end()) break;
      k = it->second;
      if (k == s) {
        closed = true;
        break;
      }
      if (used[k]) break;
    }
    if (closed && loop.size() >= 3) {
      for (auto& q : loop) q = plane.project(q);
      loops.push_back(std::move(loop));
    }
  }
  return loops;
}

// === Generator
GeneratedSections generate_sections(const GeneratorOptions& options) {
  GeneratedSections out;
  out.shape = random_union(options.seed, options.min_primitives, options.max_primitives, options.torus_probability);
  SeededRandom rng(options.seed * 0x9E3779B97F4A7C15ull + 17);
  const Box3 b = out.shape.bounds();
  const double cell = out.shape.smallest_feature() / 8.0;
  const double diag = b.diagonal();
  const std::size_t lo = static_cast<std::size_t>(std::max(3, options.min_curve_points));
  const std::size_t hi = static_cast<std::size_t>(std::max(options.min_curve_points, options.max_curve_points));

  auto try_plane = [&](const Plane& pl) {
    for (const auto& q : out.sections.planes)
      if (1.0 - std::abs(q.normal.dot(pl.normal)) < 1e-6 &&
          std::abs(q.offset - (q.normal.dot(pl.normal) > 0 ? pl.offset : -pl.offset)) < 0.05 * diag)
        return false;  // too close to a plane we have
    auto loops = contour_plane(out.shape, pl, cell);
    Vec3 u, v;
    pl.basis(u, v);
    std::vector<std::vector<Vec3>> curves;
    std::vector<std::vector<Vec2>> flat;
    for (auto& loop : loops) {
      double len = 0;
      for (std::size_t k = 0; k < loop.size(); ++k) len += (loop[(k + 1) % loop.size()] - loop[k]).norm();
      std::vector<Vec2> raw;
      for (const auto& q : loop) raw.emplace_back(q.dot(u), q.dot(v));
      // Loops of a few cells are discretisation noise near tangency: skip them.
      if (loop.size() < 8 || std::abs(area2(raw)) * 0.5 < 4 * cell * cell) continue;
      const auto count = std::clamp(static_cast<std::size_t>(std::lround(len / cell)), lo, hi);
      auto c = resample_closed(loop, count);
      for (auto& q : c) q = pl.project(snap_to_surface(out.shape, pl, q, cell));
      std::vector<Vec2> f;
      for (const auto& q : c) f.emplace_back(q.dot(u), q.dot(v));
      flat.push_back(std::move(f));
      curves.push_back(std::move(c));
    }
    if (curves.empty() || !polygons_are_simple(flat)) return false;
    const int id = static_cast<int>(out.sections.planes.size());
    SectionSet trial = out.sections;
    trial.planes.push_back(pl);
    for (auto& c : curves) trial.curves.push_back(CrossSection{id, std::move(c)});
    // Rule 4 across planes, as the reconstruction sews it: near a tangency one plane's small
    // loop is dropped above (or cut by a chord) while another plane's curve still crosses the
    // shared line there, and the sewing finds a crossing without a partner. Such a plane would
    // make an input that breaks rule 4, so it is refused like a self-crossing one.
    auto checked = validate_sections(trial);
    if (!checked) return false;
    SectionSet sewn = checked->sections;
    std::vector<std::string> warnings;
    sew_crossings(sewn, kSewTolerance * checked->diagonal, &warnings);
    for (const auto& w : warnings)
      if (w.find("(rule 4)") != std::string::npos) return false;
    out.sections = std::move(trial);
    return true;
  };

  auto interior = [&](int k) { return b.min[k] + (b.max[k] - b.min[k]) * rng.uniform(0.15, 0.85); };
  for (int want = options.orthogonal_planes, attempts = 0; want > 0 && attempts < 50 * options.orthogonal_planes; ++attempts) {
    Plane pl;
    const int axis = rng.integer(0, 2);
    pl.normal = Vec3::Unit(axis);
    pl.offset = interior(axis);
    if (try_plane(pl)) --want;
  }
  for (int want = options.oblique_planes, attempts = 0; want > 0 && attempts < 50 * options.oblique_planes; ++attempts) {
    Plane pl;
    pl.normal = rng.unit_vector();
    if (pl.axis() >= 0) continue;
    const Vec3 q(interior(0), interior(1), interior(2));
    pl.offset = pl.normal.dot(q);
    if (try_plane(pl)) --want;
  }
  return out;
}

}  // namespace ps
