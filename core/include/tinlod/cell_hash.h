// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>

namespace tinlod {

// SplitMix64's finaliser: every bit of the input moves about half the output's bits.
inline std::uint64_t mixBits(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ULL;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// A random number for a place in the whole raster (a cell, or a block by its row and
// column of blocks), the same whichever part of the raster is read: sampling by place
// rather than from a stream is what lets tiles sample exactly what a whole run would.
inline std::uint64_t cellHash(std::uint64_t seed, std::int64_t row, std::int64_t col, std::uint64_t stream = 0) {
  std::uint64_t h = mixBits(seed ^ (stream * 0xD6E8FEB86659FD93ULL));
  h = mixBits(h ^ static_cast<std::uint64_t>(row));
  return mixBits(h ^ (static_cast<std::uint64_t>(col) * 0x9E3779B97F4A7C15ULL));
}

// Uniform in [0, 1) from the top 53 bits.
inline double unitFromHash(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

}  // namespace tinlod
