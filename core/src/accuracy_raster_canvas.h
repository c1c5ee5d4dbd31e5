// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the accuracy raster written a window at a time (a catalogue measured tile by
// tile), and the pieces it shares with writeAccuracyRaster.
#pragma once

#include <gdal_priv.h>

#include <string>

#include "gdal_handles.h"
#include "surface_comparison.h"
#include "tinlod/accuracy_raster.h"

namespace tinlod {

constexpr int kAccuracyBandCount = 4;
extern const char* const kAccuracyBandNames[kAccuracyBandCount];  // the bands' descriptions, in band order

// The test grid's georeferencing and CRS.
void georeference(GDALDataset& ds, const TestGrid& grid);
// The points `rect` of `grid` into the band, the grid's point (0, 0) lying at (col0, row0)
// of the band; Float32, nodata for NaN.
void writeRasterWindow(GDALRasterBand& band, const Grid& grid, const TestRect& rect, int col0, int row0);
// Statistics stored with the band, so that QGIS shows it at once (none for an all-nodata band).
void computeStatistics(GDALRasterBand& band);
// `source` into the staged file in options.format; throws Error in the user's terms.
void copyRaster(GDALDataset& source, const StagedFile& file, const RasterWriteOptions& options,
                const ProgressRange& progress);

// The four bands over the whole test grid on disk, in a scratch GeoTIFF beside the staged
// file (in its staging folder, so a failed job leaves nothing), filled window by window and
// then copied into the staged file in the format asked for.
class AccuracyRasterCanvas {
 public:
  AccuracyRasterCanvas(const TestGrid& grid, const StagedFile& file, RasterWriteOptions options);
  ~AccuracyRasterCanvas();
  AccuracyRasterCanvas(const AccuracyRasterCanvas&) = delete;
  AccuracyRasterCanvas& operator=(const AccuracyRasterCanvas&) = delete;

  // The points `rect` of `bands` (grids of one window), that window's column 0 and row 0
  // lying at (col0, row0) of the test grid.
  void write(const AccuracyBands& bands, const TestRect& rect, int col0, int row0);
  // Statistics, then the copy into the staged file.
  void finish(const ProgressRange& progress);

 private:
  const StagedFile& file_;
  RasterWriteOptions options_;
  std::string scratch_;
  DatasetPtr ds_;
};

}  // namespace tinlod
