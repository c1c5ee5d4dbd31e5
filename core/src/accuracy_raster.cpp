// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_raster.h"

#include <gdal_priv.h>

#include <cmath>
#include <filesystem>
#include <memory>

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

namespace {

void writeBand(GDALDataset& ds, int index, const Grid& grid, const char* description) {
  std::vector<float> row(grid.cols);
  GDALRasterBand* band = ds.GetRasterBand(index);
  band->SetDescription(description);
  band->SetNoDataValue(kAccuracyNodata);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c)
      row[c] = grid.valid(c, r) && std::isfinite(grid.at(c, r)) ? static_cast<float>(grid.at(c, r)) : float(kAccuracyNodata);
    if (band->RasterIO(GF_Write, 0, r, grid.cols, 1, row.data(), grid.cols, 1, GDT_Float32, 0, 0) != CE_None)
      throw Error(std::string("cannot fill the accuracy raster in memory: ") + CPLGetLastErrorMsg());
  }
  double min, max, mean, sd;
  CPLPushErrorHandler(CPLQuietErrorHandler);  // an all-nodata band has no statistics, and that is fine
  band->ComputeStatistics(false, &min, &max, &mean, &sd, nullptr, nullptr);
  CPLPopErrorHandler();
}

DatasetPtr inMemory(const AccuracyBands& bands, const TestGrid& grid) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr ds = DatasetPtr(mem->Create("", grid.cols, grid.rows, 4, GDT_Float32, nullptr));
  double gt[6];
  std::copy(grid.geotransform.begin(), grid.geotransform.end(), gt);
  ds->SetGeoTransform(gt);
  if (!grid.crsWkt.empty()) ds->SetProjection(grid.crsWkt.c_str());
  writeBand(*ds, 1, bands.elevationDifference, "elevation difference (simplified - reference), m");
  writeBand(*ds, 2, bands.meanCurvatureDifference, "mean curvature difference (simplified - reference), 1/m");
  writeBand(*ds, 3, bands.meanCurvatureReference, "mean curvature of the reference, 1/m");
  writeBand(*ds, 4, bands.meanCurvatureSimplified, "mean curvature of the simplified TIN, 1/m");
  return ds;
}

int gdalProgress(double fraction, const char*, void* data) {
  try {
    static_cast<const ProgressRange*>(data)->report(fraction, "Writing the accuracy raster");
    return TRUE;
  } catch (const Cancelled&) {
    return FALSE;
  }
}

}  // namespace

void writeAccuracyRaster(const AccuracyBands& bands, const TestGrid& grid, const StagedFile& file,
                         const RasterWriteOptions& options, const ProgressRange& progress) {
  GDALDriver& driver = driverFor(options);
  const DatasetPtr mem = inMemory(bands, grid);
  CPLErrorReset();
  CPLStringList co;
  for (const std::string& o : options.creationOptions) co.AddString(o.c_str());
  // GDAL's own messages would name the staging file: kept quiet, then said in the user's terms.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  DatasetPtr out(driver.CreateCopy(file.staging.c_str(), mem.get(), FALSE, co.List(), gdalProgress,
                                   const_cast<ProgressRange*>(&progress)));
  CPLPopErrorHandler();
  const auto failed = [&] {
    return Error(file.option + ": cannot write the accuracy raster '" + file.path +
                 "': " + inUserTerms(file, CPLGetLastErrorMsg()));
  };
  if (!out) {
    progress.report(1, "Writing the accuracy raster");  // a cancel, if that is what stopped GDAL
    throw failed();
  }
  CPLPushErrorHandler(CPLQuietErrorHandler);
  out.reset();
  CPLPopErrorHandler();
  if (CPLGetLastErrorType() == CE_Failure) throw failed();
}

}  // namespace tinlod
