// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/dem.h"

#include <algorithm>

namespace tinlod {

std::size_t Dem::validCount() const {
  return static_cast<std::size_t>(
      std::count_if(z.begin(), z.end(), [](float v) { return !std::isnan(v); }));
}

namespace {

bool strictExtreme(const Dem& dem, int row, int col, bool maximum) {
  const float z = dem.at(row, col);
  int neighbours = 0;
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc) {
      if ((!dr && !dc) || !dem.valid(row + dr, col + dc)) continue;
      const float n = dem.at(row + dr, col + dc);
      if (maximum ? n >= z : n <= z) return false;
      ++neighbours;
    }
  return neighbours > 0;
}

}  // namespace

bool strictPeakOrPit(const Dem& dem, int row, int col) {
  return dem.valid(row, col) && (strictExtreme(dem, row, col, true) || strictExtreme(dem, row, col, false));
}

}  // namespace tinlod
