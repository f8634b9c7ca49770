// libFuzzer target: mesh_import (body in fuzz_entry_points.h, shared with the corpus test).
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string problem = ps::fuzz::check_mesh_import(data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "mesh_import_fuzz: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
