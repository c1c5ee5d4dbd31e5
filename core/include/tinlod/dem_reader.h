// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"

namespace tinlod {

// Reads one band of any raster GDAL can open. Declared nodata, NaN and GDAL mask
// bands become missing cells. Throws Error for a file that is not a raster, a band
// that does not exist, a rotated geotransform, or fewer than 3 valid cells.
Dem readDem(const std::string& path, int band, const ProgressRange& progress);

}  // namespace tinlod
