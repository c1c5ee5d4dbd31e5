// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/height_range.h"
#include "tinlod/memory_check.h"

namespace tinlod {

// Reads one band of any raster GDAL can open. Declared nodata, NaN and GDAL mask
// bands become missing cells, and so do heights outside `valid` (infinity included),
// with one warning that counts them. Throws Error for a file that is not a raster, a band
// that does not exist or holds complex numbers, a rotated geotransform, or fewer than 3
// valid cells. With `use`, a DEM too large for the machine's memory is refused (or warned
// of) before a height is read (checkMemory).
Dem readDem(const std::string& path, int band, const ProgressRange& progress, const HeightRange& valid = HeightRange{},
            const MemoryUse* use = nullptr);

// A window of a raster's cells: columns xoff .. xoff + xsize - 1, rows likewise.
struct CellWindow {
  int xoff = 0, yoff = 0, xsize = 0, ysize = 0;
};

// The same for a window of the raster (a tile), which must lie inside it; the DEM's
// `window` says where it lies. A window may hold no valid cell: the caller decides.
Dem readDemWindow(const std::string& path, int band, const CellWindow& window, const ProgressRange& progress,
                  const HeightRange& valid = HeightRange{});

// Cuts a DEM down to columns [col0, col0 + width) and rows [row0, row0 + height) of it, in place.
void cropDem(Dem& dem, int col0, int row0, int width, int height);

}  // namespace tinlod
