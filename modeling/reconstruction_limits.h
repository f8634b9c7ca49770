#pragma once
// Size limits of the reconstruction input, checked before any work so that an input far beyond
// what the union can handle is refused at once with a reason, instead of running for hours.
// The largest real data set we have (../shared/data/csl, Abdomen.csl) holds 32 682 points; the
// union's cost grows faster than linearly with the points (bench/results/recon.md), so the
// total is capped at 100 000 points.
#include <cstddef>
#include <string>

#include "modeling/cross_section.h"
#include "modeling/status.h"

namespace ps {

inline constexpr std::size_t kMaxReconstructionPoints = 100000;

inline Status check_reconstruction_size(const SectionSet& sections) {
  std::size_t total = 0, largest = 0, largest_curve = 0;
  for (std::size_t c = 0; c < sections.curves.size(); ++c) {
    const std::size_t n = sections.curves[c].points.size();
    total += n;
    if (n > largest) largest = n, largest_curve = c;
  }
  if (total <= kMaxReconstructionPoints) return Status::ok();
  return Status::error("the sections hold " + std::to_string(total) + " points (curve " +
                       std::to_string(largest_curve) + " alone has " + std::to_string(largest) +
                       "); reconstruction accepts at most " + std::to_string(kMaxReconstructionPoints) +
                       " points: resample the curves more coarsely");
}

}  // namespace ps
