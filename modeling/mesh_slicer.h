#pragma once
// Slicing a closed triangle mesh by planes into cross sections: the tool that turns real meshes
// (CGAL's data meshes) into real cross-section inputs for tests and benchmarks.
//
// slice_mesh cuts the mesh with CGAL::Polygon_mesh_slicer (one AABB tree over the mesh's edges,
// shared by all planes), keeps the closed polylines (open ones are dropped with a warning),
// drops degenerate tiny loops (area below 1e-8 of the squared bounding-box diagonal), and
// resamples each loop to a target point spacing by arc length along the exact slice polyline,
// so every output point lies on the mesh surface. Where a loop crosses another plane of the
// set, that crossing point is kept exactly, so curves on different planes agree on their
// shared lines (stroke rule 4) up to rounding. After resampling, the curves on each plane are
// checked with exact predicates to be simple and pairwise disjoint; a plane that fails is
// resampled finer, and as a last resort keeps the raw slice polylines.
//
// A plane through a mesh vertex (within 1e-9 of the diagonal) is moved by 1e-6 of the diagonal
// along its normal first (with a warning), so the slices are generic.
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "modeling/cross_section.h"
#include "modeling/mesh.h"
#include "modeling/status.h"

namespace ps {

// === Deterministic random numbers
// std::mt19937's raw output is specified exactly by the standard, but the std distributions are
// not (they differ between standard libraries), so the conversions to doubles are our own:
// results depend only on the seed, on every platform.
class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed)
      : gen_(static_cast<std::uint32_t>(seed ^ (seed >> 32) ^ 0x9E3779B9u)) {}
  // Uniform in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t a = gen_() >> 5, b = gen_() >> 6;
    return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b)) * (1.0 / 9007199254740992.0);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi].
  int integer(int lo, int hi) {
    const auto span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1);
    return lo + static_cast<int>(static_cast<std::uint64_t>(uniform() * static_cast<double>(span)) % span);
  }
  // Uniform on the unit sphere (Archimedes: z uniform in [-1, 1], angle uniform).
  Vec3 unit_vector() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * M_PI);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }

 private:
  std::mt19937 gen_;
};

// === Plane sets
// per_axis_counts[k] planes perpendicular to axis k, evenly spaced strictly inside the box
// (at min + (i + 1) / (count + 1) * size). Typical counts are 2 to 4.
std::vector<Plane> axis_planes(const Box3& box, const std::array<int, 3>& per_axis_counts);

// n planes of uniformly random orientation, each through a random point of the middle 60% of
// the box (per axis). Deterministic by seed.
std::vector<Plane> random_planes(const Box3& box, int n, std::uint64_t seed);

// === Slicing
struct SliceOptions {
  double spacing = 0.0;       // target distance between curve points; 0: diagonal / 60
  int min_points = 8;         // at least this many points per curve (spacing shrinks if needed)
  double min_area = 1e-8;     // loops with area below min_area * diagonal^2 are dropped
  bool keep_empty_planes = false;  // keep planes that cut no closed loop
};

// Slices a closed triangle mesh. Fails (with a message) on an empty, non-finite, open or
// non-manifold mesh. Warnings (dropped open or tiny loops, moved planes, fallbacks) are
// appended to `warnings` when given.
Result<SectionSet> slice_mesh(const TriMesh& mesh, const std::vector<Plane>& planes,
                              const SliceOptions& options = {},
                              std::vector<std::string>* warnings = nullptr);

// === Simplicity
// True when each closed polygon is simple and no two polygons touch or cross (exact
// predicates). Polygons with fewer than 3 points count as bad. `bad`, when given, receives
// the indices of the polygons involved in a problem.
bool polygons_are_simple(const std::vector<std::vector<Vec2>>& polygons, std::vector<int>* bad = nullptr);

}  // namespace ps
