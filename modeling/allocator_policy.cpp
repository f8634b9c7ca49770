#include "modeling/allocator_policy.h"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ps {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  if (const char* v = std::getenv("PLANESKETCH_MALLOC"); v && std::strcmp(v, "default") == 0) return false;
  // Largest value glibc accepts for M_MMAP_THRESHOLD on 64-bit (HEAP_MAX_SIZE / 2).
  const int mmap_ok = mallopt(M_MMAP_THRESHOLD, 32 << 20);
  const int trim_ok = mallopt(M_TRIM_THRESHOLD, 1 << 30);
  return mmap_ok == 1 && trim_ok == 1;
#else
  return false;
#endif
}

}  // namespace ps
