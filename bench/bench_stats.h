// Small statistics shared by the benchmarks (they print figures; nothing here is asserted).
#pragma once

#include <algorithm>
#include <vector>

namespace ps::bench {

// The median of the samples (the upper one of the two middle samples for an even count), 0 for
// none.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace ps::bench
