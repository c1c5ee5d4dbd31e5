// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/sampler.h"

#include <algorithm>
#include <random>

namespace tinlod {
namespace {

enum : unsigned char { kNone = 0, kRandom = 1, kOutline = 2 };

bool isOutline(const Dem& dem, int row, int col) {
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc)
      if ((dr || dc) && !dem.valid(row + dr, col + dc)) return true;
  return false;
}

void markOutline(const Dem& dem, std::vector<unsigned char>& marks, const ProgressRange& progress) {
  for (int row = 0; row < dem.height; ++row) {
    for (int col = 0; col < dem.width; ++col)
      if (dem.valid(row, col) && isOutline(dem, row, col))
        marks[static_cast<std::size_t>(row) * dem.width + col] |= kOutline;
    if (row % 256 == 0) progress.report(double(row) / dem.height, "Finding the outline");
  }
}

// The study's sampling: a uniformly random valid cell of each block. std::mt19937_64
// is used without a std distribution because its output sequence, unlike theirs, is
// fixed by the C++ standard: the same seed gives the same TIN on every platform.
void markRandom(const Dem& dem, int block, std::uint64_t seed, std::vector<unsigned char>& marks,
                const ProgressRange& progress) {
  std::mt19937_64 rng(seed);
  for (int r0 = 0; r0 < dem.height; r0 += block) {
    const int r1 = std::min(r0 + block, dem.height);
    for (int c0 = 0; c0 < dem.width; c0 += block) {
      const int c1 = std::min(c0 + block, dem.width);
      int count = 0;
      for (int r = r0; r < r1; ++r)
        for (int c = c0; c < c1; ++c) count += dem.valid(r, c);
      if (count == 0) continue;
      int pick = static_cast<int>(rng() % static_cast<std::uint64_t>(count));
      for (int r = r0; r < r1 && pick >= 0; ++r)
        for (int c = c0; c < c1 && pick >= 0; ++c)
          if (dem.valid(r, c) && pick-- == 0) marks[static_cast<std::size_t>(r) * dem.width + c] |= kRandom;
    }
    progress.report(double(r1) / dem.height, "Sampling cells");
  }
}

}  // namespace

std::vector<SampleCell> sampleCells(const Dem& dem, int block, std::uint64_t seed,
                                    const ProgressRange& progress) {
  std::vector<unsigned char> marks(static_cast<std::size_t>(dem.width) * dem.height, kNone);
  markOutline(dem, marks, progress.sub(0, 0.5));
  markRandom(dem, block, seed, marks, progress.sub(0.5, 1));
  std::vector<SampleCell> cells;
  for (int row = 0; row < dem.height; ++row)
    for (int col = 0; col < dem.width; ++col) {
      const unsigned char m = marks[static_cast<std::size_t>(row) * dem.width + col];
      if (m != kNone) cells.push_back({row, col, (m & kOutline) != 0});
    }
  return cells;
}

}  // namespace tinlod
