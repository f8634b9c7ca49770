#pragma once
// The stress generator's orthogonal inputs as the metamorphic tests use them (random unions of
// ellipsoids and tori cut by two to four axis planes per axis, crossing curves sewn; 24-60
// points per curve), by seed: recon_axis_permutation_test and recon_aligned_frame_test.
#include <cstdint>

#include "modeling/cross_section.h"
#include "modeling/section_generator.h"

namespace ps::testing {

inline SectionSet generated_orthogonal(std::uint64_t seed) {
  GeneratorOptions g;
  g.seed = seed;
  g.orthogonal_planes = 2 + static_cast<int>(seed % 3);
  g.oblique_planes = 0;
  g.min_curve_points = 24;
  g.max_curve_points = 60;
  return generate_sections(g).sections;
}

}  // namespace ps::testing
