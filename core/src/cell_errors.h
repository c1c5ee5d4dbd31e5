// SPDX-License-Identifier: GPL-3.0-or-later
// Private: how far each triangle of the simplification is from the DEM, at every valid
// cell centre under it (see cell_scan.h for how a triangle is read in the grid). Each
// level's maximum, RMSE and covered cells follow from its triangles' figures.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "cell_scan.h"
#include "tinlod/dem.h"
#include "tinlod/tin.h"

namespace tinlod {

// The valid cells under one triangle: the largest and summed squared vertical distance
// to the DEM, and how many there are. `excess` is the largest amount by which a cell is
// further from the DEM than its bound (see CellErrors::bounded), or -infinity.
struct TriangleCells {
  double maxError = 0;
  double sumSquares = 0;
  std::uint32_t cells = 0;
  // Only its sign decides; a float keeps the struct at 24 bytes (one for each triangle of
  // the level and of its plan).
  float excess = -std::numeric_limits<float>::infinity();

  void add(const TriangleCells& o) {
    maxError = std::max(maxError, o.maxError), sumSquares += o.sumSquares, cells += o.cells;
    excess = std::max(excess, o.excess);
  }
};
static_assert(sizeof(TriangleCells) == 24, "one for each triangle of a level and of its plan: keep it small");

class CellErrors {
 public:
  CellErrors() = default;
  // `dem` and `tin` must outlive this; `tin`'s vertices say where each vertex lies in its
  // grid (read where they are, not copied: a copy would cost 32 bytes a vertex).
  CellErrors(const Dem& dem, const Tin& tin);

  // With a bound of `maxError` metres: a cell's bound is max(maxError, level 0's own
  // distance there), which setLevelZero() records as it measures level 0.
  void bound(double maxError);
  bool bounded() const { return std::isfinite(maxError_); }

  // The cells under the triangle a, b, c (TIN ids, counter-clockwise); outline[k] marks
  // the edge opposite corner k as an outline edge. With recordLevelZero, each cell's
  // distance is kept as level 0's (for bounded runs).
  TriangleCells measure(VertexId a, VertexId b, VertexId c, const bool (&outline)[3], bool recordLevelZero = false);

 private:
  const Dem* dem_ = nullptr;
  const Tin* tin_ = nullptr;
  double maxError_ = INFINITY;
  std::vector<float> levelZero_;     // by cell: level 0's distance (bounded runs only)
};

}  // namespace tinlod
