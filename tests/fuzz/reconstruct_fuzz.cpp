// libFuzzer entry: ps::fuzz::check_reconstruct_bytes (tests/fuzz/robust_entry_points.h). Any contract violation
// traps so libFuzzer records it; tests/robust_fuzz_corpus_test.cpp runs the same body in every build.
#include <cstddef>
#include <cstdint>

#include "robust_entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (!ps::fuzz::check_reconstruct_bytes(data, size).empty()) __builtin_trap();
  return 0;
}
