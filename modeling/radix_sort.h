#pragma once
// LSD radix sort of unsigned 64-bit keys, 11 bits per pass, only over the low `key_bits` bits
// (keys must be below 2^key_bits). Hand-written: the stitch weld sorts 100k+ edge keys made
// of two vertex indices, and std::sort's comparisons were a measurable part of a progressive
// update (bench/results/recon.md); a few counting passes are several times
// faster. Stable; the result equals std::sort's.
#include <array>
#include <cstdint>
#include <vector>

namespace ps {

inline void radix_sort(std::vector<std::uint64_t>& keys, int key_bits) {
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  std::vector<std::uint64_t> buffer(keys.size());
  for (int shift = 0; shift < key_bits; shift += kDigit) {
    std::array<std::size_t, kBuckets> count{};
    for (std::uint64_t k : keys) ++count[(k >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (auto& c : count) {
      const std::size_t n = c;
      c = sum;
      sum += n;
    }
    for (std::uint64_t k : keys) buffer[count[(k >> shift) & (kBuckets - 1)]++] = k;
    keys.swap(buffer);
  }
}

// Bits needed for values below n (at least 1).
inline int bits_for(std::uint64_t n) {
  int b = 1;
  while (b < 64 && (std::uint64_t{1} << b) < n) ++b;
  return b;
}

}  // namespace ps
