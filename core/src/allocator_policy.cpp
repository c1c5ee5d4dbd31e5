// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/allocator_policy.h"

#include <cstdlib>

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace tinlod {

void mapLargeArraysApart() {
#ifdef __GLIBC__
  if (!std::getenv("MALLOC_MMAP_THRESHOLD_")) mallopt(M_MMAP_THRESHOLD, 4 << 20);
#endif
}

}  // namespace tinlod
