// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace tinlod {

// Values at a regular grid of test points, row-major from the top (northern) row;
// NaN marks a point without a value (nodata, outside the TIN).
struct Grid {
  int cols = 0;
  int rows = 0;
  std::vector<double> values;

  Grid() = default;
  Grid(int cols_, int rows_, double fill = std::numeric_limits<double>::quiet_NaN())
      : cols(cols_), rows(rows_), values(static_cast<std::size_t>(cols_) * rows_, fill) {}
  double& at(int col, int row) { return values[static_cast<std::size_t>(row) * cols + col]; }
  double at(int col, int row) const { return values[static_cast<std::size_t>(row) * cols + col]; }
  bool valid(int col, int row) const { return !std::isnan(at(col, row)); }
};

}  // namespace tinlod
