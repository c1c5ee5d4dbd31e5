// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_raster.h"

#include <gdal_priv.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "accuracy_raster_canvas.h"
#include "gdal_handles.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

GDALDriver& driverFor(const RasterWriteOptions& options) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options.format.c_str());
  if (!driver || !driver->GetMetadataItem(GDAL_DCAP_RASTER))
    throw Error("-of: '" + options.format + "' is not a GDAL raster format: use e.g. GTiff (see gdalinfo --formats)");
  if (!driver->GetMetadataItem(GDAL_DCAP_CREATECOPY) && !driver->GetMetadataItem(GDAL_DCAP_CREATE))
    throw Error("-of: GDAL cannot write " + options.format + " files: use e.g. GTiff");
  // A VRT would point at an in-memory raster gone with the run; MEM writes no file at all.
  const std::string name = driver->GetDescription();
  if (name == "VRT" || name == "MEM" || name == "MBTiles" || name == "WMS")
    throw Error("-of: " + name + " cannot hold the accuracy raster's pixels in a file: use e.g. GTiff");
  return *driver;
}

}  // namespace

void checkRasterFormat(const RasterWriteOptions& options) { driverFor(options); }

const char* const kAccuracyBandNames[kAccuracyBandCount] = {
    "elevation difference (simplified - reference), m", "mean curvature difference (simplified - reference), 1/m",
    "mean curvature of the reference, 1/m", "mean curvature of the simplified TIN, 1/m"};

void georeference(GDALDataset& ds, const TestGrid& grid) {
  double gt[6];
  std::copy(grid.geotransform.begin(), grid.geotransform.end(), gt);
  ds.SetGeoTransform(gt);
  if (!grid.crsWkt.empty()) ds.SetProjection(grid.crsWkt.c_str());
}

void BandStatistics::add(float value) {
  min_ = count_ ? std::min<double>(min_, value) : value;
  max_ = count_ ? std::max<double>(max_, value) : value;
  ++count_;
  sum_.add(value);
  squares_.add(double(value) * value);
}

void BandStatistics::store(GDALRasterBand& band, double pixels) const {
  if (count_ == 0) return;  // as ComputeStatistics, an all-nodata band has none
  const double mean = sum_.value() / double(count_);
  const double variance = std::max(0.0, squares_.value() / double(count_) - mean * mean);
  band.SetStatistics(min_, max_, mean, std::sqrt(variance));
  band.SetMetadataItem("STATISTICS_VALID_PERCENT", CPLSPrintf("%.4g", 100.0 * double(count_) / pixels));
}

void writeRasterWindow(GDALRasterBand& band, const Grid& grid, const TestRect& rect, int col0, int row0,
                       BandStatistics* statistics) {
  // Bands of rows at a time: a call per row would cost a tiled file a pass over its blocks
  // per row.
  constexpr int kRows = 256;
  const int width = rect.col1 - rect.col0;
  if (width <= 0) return;
  std::vector<float> rows(static_cast<std::size_t>(width) * std::min(kRows, std::max(rect.row1 - rect.row0, 0)));
  for (int r0 = rect.row0; r0 < rect.row1; r0 += kRows) {
    const int count = std::min(kRows, rect.row1 - r0);
    for (int r = r0; r < r0 + count; ++r)
      for (int c = rect.col0; c < rect.col1; ++c) {
        const double v = grid.at(c, r);
        float& out = rows[static_cast<std::size_t>(r - r0) * width + (c - rect.col0)];
        out = std::isfinite(v) ? static_cast<float>(v) : float(kAccuracyNodata);
        if (statistics && std::isfinite(v)) statistics->add(out);
      }
    if (band.RasterIO(GF_Write, col0 + rect.col0, row0 + r0, width, count, rows.data(), width, count, GDT_Float32, 0,
                      0) != CE_None)
      throw Error(std::string("cannot fill the accuracy raster: ") + CPLGetLastErrorMsg());
  }
}

Error rasterWriteError(const StagedFile& file) {
  return Error(file.option + ": cannot write the accuracy raster '" + file.path +
               "': " + inUserTerms(file, CPLGetLastErrorMsg()));
}

void closeRaster(DatasetPtr& out, const StagedFile& file) {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  out.reset();
  CPLPopErrorHandler();
  if (CPLGetLastErrorType() == CE_Failure) throw rasterWriteError(file);
}

namespace {

int gdalProgress(double fraction, const char*, void* data) {
  try {
    static_cast<const ProgressRange*>(data)->report(fraction, "Writing the accuracy raster");
    return TRUE;
  } catch (const Cancelled&) {
    return FALSE;
  }
}

}  // namespace

void copyRaster(GDALDataset& source, const StagedFile& file, const RasterWriteOptions& options,
                const ProgressRange& progress) {
  GDALDriver& driver = driverFor(options);
  CPLErrorReset();
  CPLStringList co;
  for (const std::string& o : options.creationOptions) co.AddString(o.c_str());
  // GDAL's own messages would name the staging file: kept quiet, then said in the user's terms.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  DatasetPtr out(driver.CreateCopy(file.staging.c_str(), &source, FALSE, co.List(), gdalProgress,
                                   const_cast<ProgressRange*>(&progress)));
  CPLPopErrorHandler();
  if (!out) {
    progress.report(1, "Writing the accuracy raster");  // a cancel, if that is what stopped GDAL
    throw rasterWriteError(file);
  }
  closeRaster(out, file);
}

}  // namespace tinlod
