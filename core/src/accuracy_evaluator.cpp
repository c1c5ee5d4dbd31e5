// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_evaluator.h"

#include "surface_comparison.h"
#include "tinlod/accuracy_statistics.h"
#include "tinlod/error.h"
#include "tinlod/terrain_measures.h"
#include "tinlod/tin_rasterizer.h"

namespace tinlod {

std::string referenceName(Reference reference) { return reference == Reference::Tin ? "tin" : "dem"; }

Reference parseReference(const std::string& name) {
  if (name == "tin") return Reference::Tin;
  if (name == "dem") return Reference::Dem;
  throw Error("unknown reference '" + name + "': choose tin (the original TIN, as in the study) or dem (the DEM itself)");
}

void AccuracyOptions::validate() const {
  if (step < 1) throw Error("-step must be 1 or more (test points every step-th DEM cell), not " + std::to_string(step));
  if (controlSpacing < 1)
    throw Error("-control must be 1 or more (B-spline control points every control-th test point), not " +
                std::to_string(controlSpacing));
}

struct AccuracyEvaluator::Impl {
  AccuracyOptions options;
  TestGrid grid;
  std::vector<std::array<double, 2>> positions;
  std::vector<double> z;
  Grid reference;
  std::unique_ptr<BsplineSurface> referenceSurface;

  Grid errorField(const Grid& simplified) const {
    Grid error(grid.cols, grid.rows);
    for (std::size_t i = 0; i < error.values.size(); ++i) error.values[i] = simplified.values[i] - reference.values[i];
    return error;
  }

  void errorStatistics(const Grid& error, LevelAccuracy& row) const {
    ErrorStatistics stats;
    for (int r = 0; r < grid.rows; ++r)
      for (int c = 0; c < grid.cols; ++c)
        if (error.valid(c, r)) stats.add(error.at(c, r), grid.x(c), grid.y(r), std::uint64_t(r) * grid.cols + c);
    row.testPoints = stats.count();
    row.rmse = stats.rmse();
    row.meanError = stats.mean();
    row.maxAbsError = stats.maxAbs();
    row.maxErrorX = stats.maxX();
    row.maxErrorY = stats.maxY();
    row.moransI = moransI(error);
  }

  // Fits the simplified heights and compares both surfaces point by point.
  SurfaceComparison compare(const Grid& simplified, AccuracyBands* bands, const ProgressRange& progress) const {
    const BsplineSurface surface(simplified, options.controlSpacing, grid.cellWidth, grid.cellHeight);
    return compareSurfaces(*referenceSurface, surface, TestRect{0, 0, grid.cols, grid.rows}, bands, 0, progress);
  }
};

AccuracyEvaluator::AccuracyEvaluator(const Dem& dem, const Tin& original, const CrsTransform& toTin,
                                     const AccuracyOptions& options, const ProgressRange& progress)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  Impl& m = *impl_;
  m.options = options;
  m.grid = makeTestGrid(dem, options.step, toTin);
  m.positions = gridPositions(m.grid, dem, original.vertices, toTin);
  m.z.reserve(original.vertices.size());
  for (const TinVertex& v : original.vertices) m.z.push_back(v.z);
  m.reference = options.reference == Reference::Dem
                    ? demHeights(dem, m.grid)
                    : rasterizeTin(m.positions, m.z, original.triangles, m.grid.cols, m.grid.rows, progress);
  m.referenceSurface =
      std::make_unique<BsplineSurface>(m.reference, options.controlSpacing, m.grid.cellWidth, m.grid.cellHeight);
}

AccuracyEvaluator::~AccuracyEvaluator() = default;

const TestGrid& AccuracyEvaluator::grid() const { return impl_->grid; }
const AccuracyOptions& AccuracyEvaluator::options() const { return impl_->options; }

void AccuracyEvaluator::evaluate(const std::vector<Triangle>& triangles, LevelAccuracy& row, AccuracyBands* bands,
                                 const ProgressRange& progress) const {
  evaluate(impl_->z, triangles, row, bands, progress);
}

void AccuracyEvaluator::evaluate(const std::vector<double>& heights, const std::vector<Triangle>& triangles,
                                 LevelAccuracy& row, AccuracyBands* bands, const ProgressRange& progress) const {
  const Impl& m = *impl_;
  if (heights.size() != m.z.size()) throw Error("internal error: heights for another TIN's vertices");
  const Grid simplified = rasterizeTin(m.positions, heights, triangles, m.grid.cols, m.grid.rows, progress.sub(0, 0.3));
  Grid error = m.errorField(simplified);
  m.errorStatistics(error, row);
  if (bands) {
    const Grid empty(m.grid.cols, m.grid.rows);
    bands->meanCurvatureDifference = bands->meanCurvatureReference = bands->meanCurvatureSimplified = empty;
  }
  row.variables = m.compare(simplified, bands, progress.sub(0.35, 1)).describe();
  if (bands) bands->elevationDifference = std::move(error);
}

}  // namespace tinlod
