// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstdint>
#include <string>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"

namespace tinlod {

// The project's own default DEM, so that the quick start and tests need no data:
// fractal hills and a ridge, a flat lake and a nodata void, in UTM zone 32N.
struct SyntheticDemOptions {
  int width = 1200;
  int height = 1000;
  double cellSize = 20.0;  // metres
  std::uint64_t seed = 7;
  bool withVoid = true;    // a nodata hole inside the raster
  bool withLake = true;    // an exactly flat area
};

Dem makeSyntheticDem(const SyntheticDemOptions& options, const ProgressRange& progress = ProgressRange(Feedback{}, 0, 1));

// Writes any in-memory DEM as a GeoTIFF (Float32, nodata -9999). Throws Error.
// Staged and moved into place at the end, as every output; an existing file is an error
// unless `overwrite`.
void writeDemGeoTiff(const Dem& dem, const std::string& path, bool overwrite = true,
                     const ProgressRange& progress = ProgressRange(Feedback{}, 0, 1));

}  // namespace tinlod
