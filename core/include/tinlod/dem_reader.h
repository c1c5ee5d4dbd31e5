// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/height_range.h"

namespace tinlod {

// Reads one band of any raster GDAL can open. Declared nodata, NaN and GDAL mask
// bands become missing cells, and so do heights outside `valid` (infinity included),
// with one warning that counts them. Throws Error for a file that is not a raster, a band
// that does not exist or holds complex numbers, a rotated geotransform, or fewer than 3
// valid cells.
Dem readDem(const std::string& path, int band, const ProgressRange& progress, const HeightRange& valid = HeightRange{});

}  // namespace tinlod
