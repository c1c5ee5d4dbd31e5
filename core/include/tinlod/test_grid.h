// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/grid.h"
#include "tinlod/tin.h"

namespace tinlod {

// Where accuracy is measured: the centre of every `step`-th cell of the DEM, so that
// the accuracy raster lies on the DEM's own grid and CRS. Derivatives are taken in
// metres on the ground, also for a geographic DEM (its TIN is in a projected CRS).
struct TestGrid {
  int cols = 0, rows = 0, step = 1;
  std::array<double, 6> geotransform{};  // the test points as raster cells, in the DEM's CRS
  std::string crsWkt;                    // the DEM's as read (-s_srs's when given; empty when none)
  std::vector<double> cellWidth;         // metres between neighbouring points of each row
  double cellHeight = 0;                 // metres between neighbouring rows
  // Georeferenced centre of a test point, in the DEM's CRS.
  double x(int col) const { return geotransform[0] + (col + 0.5) * geotransform[1]; }
  double y(int row) const { return geotransform[3] + (row + 0.5) * geotransform[5]; }
};

// The fewest test points the figures need: a correlation needs three.
constexpr int kFewestTestPoints = 3;

// `toTin` takes the DEM's CRS to the TIN's (as when the TIN was sampled). Throws Error when
// `step` leaves fewer than kFewestTestPoints.
TestGrid makeTestGrid(const Dem& dem, int step, const CrsTransform& toTin);

// The warning for a test grid too small for any B-spline surface point with control points
// every `controlSpacing` test points (its correlations all nan); empty when it is not.
std::string surfacesMissWarning(const TestGrid& grid, int controlSpacing);

// Each vertex's position in test-point units (col, row): (2, 3) is the test point of
// DEM cell (3 step, 2 step).
std::vector<std::array<double, 2>> gridPositions(const TestGrid& grid, const Dem& dem,
                                                 const std::vector<TinVertex>& vertices, const CrsTransform& toTin);

// The DEM's heights at the test points (NaN where the DEM has none).
Grid demHeights(const Dem& dem, const TestGrid& grid);

}  // namespace tinlod
