// SPDX-License-Identifier: GPL-3.0-or-later
#include "accuracy_raster_canvas.h"

#include <cpl_string.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "tinlod/error.h"

namespace tinlod {

AccuracyRasterCanvas::AccuracyRasterCanvas(const TestGrid& grid, const StagedFile& file, RasterWriteOptions options)
    // Named apart from the output (whose name may take all of a file system's 255 bytes), in
    // the output's own staging folder.
    : file_(file), options_(std::move(options)), scratch_((file.staging.parent_path() / ".tinlod-canvas.tif").string()) {
  checkRasterFormat(options_);
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  // Tiled, so that a tile's window touches few blocks, as tall as the strips written, so
  // that a strip writes whole block rows; sparse, so that blocks no tile writes (nodata all
  // through) take no room and no time; not compressed, since a block a window fills in part
  // would be decompressed and compressed again; BIGTIFF for national grids.
  CPLStringList co;
  co.AddString("TILED=YES");
  co.AddString("BLOCKXSIZE=256");
  co.AddString(("BLOCKYSIZE=" + std::to_string(kComparedRows)).c_str());
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
  // GDAL's messages name the scratch file: kept quiet, and said in the user's terms (fail).
  const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);
  try {
    for (int b = 0; b < kAccuracyBandCount; ++b)
      writeRasterWindow(*ds_->GetRasterBand(b + 1), *grids[b], rect, col0, row0, &statistics_[b]);
  } catch (const Error&) {
    fail();
  }
  // To disk at once: GDAL's block cache would otherwise hold up to GDAL_CACHEMAX of it.
  ds_->FlushCache();
  if (CPLGetLastErrorType() == CE_Failure) fail();
}

void AccuracyRasterCanvas::fail() const { throw rasterWriteError(file_); }

void AccuracyRasterCanvas::finish(const ProgressRange& progress) {
  const double pixels = double(ds_->GetRasterXSize()) * ds_->GetRasterYSize();
  for (int b = 0; b < kAccuracyBandCount; ++b) statistics_[b].store(*ds_->GetRasterBand(b + 1), pixels);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options_.format.c_str());
  // CreateCopy would read the whole scratch file through GDAL's block cache.
  if (driver && driver->GetMetadataItem(GDAL_DCAP_CREATE)) copyByRows(*driver, progress);
  else copyRaster(*ds_, file_, options_, progress);
}

void AccuracyRasterCanvas::copyByRows(GDALDriver& driver, const ProgressRange& progress) {
  const int cols = ds_->GetRasterXSize(), rows = ds_->GetRasterYSize();
  CPLStringList co;
  for (const std::string& o : options_.creationOptions) co.AddString(o.c_str());
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);  // said in the user's terms below
  DatasetPtr out(driver.Create(file_.staging.c_str(), cols, rows, kAccuracyBandCount, GDT_Float32, co.List()));
  CPLPopErrorHandler();
  if (!out) fail();
  double gt[6];
  ds_->GetGeoTransform(gt);
  out->SetGeoTransform(gt);
  if (const char* wkt = ds_->GetProjectionRef(); wkt && *wkt) out->SetProjection(wkt);
  for (int b = 1; b <= kAccuracyBandCount; ++b) {
    GDALRasterBand& from = *ds_->GetRasterBand(b);
    GDALRasterBand& to = *out->GetRasterBand(b);
    to.SetDescription(from.GetDescription());
    to.SetNoDataValue(kAccuracyNodata);
    to.SetMetadata(from.GetMetadata());
  }
  // Whole blocks of the output at a time, about 2^22 pixels (16 MB), one band at a time:
  // GDAL's cache then holds a band of rows of the scratch file and of the output.
  int blockCols = 0, blockRows = 0;
  out->GetRasterBand(1)->GetBlockSize(&blockCols, &blockRows);
  blockRows = std::max(blockRows, 1);
  const int step = blockRows * std::max(1, (1 << 22) / std::max(1, cols) / blockRows);
  std::vector<float> buffer(static_cast<std::size_t>(cols) * std::min(step, rows));
  for (int r0 = 0; r0 < rows; r0 += step) {
    const int count = std::min(step, rows - r0);
    CPLErrorReset();
    for (int b = 1; b <= kAccuracyBandCount; ++b) {
      if (ds_->GetRasterBand(b)->RasterIO(GF_Read, 0, r0, cols, count, buffer.data(), cols, count, GDT_Float32, 0, 0) !=
              CE_None ||
          out->GetRasterBand(b)->RasterIO(GF_Write, 0, r0, cols, count, buffer.data(), cols, count, GDT_Float32, 0, 0) !=
              CE_None)
        fail();
      ds_->GetRasterBand(b)->FlushCache();
      out->GetRasterBand(b)->FlushCache();
      if (CPLGetLastErrorType() == CE_Failure) fail();
    }
    progress.report(double(r0 + count) / rows, "Writing the accuracy raster");
  }
  CPLErrorReset();  // every band of rows was checked
  closeRaster(out, file_);
}

}  // namespace tinlod
