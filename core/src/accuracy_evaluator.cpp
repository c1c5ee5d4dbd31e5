// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_evaluator.h"

#include <algorithm>
#include <cstddef>
#include <memory>

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

  // Fits the simplified heights and compares both surfaces point by point, a strip of
  // rows at a time: the bands, when asked for, take a strip's memory, not four grids'. The
  // same strips without them, so that the sums are grouped alike, and as a catalogue's
  // tiles group theirs.
  SurfaceComparison compare(const Grid& simplified, const Grid& error, const BandStrips* bands,
                            const ProgressRange& progress) const {
    const BsplineSurface surface(simplified, options.controlSpacing, grid.cellWidth, grid.cellHeight);
    SurfaceComparison total;
    for (int row0 = 0, row1; row0 < grid.rows; row0 = row1) {
      row1 = stripEnd(row0, grid.rows);
      std::unique_ptr<AccuracyBands> strip;
      if (bands) {
        strip = std::make_unique<AccuracyBands>(blankBands(grid.cols, row1 - row0));
        const auto from = error.values.begin() + std::ptrdiff_t(row0) * grid.cols;
        std::copy(from, from + std::ptrdiff_t(row1 - row0) * grid.cols, strip->elevationDifference.values.begin());
      }
      total.merge(compareSurfaces(*referenceSurface, surface, TestRect{0, row0, grid.cols, row1}, strip.get(), row0,
                                  progress.sub(double(row0) / grid.rows, double(row1) / grid.rows)));
      if (bands) (*bands)(*strip, row0);
    }
    return total;
  }
};

AccuracyEvaluator::AccuracyEvaluator(const Dem& dem, const Tin& original, const CrsTransform& toTin,
                                     const AccuracyOptions& options, const ProgressRange& progress)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  Impl& m = *impl_;
  m.options = options;
  m.grid = makeTestGrid(dem, options.step, toTin);
  if (const std::string small = surfacesMissWarning(m.grid, options.controlSpacing); !small.empty()) progress.warn(small);
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

void AccuracyEvaluator::evaluate(const std::vector<Triangle>& triangles, LevelAccuracy& row, const BandStrips* bands,
                                 const ProgressRange& progress) const {
  evaluate(impl_->z, triangles, row, bands, progress);
}

void AccuracyEvaluator::evaluate(const std::vector<double>& heights, const std::vector<Triangle>& triangles,
                                 LevelAccuracy& row, const BandStrips* bands, const ProgressRange& progress) const {
  const Impl& m = *impl_;
  if (heights.size() != m.z.size()) throw Error("internal error: heights for another TIN's vertices");
  const Grid simplified = rasterizeTin(m.positions, heights, triangles, m.grid.cols, m.grid.rows, progress.sub(0, 0.3));
  const Grid error = m.errorField(simplified);
  m.errorStatistics(error, row);
  row.variables = m.compare(simplified, error, bands, progress.sub(0.35, 1)).describe();
}

}  // namespace tinlod
