#include "emcontact/app/memory.hpp"

#include <cstdlib>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace emc::app {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  if (std::getenv("GLIBC_TUNABLES")) return false;
  // M_MMAP_MAX = 0: large blocks come from the heap too (glibc caps M_MMAP_THRESHOLD at 32 MB,
  // below the Newton matrices); M_TRIM_THRESHOLD: the freed top of the heap stays mapped
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1;
#else
  return false;
#endif
}

}  // namespace emc::app
