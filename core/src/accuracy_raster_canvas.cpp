// SPDX-License-Identifier: GPL-3.0-or-later
#include "accuracy_raster_canvas.h"

#include <cpl_string.h>

#include <utility>

#include "tinlod/error.h"

namespace tinlod {

AccuracyRasterCanvas::AccuracyRasterCanvas(const TestGrid& grid, const StagedFile& file, RasterWriteOptions options)
    : file_(file), options_(std::move(options)), scratch_(file.staging.string() + ".canvas.tif") {
  checkRasterFormat(options_);
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  // Tiled, so that a tile's window touches few blocks; sparse, so that blocks no tile
  // writes (nodata all through) take no room and no time; not compressed, since a block a
  // window fills in part would be decompressed and compressed again; BIGTIFF for national grids.
  CPLStringList co;
  co.AddString("TILED=YES");
  co.AddString("SPARSE_OK=TRUE");
  co.AddString("BIGTIFF=IF_SAFER");
  CPLPushErrorHandler(CPLQuietErrorHandler);
  ds_.reset(gtiff->Create(scratch_.c_str(), grid.cols, grid.rows, kAccuracyBandCount, GDT_Float32, co.List()));
  CPLPopErrorHandler();
  if (!ds_)
    throw Error(file.option + ": cannot make room for the accuracy raster '" + file.path +
                "': " + inUserTerms(file, CPLGetLastErrorMsg()));
  georeference(*ds_, grid);
  for (int b = 0; b < kAccuracyBandCount; ++b) {
    GDALRasterBand* band = ds_->GetRasterBand(b + 1);
    band->SetDescription(kAccuracyBandNames[b]);
    band->SetNoDataValue(kAccuracyNodata);  // what an unwritten block of a sparse file reads as
  }
}

AccuracyRasterCanvas::~AccuracyRasterCanvas() {
  ds_.reset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  VSIUnlink(scratch_.c_str());
  VSIUnlink((scratch_ + ".aux.xml").c_str());
  CPLPopErrorHandler();
}

void AccuracyRasterCanvas::write(const AccuracyBands& bands, const TestRect& rect, int col0, int row0) {
  CPLErrorReset();
  const Grid* grids[] = {&bands.elevationDifference, &bands.meanCurvatureDifference, &bands.meanCurvatureReference,
                         &bands.meanCurvatureSimplified};
  for (int b = 0; b < kAccuracyBandCount; ++b) writeRasterWindow(*ds_->GetRasterBand(b + 1), *grids[b], rect, col0, row0);
  // To disk at once: GDAL's block cache would otherwise hold up to GDAL_CACHEMAX of it.
  ds_->FlushCache();
  if (CPLGetLastErrorType() == CE_Failure)
    throw Error(file_.option + ": cannot write the accuracy raster '" + file_.path +
                "': " + inUserTerms(file_, CPLGetLastErrorMsg()));
}

void AccuracyRasterCanvas::finish(const ProgressRange& progress) {
  for (int b = 0; b < kAccuracyBandCount; ++b) computeStatistics(*ds_->GetRasterBand(b + 1));
  copyRaster(*ds_, file_, options_, progress);
}

}  // namespace tinlod
