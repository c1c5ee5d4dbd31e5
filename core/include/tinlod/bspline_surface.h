// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <vector>

#include "tinlod/grid.h"

namespace tinlod {

// Height and its first and second partial derivatives at a point, in ground units
// (metres): x grows east along a row, y grows north (against the row index).
struct SurfacePoint {
  double z = 0, zx = 0, zy = 0, zxx = 0, zxy = 0, zyy = 0;
};

// The study's uniform cubic B-spline surface over a grid of test points: the control
// points are the grid values at every `controlSpacing`-th column and row (0, c, 2c, ...),
// and a test point (col, row) is evaluated at parameters (col / c, row / c) with the
// basis matrix M = 1/6 [[-1,3,-3,1],[3,-6,3,0],[-3,0,3,0],[1,4,1,0]]. A point whose 4 x 4
// control points are not all valid (or not all inside the grid) gets no value.
class BsplineSurface {
 public:
  // cellWidth[row]: metres between neighbouring test points of that row (it varies with
  // latitude on geographic DEMs); cellHeight: metres between neighbouring rows.
  // The grid is referenced, not copied: it must outlive the surface. Throws Error when
  // controlSpacing < 1, cellWidth has not one entry per row, or a cell size is not positive.
  BsplineSurface(const Grid& values, int controlSpacing, std::vector<double> cellWidth, double cellHeight);

  // Fills out[col] for every column of test row `row` (resizing out); points without a
  // value get z = NaN (and NaN derivatives). Thread-safe: different threads may evaluate
  // rows of one surface concurrently.
  void evaluateRow(int row, std::vector<SurfacePoint>& out) const;

  int cols() const;
  int rows() const;

 private:
  const Grid& values_;
  int spacing_;
  std::vector<double> cellWidth_;
  double cellHeight_;

  // Weights of the 4 control points for one fractional parameter t: the value, and the
  // first and second derivatives as weights of the forward differences of the points.
  struct Weights {
    double value[4];
    double slope[3];
    double bend[2];
  };
  struct RowBlend;
  static Weights basisWeights(double t);
  void blendControlRows(int row, RowBlend& blend) const;

  int controlCols_ = 0;
  int controlRows_ = 0;
  std::vector<Weights> weights_;  // one per t = k / controlSpacing
};

}  // namespace tinlod
