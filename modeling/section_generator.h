#pragma once
// Random cross-section inputs for stress tests: slice a random union of ellipsoids and tori,
// given as an implicit function, with random orthogonal and oblique planes.
//
// Each plane's curves come from marching squares on a grid in the plane (orthonormal basis
// u, v of Plane::basis, so u x v = normal) with the saddle cases decided by the cell-centre
// value, chained into closed loops and resampled by arc length to 40..200 points per curve.
// Loops are oriented consistently: counter-clockwise in (u, v) around regions (outermost
// curves), clockwise around holes, alternating with nesting depth (stroke rule 2).
// A plane is kept only when its curves are simple and pairwise disjoint (exact check).
//
// The curves sample the same surface, so curves on different planes agree where they meet the
// line shared by their planes (stroke rule 4) -- up to discretisation: every point is snapped
// onto the zero set within its plane by Newton steps (|value| <= 1e-6 cell in practice), but
// the chords between points cut corners, so where two planes' curves cross the shared line
// their crossing points differ by up to about one point spacing times the curvature (a few
// percent of a cell; cell = 1/8 of the smallest primitive radius). Reconstruction's curve
// sewing absorbs this; inputs that need exact agreement should come from slice_mesh instead.
// Near a tangency the disagreement can be larger (a loop of a few cells is dropped as noise on
// one plane while another plane's curve crosses the shared line there): a plane whose curves
// leave a crossing the sewing cannot pair (rule 4, section_validate.h) is refused and another
// one drawn.
//
// Everything is deterministic by seed (SeededRandom, mesh_slicer.h).
#include <cstdint>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"

namespace ps {

struct Ellipsoid {
  Vec3 center = Vec3::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the local axes
  Vec3 radii = Vec3::Ones();
};

struct Torus {
  Vec3 center = Vec3::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // column 2: the symmetry axis
  double major = 1.0, minor = 0.3;                         // minor < major
};

// Union of primitives. value() < 0 inside, > 0 outside; it is a distance-like function
// (exact distance for tori, scaled radial distance for ellipsoids).
struct ImplicitUnion {
  std::vector<Ellipsoid> ellipsoids;
  std::vector<Torus> tori;
  double value(const Vec3& p) const;
  Box3 bounds() const;             // contains the whole solid
  double smallest_feature() const;  // smallest ellipsoid radius or torus minor radius
};

struct GeneratorOptions {
  std::uint64_t seed = 1;
  int min_primitives = 1, max_primitives = 4;
  double torus_probability = 0.35;
  int orthogonal_planes = 4;
  int oblique_planes = 2;
  int min_curve_points = 40, max_curve_points = 200;
};

struct GeneratedSections {
  ImplicitUnion shape;
  SectionSet sections;
};

// A random shape and its sections; deterministic by options.seed.
GeneratedSections generate_sections(const GeneratorOptions& options = {});

// A random union of primitives (used by generate_sections).
ImplicitUnion random_union(std::uint64_t seed, int min_primitives = 1, int max_primitives = 4,
                           double torus_probability = 0.35);

// Closed loops of the zero set of `shape` on `plane`, by marching squares with grid cell
// `cell`, oriented as described above (not resampled).
std::vector<std::vector<Vec3>> contour_plane(const ImplicitUnion& shape, const Plane& plane, double cell);

}  // namespace ps
