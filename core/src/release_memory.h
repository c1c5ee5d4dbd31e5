// SPDX-License-Identifier: GPL-3.0-or-later
// Private: giving an array's memory back while its owner lives on.
#pragma once

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

}  // namespace tinlod
