// SPDX-License-Identifier: GPL-3.0-or-later
// Private: grid work split over the machine's cores by blocks of rows.
#pragma once

#include <functional>

namespace tinlod {

// Calls work(rowBegin, rowEnd) for blocks covering [0, rows), on up to 8 threads. The
// calling thread works too and calls progress(fraction done) between its blocks, so a
// progress callback that throws (cancellation) stops every thread promptly; the first
// exception of any thread is rethrown once all have stopped.
void forRowBlocks(int rows, const std::function<void(int, int)>& work, const std::function<void(double)>& progress);

}  // namespace tinlod
