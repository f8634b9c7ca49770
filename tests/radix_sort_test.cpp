// radix_sort (modeling/radix_sort.h) gives std::sort's order for keys within the stated bits,
// at every digit boundary and with many duplicates (edge keys come in pairs).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "modeling/radix_sort.h"

namespace ps {
namespace {

TEST(RadixSort, EqualsStdSort) {
  std::mt19937_64 rng(3);
  for (int bits : {1, 10, 11, 12, 22, 23, 33, 40, 63, 64}) {
    for (std::size_t n : {0u, 1u, 2u, 17u, 5000u}) {
      std::vector<std::uint64_t> keys(n);
      for (auto& k : keys) {
        k = bits == 64 ? rng() : rng() & ((std::uint64_t{1} << bits) - 1);
        if (rng() % 4 == 0 && !keys.empty()) k = keys[rng() % keys.size()];  // duplicates
      }
      std::vector<std::uint64_t> expected = keys;
      std::sort(expected.begin(), expected.end());
      radix_sort(keys, bits);
      ASSERT_EQ(keys, expected) << bits << " bits, " << n << " keys";
    }
  }
}

TEST(RadixSort, BitsFor) {
  EXPECT_EQ(bits_for(0), 1);
  EXPECT_EQ(bits_for(2), 1);
  EXPECT_EQ(bits_for(3), 2);
  EXPECT_EQ(bits_for(1024), 10);
  EXPECT_EQ(bits_for(1025), 11);
  // Every value below n fits.
  for (std::uint64_t n : {5ull, 400000000ull, 1ull << 40})
    EXPECT_LT(n - 1, std::uint64_t{1} << bits_for(n));
}

}  // namespace
}  // namespace ps
