// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the accuracy raster written a window at a time (a strip of rows of a whole
// grid, or of a catalogue's tile measured on its own), and the pieces of its writing.
#pragma once

#include <gdal_priv.h>

#include <string>

#include "tinlod/accuracy_statistics.h"
#include "tinlod/error.h"

#include "gdal_handles.h"
#include "surface_comparison.h"
#include "tinlod/accuracy_raster.h"

namespace tinlod {

constexpr int kAccuracyBandCount = 4;
extern const char* const kAccuracyBandNames[kAccuracyBandCount];  // the bands' descriptions, in band order

// The test grid's georeferencing and CRS.
void georeference(GDALDataset& ds, const TestGrid& grid);
// A band's statistics as GDAL computes them (minimum, maximum, mean, population standard
// deviation of the valid pixels), summed from the values as they are written, so that a
// band on disk need not be read back for them.
class BandStatistics {
 public:
  void add(float value);
  // Stores them in the band's metadata, as ComputeStatistics does; `pixels` is the band's size.
  void store(GDALRasterBand& band, double pixels) const;

 private:
  std::size_t count_ = 0;
  detail::CompensatedSum sum_, squares_;
  double min_ = 0, max_ = 0;
};

// The points `rect` of `grid` into the band, the grid's point (0, 0) lying at (col0, row0)
// of the band; Float32, nodata for NaN. The valid values also go to `statistics` if given.
void writeRasterWindow(GDALRasterBand& band, const Grid& grid, const TestRect& rect, int col0, int row0,
                       BandStatistics* statistics = nullptr);
// "<option>: cannot write the accuracy raster '<path>': " and GDAL's last message, in the
// user's terms (it names the staging file).
Error rasterWriteError(const StagedFile& file);
// Closes a raster written into the staged file; throws rasterWriteError when GDAL has
// failed since the last CPLErrorReset (in the writing or in the closing).
void closeRaster(DatasetPtr& out, const StagedFile& file);
// `source` into the staged file in options.format; throws Error in the user's terms.
void copyRaster(GDALDataset& source, const StagedFile& file, const RasterWriteOptions& options,
                const ProgressRange& progress);

// The four bands over the whole test grid on disk, in a scratch GeoTIFF beside the staged
// file (in its staging folder, so a failed job leaves nothing), filled window by window and
// then copied into the staged file in the format asked for. Its memory is a window's, not
// the grid's: each window goes to disk at once, and the copy goes a band of rows at a time
// (but for formats GDAL can only copy whole, such as COG, which go through GDAL's block
// cache, GDAL_CACHEMAX).
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
  void copyByRows(GDALDriver& driver, const ProgressRange& progress);
  [[noreturn]] void fail() const;

  const StagedFile& file_;
  RasterWriteOptions options_;
  std::string scratch_;
  DatasetPtr ds_;
  BandStatistics statistics_[kAccuracyBandCount];
};

}  // namespace tinlod
