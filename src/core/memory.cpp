#include "core/memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace rescuesim {

bool return_free_memory() {
#if defined(__GLIBC__)
  return ::malloc_trim(0) != 0;
#else
  return false;
#endif
}

void tune_allocator_for_long_runs() {
#if defined(__GLIBC__)
  ::mallopt(M_MMAP_THRESHOLD, 4 * 1024 * 1024);
  ::mallopt(M_TRIM_THRESHOLD, 4 * 1024 * 1024);
#endif
}

}  // namespace rescuesim
