// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cstdlib>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "tinlod/allocator_policy.h"

namespace {

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
// The array is written and read through a volatile pointer, so the allocation is not elided.
void touch(std::size_t bytes, bool holdWhile, std::size_t* mappedMeanwhile) {
  volatile char* p = static_cast<volatile char*>(std::malloc(bytes));
  ASSERT_NE(p, nullptr);
  p[0] = 1, p[bytes - 1] = p[0];
  if (holdWhile) *mappedMeanwhile = mallinfo2().hblks;
  std::free(const_cast<char*>(p));
}
#endif

}  // namespace

// glibc's own policy: freeing a 20 MB mapping raises its threshold to 20 MB, after which an
// 8 MB array comes from the heap (and stays resident once freed). With the policy it has a
// mapping of its own, whatever was freed before.
TEST(AllocatorPolicy, ArraysOf4MbOrMoreAreMappedApartEvenAfterALargerOneWasFreed) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's allocator only (a sanitizer replaces it)";
#else
  if (std::getenv("MALLOC_MMAP_THRESHOLD_")) GTEST_SKIP() << "MALLOC_MMAP_THRESHOLD_ is set: the user's threshold stands";
  tinlod::mapLargeArraysApart();
  std::size_t ignored = 0, during = 0;
  touch(20 << 20, false, &ignored);
  const std::size_t before = mallinfo2().hblks;
  touch(8 << 20, true, &during);
  EXPECT_EQ(during, before + 1) << "the 8 MB array came from the heap";
#endif
}
