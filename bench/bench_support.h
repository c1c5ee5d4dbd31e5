// SPDX-License-Identifier: GPL-3.0-or-later
// What the benchmark programs share: wall-clock seconds, peak memory, the default DEM.
#pragma once

#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <string>

namespace tinlod::bench {

using Clock = std::chrono::steady_clock;

inline double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

inline double peakMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

// The scaling benchmark DEM in ../shared/data (or $TINLOD_TEST_DATA).
inline std::string defaultDem() {
  const char* env = std::getenv("TINLOD_TEST_DATA");
  return std::string(env ? env : "../shared/data") + "/alps_2x2_N46E007_N47E008.tif";
}

}  // namespace tinlod::bench
