// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tinlod/accuracy_report.h"
#include "tinlod/bspline_surface.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/grid.h"
#include "tinlod/test_grid.h"
#include "tinlod/tin.h"

namespace tinlod {

enum class Reference { Tin, Dem };  // the original TIN (as in the study) or the DEM itself

std::string referenceName(Reference reference);
Reference parseReference(const std::string& name);  // throws Error listing the choices

struct AccuracyOptions {
  Reference reference = Reference::Tin;
  int step = 1;            // test points at every step-th DEM cell
  int controlSpacing = 3;  // B-spline control points every controlSpacing test points
  void validate() const;   // throws Error naming the parameter
};

// The accuracy raster's bands, on the test grid (NaN: no value).
struct AccuracyBands {
  Grid elevationDifference;      // simplified - reference, linear interpolation, metres
  Grid meanCurvatureDifference;  // of the fitted B-spline surfaces, 1/m
  Grid meanCurvatureReference;
  Grid meanCurvatureSimplified;
};

// Takes the accuracy raster's bands a strip of rows at a time: the grids of `strip` hold
// every column of the test grid's rows from `row0` on.
using BandStrips = std::function<void(const AccuracyBands& strip, int row0)>;

// Measures simplified TINs against one reference: the test grid, the reference heights
// and their B-spline surface are made once, then each TIN is interpolated, fitted and
// compared (elevation statistics on the interpolated heights; correlations of elevation
// and of the terrain variables on the fitted surfaces, as in the study).
class AccuracyEvaluator {
 public:
  // `original` is the level-0 TIN sampled from `dem`; `toTin` takes the DEM's CRS to the TIN's.
  AccuracyEvaluator(const Dem& dem, const Tin& original, const CrsTransform& toTin, const AccuracyOptions& options,
                    const ProgressRange& progress);
  ~AccuracyEvaluator();
  AccuracyEvaluator(const AccuracyEvaluator&) = delete;
  AccuracyEvaluator& operator=(const AccuracyEvaluator&) = delete;

  // `triangles` index the original TIN's vertices (a level of a hierarchy). Fills the
  // test point count, error statistics and variable comparisons of `row`, and gives the
  // bands to `bands` when it is not null.
  void evaluate(const std::vector<Triangle>& triangles, LevelAccuracy& row, const BandStrips* bands,
                const ProgressRange& progress) const;
  // The same with other heights for the original's vertices (one per vertex).
  void evaluate(const std::vector<double>& heights, const std::vector<Triangle>& triangles, LevelAccuracy& row,
                const BandStrips* bands, const ProgressRange& progress) const;

  const TestGrid& grid() const;
  const AccuracyOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tinlod
