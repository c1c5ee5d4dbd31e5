// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/feedback.h"
#include "tinlod/output_files.h"
#include "tinlod/test_grid.h"

namespace tinlod {

struct RasterWriteOptions {
  std::string format = "GTiff";            // any GDAL raster driver that can create copies
  std::vector<std::string> creationOptions;  // NAME=VALUE, as gdal_translate -co
};

constexpr double kAccuracyNodata = -9999;

// Throws Error, naming -of, unless GDAL can write rasters in options.format: for checks
// before long work.
void checkRasterFormat(const RasterWriteOptions& options);

// Writes the four bands on the test grid with its georeferencing and the DEM's CRS,
// Float32, band descriptions, nodata and statistics set, so that QGIS shows it at once.
// Into a file of the job's OutputFiles, with any sidecar files the format has.
void writeAccuracyRaster(const AccuracyBands& bands, const TestGrid& grid, const StagedFile& file,
                         const RasterWriteOptions& options, const ProgressRange& progress);

}  // namespace tinlod
