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

}  // namespace rescuesim
