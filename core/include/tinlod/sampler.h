// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"

namespace tinlod {

struct SampleCell {
  std::int32_t row = 0;
  std::int32_t col = 0;
  bool outline = false;
};

// Every valid cell on the outline of the valid area (a valid cell with a missing or
// off-raster 8-neighbour), so that the TIN covers the DEM's whole valid extent and
// its holes keep their shape, plus one uniformly random valid cell from each
// block x block block (the study's sampling), and with `peaksAndPits` every strict peak and
// pit of 3 x 3 cells (strictPeakOrPit; on a tile's shared line, read beyond the tile), so
// that fixing them keeps them all. Returned in row-major order, each cell once.
std::vector<SampleCell> sampleCells(const Dem& dem, int block, std::uint64_t seed,
                                    const ProgressRange& progress, bool peaksAndPits = false);

}  // namespace tinlod
