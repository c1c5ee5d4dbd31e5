// SPDX-License-Identifier: GPL-3.0-or-later
// What the benchmark programs share: wall-clock and CPU seconds, peak memory, the default DEM.
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

// CPU seconds this process has used, on every thread: less shaken than wall time when
// the machine is shared, so two versions compare on it too.
inline double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The scaling benchmark DEM in ../shared/data (or $TINLOD_TEST_DATA).
inline std::string defaultDem() {
  const char* env = std::getenv("TINLOD_TEST_DATA");
  return std::string(env ? env : "../shared/data") + "/alps_2x2_N46E007_N47E008.tif";
}

}  // namespace tinlod::bench
