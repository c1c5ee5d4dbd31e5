// SPDX-License-Identifier: GPL-3.0-or-later
#include "cell_errors.h"

#include <algorithm>

#include "tinlod/hierarchy.h"

namespace tinlod {

CellErrors::CellErrors(const Dem& dem, const Tin& tin) : dem_(&dem), tin_(&tin) {}

void CellErrors::bound(double maxError) {
  maxError_ = maxError;
  if (bounded()) levelZero_.assign(static_cast<std::size_t>(dem_->width) * dem_->height, 0.0f);
}

TriangleCells CellErrors::measure(VertexId a, VertexId b, VertexId c, const bool (&outline)[3], bool recordLevelZero) {
  TriangleCells out;
  const std::vector<TinVertex>& v = tin_->vertices;
  const CellCorner p[3] = {cellCorner(v[a], a), cellCorner(v[b], b), cellCorner(v[c], c)};
  const float* z = dem_->z.data();
  const int width = dem_->width;
  const bool bounded = this->bounded();
  float* zero = levelZero_.data();
  scanCells(width, dem_->height, p, outline, [&](int row, int col, double height) {
    const std::size_t cell = static_cast<std::size_t>(row) * width + col;
    const float dem = z[cell];
    if (std::isnan(dem)) return;
    const double d = std::fabs(double(dem) - height);
    out.maxError = std::max(out.maxError, d);
    out.sumSquares += d * d;
    ++out.cells;
    if (!bounded) return;
    if (recordLevelZero) zero[cell] = roundedUpError(d);  // never a tighter bound than level 0's
    const double allowed = std::max(maxError_, double(zero[cell]));
    // Rounded up, a passing cell's excess stays above 0 in the float.
    out.excess = std::max(out.excess, roundedUpError(d - allowed));
  });
  return out;
}

}  // namespace tinlod
