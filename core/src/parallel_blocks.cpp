// SPDX-License-Identifier: GPL-3.0-or-later
#include "parallel_blocks.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tinlod {

namespace {
thread_local bool tAlone = false;
}  // namespace

ThisThreadAlone::ThisThreadAlone() : before_(tAlone) { tAlone = true; }
ThisThreadAlone::~ThisThreadAlone() { tAlone = before_; }

unsigned threadCount() {
  if (tAlone) return 1;
  // A tiled run's workers share the machine: each tinlod is told its share of the cores.
  static const unsigned count = [] {
    const char* given = std::getenv("TINLOD_THREADS");
    const long wanted = given ? std::strtol(given, nullptr, 10) : 0;
    return wanted > 0 ? static_cast<unsigned>(std::min(wanted, 64L))
                      : std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
  }();
  return count;
}

void forEachBlock(int count, const std::function<void(int, int)>& work, const std::function<void(double)>& progress) {
  const int block = std::max(1, std::min(4096, count / 64));
  std::atomic<int> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto loop = [&](bool reporting) {
    try {
      for (int b = next.fetch_add(block); b < count && !stop; b = next.fetch_add(block)) {
        work(b, std::min(count, b + block));
        done += std::min(count, b + block) - b;
        if (reporting && progress) progress(double(done) / count);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  const unsigned threads = threadCount();
  std::vector<std::thread> workers;
  for (unsigned t = 1; t < threads; ++t) workers.emplace_back(loop, false);
  loop(true);
  for (std::thread& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
}

void runBoth(const std::function<void()>& first, const std::function<void()>& second) {
  if (threadCount() == 1) {
    first();
    second();
    return;
  }
  std::exception_ptr failure;
  std::thread other([&] {
    try {
      second();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  try {
    first();
  } catch (...) {
    other.join();
    throw;
  }
  other.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tinlod
