// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the study's point-by-point comparison of two fitted surfaces (elevation and the
// terrain variables), shared by the whole-grid evaluator and the tile-by-tile measure of a
// catalogue.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/accuracy_statistics.h"
#include "tinlod/bspline_surface.h"
#include "tinlod/feedback.h"
#include "tinlod/terrain_measures.h"

namespace tinlod {

// Test points [col0, col1) x [row0, row1) of a grid.
struct TestRect {
  int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
  bool empty() const { return col0 >= col1 || row0 >= row1; }
};

// Sums of the compared variables over some test points; sums of parts merge into the
// sums of the whole.
class SurfaceComparison {
 public:
  static constexpr int kVariableCount = 7;
  void add(const TerrainMeasures& reference, const TerrainMeasures& simplified);
  void merge(const SurfaceComparison& other);
  std::vector<VariableComparison> describe() const;

 private:
  std::array<PairStatistics, kVariableCount> linear_;
  CircularPairStatistics aspect_;
};

// Rows of test points compared at a time, on the whole test grid's multiples of it: the
// accuracy raster's bands are held a strip this tall at a time, and the blocks it is
// written in are as tall.
constexpr int kComparedRows = 256;

// Where the strip of rows from `row` ends: at the whole grid's next multiple of
// kComparedRows (a window's row `row` being the whole grid's `origin + row`), or at `end`.
inline int stripEnd(int row, int end, int origin = 0) {
  return std::min(end, ((origin + row) / kComparedRows + 1) * kComparedRows - origin);
}

// The four bands over `rows` rows, without a value (NaN) until filled.
inline AccuracyBands blankBands(int cols, int rows) {
  const Grid blank(cols, rows);
  return {blank, blank, blank, blank};
}

// Both surfaces (over one grid) compared at the points of `rect`, on all cores, merged in
// row order so any core count gives the same sums. When `bands` is not null its curvature
// grids (the surfaces' width, holding their rows from `bandsRow0` on) get the mean
// curvatures at those points.
SurfaceComparison compareSurfaces(const BsplineSurface& reference, const BsplineSurface& simplified, const TestRect& rect,
                                  AccuracyBands* bands, int bandsRow0, const ProgressRange& progress);

}  // namespace tinlod
