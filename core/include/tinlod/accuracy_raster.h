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
// As above, and unless the format keeps the accuracy raster's four bands of 32-bit floats
// (a small raster is written to a temporary folder and read back). Returns the names of the
// files the format writes beside a raster named `path` (ENVI's "a.hdr" beside "a.bil"), GDAL's
// .aux.xml aside.
std::vector<std::string> checkRasterKeepsItsBands(const RasterWriteOptions& options, const std::string& path);

// The GDAL raster format that writes files named as `path` (GTiff for .tif), as gdal_translate
// picks it without -of; empty when no format writes such files. The command line and QGIS
// both call it, so one name gives one format whichever the user runs.
std::string rasterFormatFor(const std::string& path);

}  // namespace tinlod
