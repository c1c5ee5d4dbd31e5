// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/sampler.h"

#include <algorithm>

#include "tinlod/cell_hash.h"
#include "tinlod/tile_borders.h"

namespace tinlod {
namespace {

enum : unsigned char { kNone = 0, kRandom = 1, kOutline = 2, kPeakOrPit = 4 };

// A window starts on a block line (a tile's offset is a multiple of the block); a DEM
// that is its own whole raster starts at 0.
int firstBlockStart(std::int64_t globalStart, int block) {
  return static_cast<int>((block - globalStart % block) % block);
}

bool isOutline(const Dem& dem, int row, int col) {
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc)
      if ((dr || dc) && !dem.valid(row + dr, col + dc)) return true;
  return false;
}

// A tile's shared lines are sampled by their own rule (lineCellSampled), the same in both
// tiles, not as the raster's edge is (every cell); their peaks and pits are those of the
// whole raster, which both tiles read beyond their edge.
void markOutlineAndPeaks(const Dem& dem, int block, std::uint64_t seed, bool peaksAndPits,
                         std::vector<unsigned char>& marks, const ProgressRange& progress) {
  for (int row = 0; row < dem.height; ++row) {
    for (int col = 0; col < dem.width; ++col) {
      if (!dem.valid(row, col)) continue;
      const bool line = onSharedLine(dem, row, col);
      unsigned char& mark = marks[static_cast<std::size_t>(row) * dem.width + col];
      if (line ? lineCellSampled(dem, row, col, block, seed) : isOutline(dem, row, col))
        mark |= kOutline;
      else if (peaksAndPits && (line ? dem.edgePeakOrPitAt(row, col) : strictPeakOrPit(dem, row, col)))
        mark |= kPeakOrPit;
    }
    if (row % 256 == 0) progress.report(double(row) / dem.height, "Finding the outline");
  }
}

// The study's sampling: a uniformly random valid cell of each block. The cell is drawn
// from a hash of the seed and the block's place in the whole raster, not from a stream:
// a tile then samples each of its blocks as a run over the whole raster does. Blocks
// start at the whole raster's multiples of `block`; one that starts on a tile's shared
// last column or row is the next tile's.
void markRandom(const Dem& dem, int block, std::uint64_t seed, std::vector<unsigned char>& marks,
                const ProgressRange& progress) {
  const int ownRows = dem.height - dem.sharesLastRow(), ownCols = dem.width - dem.sharesLastCol();
  const int firstRow = firstBlockStart(dem.globalRow(0), block), firstCol = firstBlockStart(dem.globalCol(0), block);
  for (int r0 = firstRow; r0 < ownRows; r0 += block) {
    const int r1 = std::min(r0 + block, dem.height);
    for (int c0 = firstCol; c0 < ownCols; c0 += block) {
      const int c1 = std::min(c0 + block, dem.width);
      int count = 0;
      for (int r = r0; r < r1; ++r)
        for (int c = c0; c < c1; ++c) count += dem.valid(r, c);
      if (count == 0) continue;
      const std::uint64_t h = cellHash(seed, dem.globalRow(r0) / block, dem.globalCol(c0) / block);
      int pick = static_cast<int>(h % static_cast<std::uint64_t>(count));
      for (int r = r0; r < r1 && pick >= 0; ++r)
        for (int c = c0; c < c1 && pick >= 0; ++c)
          // A pick on a shared line is the line's to decide: the other tile would not have it.
          if (dem.valid(r, c) && pick-- == 0 && !onSharedLine(dem, r, c))
            marks[static_cast<std::size_t>(r) * dem.width + c] |= kRandom;
    }
    if ((r0 / block) % 64 == 0) progress.report(double(r1) / dem.height, "Sampling cells");
  }
}

}  // namespace

std::vector<SampleCell> sampleCells(const Dem& dem, int block, std::uint64_t seed,
                                    const ProgressRange& progress, bool peaksAndPits) {
  std::vector<unsigned char> marks(static_cast<std::size_t>(dem.width) * dem.height, kNone);
  markOutlineAndPeaks(dem, block, seed, peaksAndPits, marks, progress.sub(0, 0.5));
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
