// libFuzzer entry: ps::fuzz::check_recon_kernel_bytes (tests/fuzz/recon_kernel_entry_point.h).
// A contract violation prints what went wrong and aborts, so libFuzzer records the input;
// tests/recon_kernel_fuzz_corpus_test.cpp runs the same body over the seed corpus in every build.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/fuzz/recon_kernel_entry_point.h"

namespace {
// PLANESKETCH_FUZZ_STRICT=1: self-intersections are fatal too (see recon_kernel_entry_point.h).
const bool kStrict = [] {
  const char* v = std::getenv("PLANESKETCH_FUZZ_STRICT");
  return v != nullptr && std::string(v) == "1";
}();
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string problem = ps::fuzz::check_recon_kernel_bytes(data, size, kStrict);
  if (!problem.empty()) {
    std::fprintf(stderr, "recon_kernel_fuzz: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
