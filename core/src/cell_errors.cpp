// SPDX-License-Identifier: GPL-3.0-or-later
#include "cell_errors.h"

#include <algorithm>

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
    if (recordLevelZero) {
      float f = static_cast<float>(d);
      if (double(f) < d) f = std::nextafter(f, INFINITY);  // rounded up: never a tighter bound than level 0's
      zero[cell] = f;
    }
    const double allowed = std::max(maxError_, double(zero[cell]));
    // Rounded away from zero, so that the sign survives the float.
    if (const double e = d - allowed; e > out.excess) out.excess = e > 0 ? std::nextafter(static_cast<float>(e), INFINITY) : static_cast<float>(e);
  });
  return out;
}

}  // namespace tinlod
