#pragma once
// Body of the reconstruction-kernel fuzz target (issue 8, point 1), shared by
// tests/fuzz/recon_kernel_fuzz.cpp (libFuzzer, clang with PLANESKETCH_FUZZ=ON) and
// tests/recon_kernel_fuzz_corpus_test.cpp (every build, over tests/fuzz/corpus/recon_kernel and
// deterministic mutations of it).
//
// Where reconstruct_fuzz (robust_entry_points.h) feeds mostly well-formed star curves, this
// target aims at the numerical edges of the orthogonal path: whole inputs scaled to 1e-30 or
// 1e30 and translated far from the origin, planes given twice (same or flipped normal, same or
// nearly the same offset), non-unit normals, NaN/inf/huge/subnormal coordinates, repeated
// points, collinear curves, raw (self-crossing) point lists, too few points, bad plane indices
// and points slightly off their plane. Inputs stay small (at most 5 planes, 6 curves of 20
// points) so one reconstruction takes well under a second.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "modeling/cross_section.h"
#include "modeling/mesh_queries.h"
#include "modeling/mesh_topology.h"
#include "modeling/reconstruct.h"

namespace ps::fuzz {

// Reads bytes in order; an exhausted input reads as zeros, so every byte string decodes.
struct KernelBytes {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  std::uint8_t next() { return pos < size ? data[pos++] : 0; }
  double unit() { return next() / 255.0; }
  double signed_unit() { return next() / 127.5 - 1.0; }
};

// The values that break arithmetic: NaN, infinities, overflow on squaring, subnormals, -0.
inline double special_value(std::uint8_t b) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  static constexpr std::array<double, 10> table = {
      std::numeric_limits<double>::quiet_NaN(), inf, -inf, 1e30, -1e30, 1e-30, 1e300,
      std::numeric_limits<double>::denorm_min(), -0.0, std::numeric_limits<double>::max()};
  return table[b % table.size()];
}

// Overall scale and translation of a decoded input (the same shape at every magnitude).
inline double kernel_scale(std::uint8_t b) {
  static constexpr std::array<double, 8> table = {1.0, 1e-30, 1e30, 1e-8, 1e8, 1e-150, 1e150, 1.0};
  return table[b % table.size()];
}

inline Vec3 kernel_translation(std::uint8_t b, double scale) {
  switch (b % 4) {
    case 1: return Vec3(3.0, -2.0, 1.0) * scale;    // off-centre by a few sizes
    case 2: return Vec3(1e6, 1e6, -1e6) * scale;    // far: six digits of the mantissa lost
    case 3: return Vec3(1e12, 0.0, 1e12) * scale;   // very far: curves near rounding level
    default: return Vec3::Zero();
  }
}

inline SectionSet decode_kernel_sections(const std::uint8_t* data, std::size_t size) {
  KernelBytes r{data, size};
  SectionSet s;
  const std::uint8_t frame = r.next();
  const double scale = kernel_scale(frame);
  const Vec3 shift = kernel_translation(static_cast<std::uint8_t>(frame >> 3), scale);

  // === Planes: axis normals (sometimes flipped or not of unit length), offsets in [-0.8, 0.8]
  // of the scale, or a copy of the previous plane, or a special value.
  const int np = 1 + r.next() % 5;
  for (int i = 0; i < np; ++i) {
    const std::uint8_t kind = r.next();
    const int axis = (kind & 3) % 3;  // 3 reads as x
    const double sign = (kind & 4) ? -1.0 : 1.0;
    const double length = (kind & 64) ? 2.0 : 1.0;
    Plane p;
    p.normal = sign * length * Vec3::Unit(axis);
    const double local = 0.8 * r.signed_unit();
    double offset = length * (sign * shift[axis] + scale * local);
    switch ((kind >> 3) & 7) {
      case 5:  // the previous plane again (coincident planes)
        if (i > 0) p = s.planes.back(), offset = p.offset;
        break;
      case 6:  // the previous plane with a flipped normal: the same plane given twice
        if (i > 0) p.normal = -s.planes.back().normal, offset = -s.planes.back().offset;
        break;
      case 7:
        offset = special_value(r.next());
        break;
      default:
        break;
    }
    if (kind & 128) offset += 1e-10 * scale;  // nearly coincident with the decoded offset
    p.offset = offset;
    s.planes.push_back(p);
  }

  // === Curves
  const int nc = 1 + r.next() % 6;
  for (int c = 0; c < nc; ++c) {
    CrossSection cs;
    const std::uint8_t pick = r.next();
    cs.plane = pick == 255 ? np : pick == 254 ? -1 : pick % np;
    const Plane& p = s.planes[static_cast<std::size_t>(pick % np)];
    const double len = p.normal.norm();
    const Vec3 n = len > 0 && std::isfinite(len) ? Vec3(p.normal / len) : Vec3::UnitZ();
    Vec3 u, v;
    Plane{n, 0.0}.basis(u, v);
    const double on_plane = std::isfinite(p.offset) ? p.offset / len : 0.0;
    const Vec3 origin = on_plane * n;
    // In-plane centre relative to the shift, so a translated input keeps its shape.
    const Vec3 base = origin + (shift - n.dot(shift) * n);

    const std::uint8_t count = r.next();
    const int points = count >= 240 ? count % 3 : 3 + count % 18;
    const std::uint8_t mode = r.next();
    const double cu = 0.6 * r.signed_unit(), cv = 0.6 * r.signed_unit();
    const double radius = 0.02 + 0.6 * r.unit();
    const double off_plane = (mode & 8) ? 1e-2 * r.signed_unit() * scale : 0.0;
    const int special_at = (mode & 7) == 6 ? r.next() % std::max(points, 1) : -1;
    for (int k = 0; k < points; ++k) {
      double a = 0.0, b = 0.0;
      switch (mode & 7) {
        case 4:  // raw points: usually self-crossing
          a = r.signed_unit();
          b = r.signed_unit();
          break;
        case 7: {  // collinear: zero area
          const double t = r.signed_unit();
          a = cu + t * radius;
          b = cv + 0.5 * t * radius;
          break;
        }
        default: {  // star-shaped around (cu, cv): simple
          const double t = 2.0 * 3.141592653589793 * k / points;
          const double rr = radius * (0.4 + 0.6 * r.unit());
          a = cu + rr * std::cos(t);
          b = cv + rr * std::sin(t);
        }
      }
      Vec3 q = base + scale * (a * u + b * v) + off_plane * n;
      if (k == special_at) q[r.next() % 3] = special_value(r.next());
      cs.points.push_back(q);
      if ((mode & 7) == 5 && (r.next() & 3) == 0) cs.points.push_back(q);  // repeated point
    }
    s.curves.push_back(std::move(cs));
  }
  return s;
}

// The reconstruction contract on the orthogonal path: refuse with a message, or return a
// non-empty mesh with finite vertices that is closed, 2-manifold, consistently and outward
// oriented, with the report's per-vertex flags sized to it; with `no_self_intersection` also
// free of self-intersections (the whole contract of reconstruct.h).
//
// Self-intersections are checked only on request (a whole-mesh test per input slows fuzzing
// down); the libFuzzer target makes them fatal with PLANESKETCH_FUZZ_STRICT=1. The defect that
// motivated this (two vertices a few 1e-17 apart with crossing fans where three primitives of
// one zone meet almost at one point) is repaired since (repair_close_vertices,
// modeling/zone_stitch.h; tests/recon_kernel_fuzz_corpus_test.cpp, KnownSelfIntersection).
inline std::string check_recon_kernel_bytes(const std::uint8_t* data, std::size_t size, bool no_self_intersection = false) {
  const SectionSet s = decode_kernel_sections(data, size);
  ReconstructOptions o;
  o.improve = false;  // one input well under a second; improvement has its own tests
  o.threads = 1;
  ReconstructReport report;
  auto m = reconstruct(s, o, &report);
  if (!m) return m.message().empty() ? "refusal without a message" : "";
  if (m->faces.empty()) return "ok status with an empty mesh";
  for (const auto& q : m->vertices)
    if (!q.allFinite()) return "ok status with a non-finite vertex";
  for (const auto& f : m->faces)
    for (int i : f)
      if (i < 0 || static_cast<std::size_t>(i) >= m->vertices.size()) return "ok status with a face index out of range";
  if (report.curve_vertex.size() != m->vertices.size()) return "report curve flags do not match the mesh";
  // The checks run on an exactly rescaled copy: multiplying by a power of two changes no
  // orientation or intersection predicate, and keeps the signed volume (cubic in the size)
  // representable for inputs at 1e-150 or 1e150, where it would underflow or overflow.
  TriMesh unit = *m;
  const double diag = bounding_box(unit.vertices).diagonal();
  if (std::isfinite(diag) && diag > 0)
    for (auto& q : unit.vertices) q *= std::ldexp(1.0, -std::ilogb(diag));
  const MeshTopology t = mesh_topology(unit);
  if (!t.closed || !t.manifold() || !t.consistently_oriented || !(t.signed_volume > 0.0))
    return "ok status but the result is not a closed, outward 2-manifold: " + t.problem;
  if (no_self_intersection && does_self_intersect(unit)) return "ok status but the surface intersects itself";
  return {};
}

}  // namespace ps::fuzz
