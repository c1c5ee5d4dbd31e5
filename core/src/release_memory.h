// SPDX-License-Identifier: GPL-3.0-or-later
// Private: giving an array's memory back while its owner lives on.
#pragma once

#include <type_traits>
#include <vector>

namespace tinlod {

// Empties `c` and frees its memory. `c = {}` would not: for a vector it assigns an empty
// list and keeps the capacity, which is how a 4096 x 4096 tile once held its heights and
// nodata flags (84 MB) and level 0's neighbours (45 MB) to the end after "freeing" them.
template <class Container>
void releaseMemory(Container& c) {
  Container().swap(c);
}

// Gives the heap's free pages back to the system. glibc keeps what a program frees in its
// heaps, resident, unless asked (150 MB by the last level of a 4096 x 4096 tile's build).
// A few milliseconds.
void releaseFreedMemory();

// Gives back the whole pages in [begin, end), which the caller no longer reads: they read
// as zeros if touched again.
void releasePages(void* begin, void* end);

// Gives back the pages past the end of `v` that its capacity holds, keeping the capacity:
// a vector shrinks to fit only by a copy, which would hold it twice.
template <class T>
void releaseUnusedCapacity(std::vector<T>& v) {
  static_assert(std::is_trivially_copyable_v<T>, "the entries past the end are never read");
  releasePages(v.data() + v.size(), v.data() + v.capacity());
}

}  // namespace tinlod
