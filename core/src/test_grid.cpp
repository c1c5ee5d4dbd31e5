// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/test_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "tinlod/error.h"

namespace tinlod {
TestGrid makeTestGrid(const Dem& dem, int step, const CrsTransform& toTin) {
  if (step < 1) throw Error("-step must be 1 or more (test points every step-th DEM cell), not " + std::to_string(step));
  TestGrid g;
  g.step = step;
  g.cols = (dem.width + step - 1) / step;
  g.rows = (dem.height + step - 1) / step;
  const std::array<double, 6>& gt = dem.geotransform;
  // Test point (c, r) is the centre of DEM cell (r step, c step): a raster cell of step
  // DEM cells centred there.
  g.geotransform = {gt[0] + 0.5 * (1 - step) * gt[1], step * gt[1], 0, gt[3] + 0.5 * (1 - step) * gt[5], 0, step * gt[5]};
  if (std::int64_t(g.cols) * g.rows < kFewestTestPoints)
    throw Error("-step " + std::to_string(step) + " leaves " + std::to_string(g.cols * g.rows) + " test point" +
                (g.cols * g.rows == 1 ? "" : "s") + " on the DEM's " + std::to_string(dem.width) + " x " +
                std::to_string(dem.height) + " cells, and the figures need " + std::to_string(kFewestTestPoints) +
                ": give a smaller -step");
  g.crsWkt = toTin.sourceWkt();  // -s_srs's when given: the DEM's file may have none
  // Measured over one DEM cell, times the step: a step of many cells of a DEM in degrees
  // would reach beyond the poles.
  const double midX = g.x(g.cols / 2);
  g.cellHeight = step * toTin.groundDistance(midX, g.y(g.rows / 2), midX, g.y(g.rows / 2) + gt[5]);
  g.cellWidth.resize(g.rows);
  for (int r = 0; r < g.rows; ++r) g.cellWidth[r] = step * toTin.groundDistance(midX, g.y(r), midX + gt[1], g.y(r));
  return g;
}

std::string surfacesMissWarning(const TestGrid& grid, int controlSpacing) {
  // A cubic B-spline is defined between its second and its second-to-last control points: the
  // test points from the first spacing up to the spacing before the second-to-last point.
  const auto reached = [controlSpacing](int points) {
    const std::int64_t c = controlSpacing, controls = (points - 1) / c + 1;
    return std::max<std::int64_t>(0, std::min<std::int64_t>(points, (controls - 2) * c) - c);
  };
  const std::int64_t points = reached(grid.cols) * reached(grid.rows);
  if (points >= kFewestTestPoints) return {};
  return "the test grid of " + std::to_string(grid.cols) + " x " + std::to_string(grid.rows) +
         " points is too small for B-spline surfaces with control points every " + std::to_string(controlSpacing) +
         ": they reach " + std::to_string(points) + " of its points, and a correlation needs " + std::to_string(kFewestTestPoints) +
         ": the height and curvature correlations are not measured (nan); give a smaller -step or -control";
}

namespace {

// A vertex on the raster's edge moves only along it (sample_job.cpp): across it, it lies on
// the edge's cell centres exactly. Taken back from the TIN's CRS it comes within rounding
// of them, either side: a point outside would leave the cell centres on that edge outside
// every triangle (112 of zion's 212,505 cells, sampled in UTM). Any other vertex is
// further from the edge than this by most of a cell (the jitter is smaller than a cell).
constexpr double kOnEdge = 1e-7;  // cells

double ontoEdge(double cell, int last) {
  if (std::abs(cell) < kOnEdge) return 0;
  if (std::abs(cell - last) < kOnEdge) return last;
  return cell;
}

}  // namespace

std::vector<std::array<double, 2>> gridPositions(const TestGrid& grid, const Dem& dem,
                                                 const std::vector<TinVertex>& vertices, const CrsTransform& toTin) {
  std::vector<double> x(vertices.size()), y(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) x[i] = vertices[i].x, y[i] = vertices[i].y;
  toTin.applyInverse(x, y);
  const std::array<double, 6>& gt = dem.geotransform;
  std::vector<std::array<double, 2>> out(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    out[i] = {ontoEdge((x[i] - gt[0]) / gt[1] - 0.5, dem.width - 1) / grid.step,
              ontoEdge((y[i] - gt[3]) / gt[5] - 0.5, dem.height - 1) / grid.step};
  return out;
}

Grid demHeights(const Dem& dem, const TestGrid& grid) {
  Grid out(grid.cols, grid.rows);
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.cols; ++c)
      if (dem.valid(r * grid.step, c * grid.step)) out.at(c, r) = dem.at(r * grid.step, c * grid.step);
  return out;
}

}  // namespace tinlod
