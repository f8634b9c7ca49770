#pragma once
// Runs a fuzz target's body over its seed corpus (tests/fuzz/corpus/<target>/) and over
// deterministic mutations of each seed, so the fuzz entry points are exercised in every build
// (GCC Release and ASan+UBSan) even where libFuzzer is not available. Used by
// tests/formats_fuzz_corpus_test.cpp and tests/robust_fuzz_corpus_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "modeling/mesh_slicer.h"

namespace ps::fuzz {

using Check = std::function<std::string(const std::uint8_t*, std::size_t)>;

inline std::vector<std::pair<std::string, std::string>> corpus(const std::string& target) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::filesystem::path dir = std::filesystem::path(PLANESKETCH_SOURCE_DIR) / "tests/fuzz/corpus" / target;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    out.emplace_back(e.path().filename().string(), s.str());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Small deterministic mutations: byte flips, deletions, insertions of tokens that readers
// find hard (numbers at the edges of double, signs, brackets, 'h', line breaks), duplication
// and truncation.
inline std::string mutate(const std::string& seed, ps::SeededRandom& rng) {
  static const char* tokens[] = {"nan", "-inf", "1e308", "1e-320", "-0", "999999999999", "-1", "h", "h-3",
                                 "\n",  "\r\n", " ",     "[",      "]",  "{",            "}",  ",", "\"", "0.5", "4294967296"};
  std::string s = seed;
  const int edits = rng.integer(1, 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t n = s.size();
    const auto pos = static_cast<std::size_t>(rng.integer(0, static_cast<int>(n)));
    switch (rng.integer(0, 4)) {
      case 0:
        if (pos < n) s[pos] = static_cast<char>(rng.integer(0, 255));
        break;
      case 1:
        s.erase(pos, static_cast<std::size_t>(rng.integer(1, 16)));
        break;
      case 2:
        s.insert(pos, tokens[rng.integer(0, static_cast<int>(std::size(tokens)) - 1)]);
        break;
      case 3: {
        const std::string chunk = s.substr(pos, static_cast<std::size_t>(rng.integer(1, 64)));
        s.insert(static_cast<std::size_t>(rng.integer(0, static_cast<int>(s.size()))), chunk);
        break;
      }
      default:
        s.resize(pos);
    }
  }
  return s;
}

inline void run_target(const std::string& target, const Check& check, int mutations_per_seed) {
  const auto seeds = corpus(target);
  ASSERT_GE(seeds.size(), 5u) << target;
  ps::SeededRandom rng(0xC0FFEE);
  int runs = 0;
  for (const auto& [name, bytes] : seeds) {
    const std::string problem = check(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    EXPECT_TRUE(problem.empty()) << target << "/" << name << ": " << problem;
    for (int m = 0; m < mutations_per_seed; ++m) {
      const std::string mutated = mutate(bytes, rng);
      const std::string p = check(reinterpret_cast<const std::uint8_t*>(mutated.data()), mutated.size());
      EXPECT_TRUE(p.empty()) << target << "/" << name << " mutation " << m << ": " << p;
      ++runs;
    }
  }
  EXPECT_GT(runs, 0);
}

// The check over `cases` random byte strings of up to `max_len` bytes (deterministic by seed).
inline void run_random_bytes(const Check& check, std::uint64_t seed, int cases, int max_len) {
  ps::SeededRandom rng(seed);
  for (int c = 0; c < cases; ++c) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(rng.integer(0, max_len)));
    for (auto& b : bytes) b = static_cast<std::uint8_t>(rng.integer(0, 255));
    const std::string p = check(bytes.data(), bytes.size());
    EXPECT_TRUE(p.empty()) << "random input " << c << ": " << p;
  }
}

}  // namespace ps::fuzz
