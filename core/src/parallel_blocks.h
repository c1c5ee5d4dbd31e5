// SPDX-License-Identifier: GPL-3.0-or-later
// Private: work on items 0 .. count - 1 (grid rows, vertices) split over the machine's
// cores by blocks.
#pragma once

#include <functional>

namespace tinlod {

// The threads forEachBlock and runBoth use: TINLOD_THREADS when set (a tiled run gives each
// of its workers a share of the cores), else the machine's cores, at most 8.
unsigned threadCount();

// While one lives, forEachBlock and runBoth called from its thread use that thread alone:
// for background work beside a busy thread (the independent check of a greedy insertion
// while the main thread writes the file), which more threads would only slow down.
class ThisThreadAlone {
 public:
  ThisThreadAlone();
  ~ThisThreadAlone();
  ThisThreadAlone(const ThisThreadAlone&) = delete;
  ThisThreadAlone& operator=(const ThisThreadAlone&) = delete;

 private:
  bool before_;
};

// Calls work(begin, end) for blocks covering [0, count), on threadCount() threads. The
// calling thread works too and calls progress(fraction done) between its blocks, so a
// progress callback that throws (cancellation) stops every thread promptly; the first
// exception of any thread is rethrown once all have stopped.
void forEachBlock(int count, const std::function<void(int, int)>& work, const std::function<void(double)>& progress);

// Runs first and second at once, second on a thread of its own (one after the other with
// one thread). Once both have ended,
// rethrows first's exception if it threw, else second's.
void runBoth(const std::function<void()>& first, const std::function<void()>& second);

}  // namespace tinlod
