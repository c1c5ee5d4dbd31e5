// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/accuracy_raster.h"

#include <gdal_priv.h>
#include <ogr_srs_api.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>

#include <unistd.h>

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

// What the driver makes of a raster like the accuracy raster (four bands of 32-bit floats,
// a fraction and the nodata value), written to memory and read back: some drivers take any
// raster and keep less (PNG bytes, XYZ one band) without an error.
std::string whatItKeeps(GDALDriver& driver, const RasterWriteOptions& options, const std::filesystem::path& target,
                        std::vector<std::string>& besides) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr probe(mem->Create("", 2, 2, kAccuracyBandCount, GDT_Float32, nullptr));
  const double gt[6] = {0, 1, 0, 2, 0, -1};
  probe->SetGeoTransform(const_cast<double*>(gt));
  probe->SetProjection(SRS_WKT_WGS84_LAT_LONG);  // so that a format writes its CRS's file too (EHdr's .prj)
  float values[4] = {0.25f, -1.5f, 1e-4f, float(kAccuracyNodata)};
  for (int b = 1; b <= kAccuracyBandCount; ++b) {
    probe->GetRasterBand(b)->SetNoDataValue(kAccuracyNodata);
    if (probe->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, 2, 2, values, 2, 2, GDT_Float32, 0, 0) != CE_None) return "";
  }
  const char* ext = driver.GetMetadataItem(GDAL_DMD_EXTENSION);
  // In a folder of its own on disk: some drivers (netCDF) write no virtual files, others
  // write sidecar files beside theirs.
  // One folder per probe: QGIS may run two algorithms at once in one process.
  static std::atomic<unsigned> probes{0};
  std::error_code ignored;
  const std::filesystem::path folder = std::filesystem::temp_directory_path(ignored) /
                                       ("tinlod_format_probe_" + std::to_string(::getpid()) + "_" + std::to_string(probes++));
  std::filesystem::create_directories(folder, ignored);
  const std::string path = (folder / (std::string("probe.") + (ext && *ext ? ext : "bin"))).string();
  CPLStringList co;
  for (const std::string& o : options.creationOptions) co.AddString(o.c_str());
  CPLPushErrorHandler(CPLQuietErrorHandler);
  DatasetPtr copy(driver.CreateCopy(path.c_str(), probe.get(), FALSE, co.List(), nullptr, nullptr));
  copy.reset();
  DatasetPtr back(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  std::string kept;
  if (!back) {
    kept = "GDAL wrote no such file";
  } else if (back->GetRasterCount() != kAccuracyBandCount) {
    kept = "its file reads back as " + std::to_string(back->GetRasterCount()) + " band" + (back->GetRasterCount() == 1 ? "" : "s");
  } else {
    float read[4] = {0, 0, 0, 0};
    GDALRasterBand* band = back->GetRasterBand(1);
    const GDALDataType type = band->GetRasterDataType();
    if (band->RasterIO(GF_Read, 0, 0, 2, 2, read, 2, 2, GDT_Float32, 0, 0) != CE_None || read[0] != values[0] ||
        read[1] != values[1] || read[2] != values[2])
      kept = std::string("its file keeps ") + GDALGetDataTypeName(type) + " pixels";
  }
  back.reset();
  CPLPopErrorHandler();
  // The probe's other files, named as the format names them beside `target`: "probe.hdr" is
  // "a.hdr" beside "a.bil", "probe.bil.xml" "a.bil.xml".
  const std::string main = std::filesystem::path(path).filename().string();
  for (const auto& entry : std::filesystem::directory_iterator(folder, ignored)) {
    const std::string name = entry.path().filename().string();
    const bool statistics = name.size() > 8 && name.compare(name.size() - 8, 8, ".aux.xml") == 0;
    if (name == main || statistics || name.rfind("probe", 0) != 0) continue;
    besides.push_back(name.rfind(main, 0) == 0 ? target.filename().string() + name.substr(main.size())
                                               : target.stem().string() + name.substr(5));
  }
  std::filesystem::remove_all(folder, ignored);
  return kept;
}

}  // namespace

void checkRasterFormat(const RasterWriteOptions& options) { driverFor(options); }

std::vector<std::string> checkRasterKeepsItsBands(const RasterWriteOptions& options, const std::string& path) {
  GDALDriver& driver = driverFor(options);
  std::vector<std::string> besides;
  const std::string kept = whatItKeeps(driver, options, path, besides);
  if (!kept.empty())
    throw Error("-of: " + std::string(driver.GetDescription()) + " cannot hold the accuracy raster (" +
                std::to_string(kAccuracyBandCount) + " bands of 32-bit floats): " + kept + "; use e.g. GTiff (.tif)");
  return besides;
}

std::string rasterFormatFor(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "tif" || ext == "tiff") return "GTiff";
  GDALAllRegister();
  GDALDriverManager& drivers = *GetGDALDriverManager();
  for (int i = 0; !ext.empty() && i < drivers.GetDriverCount(); ++i) {
    GDALDriver* d = drivers.GetDriver(i);
    if (!d->GetMetadataItem(GDAL_DCAP_RASTER) || (!d->GetMetadataItem(GDAL_DCAP_CREATE) && !d->GetMetadataItem(GDAL_DCAP_CREATECOPY)))
      continue;
    const char* list = d->GetMetadataItem(GDAL_DMD_EXTENSIONS);
    const CPLStringList extensions(CSLTokenizeString(list ? list : ""));
    for (int k = 0; k < extensions.size(); ++k)
      if (EQUAL(extensions[k], ext.c_str())) return d->GetDescription();
  }
  return {};
}

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
               "': " + writeFailureInUserTerms(file, CPLGetLastErrorMsg()));
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
