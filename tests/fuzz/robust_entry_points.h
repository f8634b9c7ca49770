#pragma once
// Bodies of the deformation-spec and reconstruction fuzz targets (issue 8, point 1), shared by
// tests/fuzz/{deform_spec,reconstruct}_fuzz.cpp (libFuzzer, clang with PLANESKETCH_FUZZ=ON) and
// tests/robust_fuzz_corpus_test.cpp (every build, including ASan+UBSan, over seeds and
// deterministic mutations). Each returns an empty string when the input was handled correctly,
// or what went wrong.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/deform_spec.h"
#include "modeling/edge_graph_deformer.h"
#include "modeling/mesh_queries.h"
#include "modeling/reconstruct.h"

namespace ps::fuzz {

// A regular octahedron: the smallest closed mesh on which every spec field has a meaning.
inline TriMesh fuzz_octahedron() {
  TriMesh m;
  m.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// The spec reader's contract: a failure carries a message naming the source; an accepted spec
// that passes the mesh check drives the solver, whose result keeps every vertex finite and
// puts every handle on its target.
inline std::string check_deform_spec_bytes(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto spec = parse_deform_spec(text, "fuzz.json");
  if (!spec) return spec.message().rfind("fuzz.json", 0) == 0 ? "" : "error does not name the source: " + spec.message();
  const TriMesh mesh = fuzz_octahedron();
  if (auto st = check_deform_spec(*spec, mesh.vertices.size(), "fuzz.json"); !st)
    return st.message().rfind("fuzz.json", 0) == 0 ? "" : "error does not name the source: " + st.message();
  const DeformParameters p = deform_parameters(*spec, mesh.vertices.size());
  if (!p.vertex_lambda.empty() && p.vertex_lambda.size() != mesh.vertices.size()) return "per-vertex lambda of the wrong size";
  // The solver only on small requests, so one input stays fast.
  if (spec->max_iterations > 50) return {};
  auto out = deform_mesh(mesh, spec->roi, spec->handles, p);
  if (!out) return out.message().empty() ? "solver error without a message" : "";
  if (out->vertices.size() != mesh.vertices.size() || out->faces != mesh.faces) return "solver changed the connectivity";
  for (const auto& v : out->vertices)
    if (!v.allFinite()) return "solver produced a non-finite vertex";
  for (const auto& h : spec->handles) {
    const Vec3 d = out->vertices[static_cast<std::size_t>(h.vertex)] - h.position;
    if (!(d.norm() <= 1e-6 * (1.0 + h.position.norm()))) return "handle " + std::to_string(h.vertex) + " missed its target";
  }
  return {};
}

// === Reconstruction from bytes
// Decodes bytes into a small section set on up to four planes (mostly axis planes, sometimes an
// oblique one): each curve is star-shaped around a centre (simple, usually valid) or, when its
// mode byte says so, raw points from the bytes (usually self-crossing: must be refused).
// A byte of 255 where a coordinate is read injects a NaN. Exhausted input reads as zeros.
struct ByteReader {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  std::uint8_t next() { return pos < size ? data[pos++] : 0; }
  double unit() { return next() / 255.0; }
  double coord(double scale) {
    const std::uint8_t b = next();
    if (b == 255) return std::numeric_limits<double>::quiet_NaN();
    return (b / 127.0 - 1.0) * scale;
  }
};

inline SectionSet decode_sections(const std::uint8_t* data, std::size_t size) {
  ByteReader r{data, size};
  SectionSet s;
  const int np = 1 + r.next() % 4;
  for (int i = 0; i < np; ++i) {
    const std::uint8_t kind = r.next();
    Plane p;
    if (kind % 8 == 7) {  // oblique
      Vec3 n(r.coord(1), r.coord(1), r.coord(1) + 0.01);
      p.normal = n.allFinite() && n.norm() > 1e-3 ? Vec3(n.normalized()) : Vec3(0, 0, 1);
    } else {
      p.normal = Vec3::Unit(kind % 3);
    }
    p.offset = r.coord(0.8);
    if (!std::isfinite(p.offset)) p.offset = 0.0;
    s.planes.push_back(p);
  }
  const int nc = 1 + r.next() % 5;
  for (int c = 0; c < nc; ++c) {
    CrossSection cs;
    cs.plane = r.next() % np;
    const Plane& p = s.planes[static_cast<std::size_t>(cs.plane)];
    Vec3 u, v;
    p.basis(u, v);
    const int n = 3 + r.next() % 14;
    const bool raw = r.next() % 6 == 5;
    const double cu = r.coord(0.6), cv = r.coord(0.6), radius = 0.05 + 0.6 * r.unit();
    for (int k = 0; k < n; ++k) {
      double a, b;
      if (raw) {
        a = r.coord(1.0);
        b = r.coord(1.0);
      } else {
        const double t = 2.0 * 3.141592653589793 * k / n;
        const double rr = radius * (0.5 + 0.5 * r.unit());
        a = cu + rr * std::cos(t);
        b = cv + rr * std::sin(t);
      }
      cs.points.push_back(p.offset * p.normal + a * u + b * v);
    }
    s.curves.push_back(std::move(cs));
  }
  return s;
}

// The reconstruction contract: refuse with a message, or return a closed, 2-manifold,
// outward-oriented surface without self-intersections.
inline std::string check_reconstruct_bytes(const std::uint8_t* data, std::size_t size) {
  const SectionSet s = decode_sections(data, size);
  ReconstructOptions o;
  o.improve = false;  // keeps one input well under a second; improvement has its own tests
  o.threads = 1;
  auto m = reconstruct(s, o);
  if (!m) return m.message().empty() ? "refusal without a message" : "";
  const auto g = check_guarantees(*m);
  if (!g.valid()) return "result breaks a guarantee: " + g.problem();
  return {};
}

}  // namespace ps::fuzz
