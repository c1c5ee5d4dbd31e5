// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/dem_reader.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <future>
#include <memory>
#include <optional>

#include "gdal_handles.h"
#include "parallel_blocks.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// GDAL's drivers that can decode blocks on several threads (GeoTIFF, since 3.6) do so
// when told at opening; a user's own GDAL_NUM_THREADS is kept.
GDALDataset* openWithDecodingThreads(const std::string& path) {
  const bool given = CPLGetConfigOption("GDAL_NUM_THREADS", nullptr) != nullptr;
  if (!given) CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", std::to_string(threadCount()).c_str());
  auto* ds = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  if (!given) CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", nullptr);
  return ds;
}

// GDAL's failures while the cells are read are said once, in the error thrown with its last
// message (a VRT's missing source printed "ERROR 4: src/a.tif: No such file or directory"
// above it); its warnings show as usual.
void CPL_STDCALL failuresAside(CPLErr level, CPLErrorNum number, const char* message) {
  if (level < CE_Failure) CPLDefaultErrorHandler(level, number, message);
}

DatasetPtr openRaster(const std::string& path) {
  GDALAllRegister();
  if (plainPathMissing(path)) throw Error("DEM '" + path + "' does not exist" + tildeHint(path));
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDataset* ds = openWithDecodingThreads(path);
  const std::string gdalMessage = CPLGetLastErrorMsg();
  CPLPopErrorHandler();
  if (!ds) {
    std::string msg = "'" + path + "' is not a raster GDAL can read";
    if (!gdalMessage.empty()) msg += " (" + gdalMessage + ")";
    throw Error(msg);
  }
  if (ds->GetRasterCount() < 1) {
    // A netCDF or HDF file of several variables: GDAL reads each as a subdataset of its own.
    std::string subdatasets;
    int count = 0;
    for (char** item = ds->GetMetadata("SUBDATASETS"); item && *item; ++item) {
      const std::string entry = *item;
      const std::size_t name = entry.find("_NAME=");
      if (name == std::string::npos) continue;
      if (++count <= 3) subdatasets += (count > 1 ? ", " : "") + entry.substr(name + 6);
    }
    GDALClose(ds);
    if (count > 0)
      throw Error("'" + path + "' holds " + std::to_string(count) + " rasters (subdatasets), not one: give one of them as "
                  "the DEM, e.g. " + subdatasets + (count > 3 ? " ..." : ""));
    throw Error("'" + path + "' has no raster band");
  }
  return DatasetPtr(ds);
}

void readGeoreferencing(GDALDataset& ds, Dem& dem, const ProgressRange& progress) {
  double gt[6];
  dem.hasGeotransform = ds.GetGeoTransform(gt) == CE_None;
  if (dem.hasGeotransform) {
    if (gt[2] != 0.0 || gt[4] != 0.0)
      throw Error("'" + dem.path +
                  "' has a rotated geotransform, which tinlod does not support: "
                  "make it north-up first, e.g. gdalwarp in.tif northup.tif");
    if (gt[1] == 0.0 || gt[5] == 0.0)
      throw Error("'" + dem.path + "' has a zero pixel size in its geotransform");
    for (int i = 0; i < 6; ++i) dem.geotransform[i] = gt[i];
  } else if (ds.GetGCPCount() > 0) {
    // Its cells' places come from a warp GDAL has not made: as 1 x 1 metre in no CRS, the TIN
    // would be nowhere.
    throw Error("'" + dem.path + "' is georeferenced by " + std::to_string(ds.GetGCPCount()) +
                " ground control points, not a geotransform: warp it to a grid first, e.g. gdalwarp in.tif warped.tif");
  } else if (const bool rpc = ds.GetMetadata("RPC") != nullptr; rpc || ds.GetMetadata("GEOLOCATION")) {
    throw Error("'" + dem.path + "' is georeferenced by " + (rpc ? "rational polynomial coefficients (RPC)" : "a geolocation array") +
                ", not a geotransform: warp it to a grid first, e.g. gdalwarp " + (rpc ? "-rpc" : "-geoloc") + " in.tif warped.tif");
  } else {
    progress.warn("'" + dem.path + "' has no geotransform: cells are taken as 1 x 1 metre");
  }
}

std::string crsWkt(GDALDataset& ds) {
  std::string out;
  if (const OGRSpatialReference* srs = ds.GetSpatialRef()) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    out = wkt ? wkt : "";
    CPLFree(wkt);
  }
  return out;
}

// Marks missing cells as NaN. Declared nodata is compared as float, the type the
// heights are read in, so that e.g. -3.4e38 given in double still matches.
void applyMask(GDALRasterBand& band, Dem& dem) {
  const int flags = band.GetMaskFlags();
  if (flags & GMF_NODATA) {
    int has = 0;
    const float nodata = static_cast<float>(band.GetNoDataValue(&has));
    if (has) {
      for (float& v : dem.z)
        if (v == nodata) v = NAN;
    }
    return;
  }
  if (flags & GMF_ALL_VALID) return;
  std::vector<unsigned char> mask(dem.z.size());
  const CPLErrorHandlerPusher failures(failuresAside);
  if (band.GetMaskBand()->RasterIO(GF_Read, dem.window.colOffset, dem.window.rowOffset, dem.width, dem.height, mask.data(), dem.width,
                                   dem.height, GDT_Byte, 0, 0) != CE_None)
    throw Error("cannot read the mask of '" + dem.path + "': " + CPLGetLastErrorMsg());
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i] == 0) dem.z[i] = NAN;
}

// Metres per unit of the band's heights, from its unit name; 0 when unknown.
double metresPerUnit(std::string unit) {
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters")
    return 1.0;
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
  if (unit == "us-ft" || unit == "ftus" || unit == "us survey foot" || unit == "foot_us" || unit == "us_survey_foot")
    return 1200.0 / 3937.0;
  if (unit == "cm" || unit == "centimetre" || unit == "centimeter") return 0.01;
  if (unit == "mm" || unit == "millimetre" || unit == "millimeter") return 0.001;
  if (unit == "km" || unit == "kilometre" || unit == "kilometer") return 1000.0;
  return 0.0;
}

// A county DEM in a State Plane CRS in feet often gives its heights in feet too, without
// naming the unit: taken as metres, they would stand 3.28 times too tall.
void warnOfFeetCrsWithoutHeightUnit(const Dem& dem, const std::string& unit, const ProgressRange& progress) {
  OGRSpatialReference srs;
  if (!unit.empty() || dem.crsWkt.empty() || srs.importFromWkt(dem.crsWkt.c_str()) != OGRERR_NONE || !srs.IsProjected())
    return;
  const double metres = srs.GetLinearUnits();
  if (std::fabs(metres - 0.3048) > 1e-4 && std::fabs(metres - 1200.0 / 3937.0) > 1e-4) return;
  const char* name = srs.GetName();
  progress.warn("'" + dem.path + "' is in " + (name ? name : "a CRS") + ", whose x and y are in feet, and names no unit "
                "for its heights: they are taken as metres; if they are feet, say so (gdal_edit -units ft, or US-ft)");
}

// Packed DEMs store heights as integers with a scale and offset, and some store them in
// feet: both are turned into metres here, once.
void toMetres(GDALRasterBand& band, Dem& dem, const ProgressRange& progress) {
  int hasScale = 0, hasOffset = 0;
  const double scale = band.GetScale(&hasScale), offset = band.GetOffset(&hasOffset);
  const char* unitType = band.GetUnitType();
  const std::string unit = unitType ? unitType : "";
  double perUnit = metresPerUnit(unit);
  warnOfFeetCrsWithoutHeightUnit(dem, unit, progress);
  if (perUnit == 0.0) {
    progress.warn("'" + dem.path + "' gives its heights in '" + unit + "', a unit tinlod does not know: taken as metres");
    perUnit = 1.0;
  } else if (perUnit != 1.0) {
    progress.inform("'" + dem.path + "' gives its heights in '" + unit + "': converted to metres");
  }
  const double a = (hasScale ? scale : 1.0) * perUnit, b = (hasOffset ? offset : 0.0) * perUnit;
  if (a == 1.0 && b == 0.0) return;
  for (float& v : dem.z) v = static_cast<float>(v * a + b);  // NaN stays NaN
}

// Reading a complex band as Float32 would quietly keep its real part.
void refuseComplex(GDALRasterBand& band, const Dem& dem) {
  const GDALDataType type = band.GetRasterDataType();
  if (GDALDataTypeIsComplex(type))
    throw Error("'" + dem.path + "' band " + std::to_string(dem.band) + " holds complex numbers (" +
                GDALGetDataTypeName(type) + "), not heights: choose a band of heights with -b");
}

// A band of an image (red, a palette index...) reads as numbers like any other: an RGB
// photo made a 15-level "hierarchy" of red values without a word.
void warnOfImageBand(GDALRasterBand& band, const Dem& dem, const ProgressRange& progress) {
  const GDALColorInterp colour = band.GetColorInterpretation();
  if (colour == GCI_Undefined || colour == GCI_GrayIndex) return;
  progress.warn("'" + dem.path + "' band " + std::to_string(dem.band) + " is an image's " +
                GDALGetColorInterpretationName(colour) + " band (its colour interpretation), not heights: its values "
                "are taken as metres; give a DEM, or -b for a band of heights");
}

void dropImplausibleHeights(Dem& dem, const HeightRange& valid, const ProgressRange& progress) {
  const std::size_t dropped = dropHeightsOutside(dem.z, valid);
  if (dropped == 0) return;
  progress.warn("ignored " + std::to_string(dropped) + (dropped == 1 ? " cell" : " cells") + " of '" + dem.path +
                "' with heights outside " + valid.text() + " (treated as nodata); widen with -valid_range");
}

void readHeights(GDALRasterBand& band, Dem& dem, const ProgressRange& progress) {
  dem.z.resize(static_cast<std::size_t>(dem.width) * dem.height);
  const int chunk = std::max(1, (1 << 22) / std::max(1, dem.width));  // about 4 M cells a read
  const CPLErrorHandlerPusher failures(failuresAside);
  for (int row = 0; row < dem.height; row += chunk) {
    const int rows = std::min(chunk, dem.height - row);
    float* dst = dem.z.data() + static_cast<std::size_t>(row) * dem.width;
    if (band.RasterIO(GF_Read, dem.window.colOffset, dem.window.rowOffset + row, dem.width, rows, dst, dem.width, rows,
                      GDT_Float32, 0, 0) !=
        CE_None)
      throw Error("cannot read '" + dem.path + "': " + CPLGetLastErrorMsg());
    progress.report(double(row + rows) / dem.height, "Reading DEM");
  }
}

void checkValidCells(const Dem& dem, const HeightRange& valid) {
  const std::size_t count = dem.validCount();
  const std::string band = "'" + dem.path + "' band " + std::to_string(dem.band);
  if (count == 0)
    throw Error(band + " has no valid cell: all its " + std::to_string(dem.z.size()) +
                " cells are nodata (declared nodata, NaN, masked, or heights outside " + valid.text() +
                "; -valid_range widens that)");
  if (count < 3)
    throw Error(band + " has " + std::to_string(count) + " valid cell(s): a TIN needs at least 3");
}

}  // namespace

namespace {

// The heights from a handle of their own (a GDAL handle serves one thread at a time),
// decoded on other cores, while this thread takes the CRS from `ds`: a GeoTIFF's comes
// from PROJ's database, 10-20 ms when cold, and PROJ's caches are per thread, so this
// thread, which makes the transform to the TIN's CRS next, is the one to warm them.
// In turn when the file cannot be opened twice (a stream) or one core is all there is.
void readHeightsBesideCrs(GDALDataset& ds, int bandNumber, Dem& dem, const ProgressRange& progress) {
  DatasetPtr second;
  if (threadCount() > 1) {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    second.reset(openWithDecodingThreads(dem.path));
    CPLPopErrorHandler();
    // The same raster, or the first handle alone (a file replaced between the two opens).
    if (second && (second->GetRasterCount() < bandNumber || second->GetRasterXSize() != ds.GetRasterXSize() ||
                   second->GetRasterYSize() != ds.GetRasterYSize()))
      second.reset();
  }
  if (!second) {
    readHeights(*ds.GetRasterBand(bandNumber), dem, progress);
    dem.crsWkt = crsWkt(ds);
    return;
  }
  std::future<void> heights = std::async(std::launch::async, [&] { readHeights(*second->GetRasterBand(bandNumber), dem, progress); });
  try {
    dem.crsWkt = crsWkt(ds);
  } catch (...) {
    heights.wait();
    throw;
  }
  heights.get();
}

Dem readBand(const std::string& path, int bandNumber, const CellWindow* window, const ProgressRange& progress,
             const HeightRange& valid, const MemoryUse* use = nullptr) {
  valid.validate();
  DatasetPtr ds = openRaster(path);
  if (bandNumber < 1 || bandNumber > ds->GetRasterCount())
    throw Error("invalid band number " + std::to_string(bandNumber) + ": '" + path + "' has bands 1 to " +
                std::to_string(ds->GetRasterCount()));
  Dem dem;
  dem.path = path;
  dem.band = bandNumber;
  dem.width = ds->GetRasterXSize();
  dem.height = ds->GetRasterYSize();
  dem.window.fullWidth = dem.width, dem.window.fullHeight = dem.height;
  GDALRasterBand* band = ds->GetRasterBand(bandNumber);
  refuseComplex(*band, dem);
  warnOfImageBand(*band, dem, progress);
  readGeoreferencing(*ds, dem, progress);
  dem.window.fullGeotransform = dem.geotransform;
  if (window) {
    if (window->xoff < 0 || window->yoff < 0 || window->xsize < 1 || window->ysize < 1 ||
        window->xoff + window->xsize > dem.width || window->yoff + window->ysize > dem.height)
      throw Error("the window of " + std::to_string(window->xsize) + " x " + std::to_string(window->ysize) +
                  " cells at column " + std::to_string(window->xoff) + ", row " + std::to_string(window->yoff) +
                  " is not inside '" + path + "' (" + std::to_string(dem.width) + " x " + std::to_string(dem.height) +
                  " cells)");
    dem.window.colOffset = window->xoff, dem.window.rowOffset = window->yoff;
    dem.width = window->xsize, dem.height = window->ysize;
    dem.geotransform[0] += window->xoff * dem.geotransform[1];
    dem.geotransform[3] += window->yoff * dem.geotransform[5];
  }
  if (use) checkMemory(path, dem.width, dem.height, *use, progress);
  readHeightsBesideCrs(*ds, bandNumber, dem, progress);
  applyMask(*band, dem);  // on the stored values, where declared nodata applies
  toMetres(*band, dem, progress);
  dropImplausibleHeights(dem, valid, progress);  // in metres, as the range is given
  return dem;
}

}  // namespace

Dem readDem(const std::string& path, int bandNumber, const ProgressRange& progress, const HeightRange& valid,
            const MemoryUse* use) {
  Dem dem = readBand(path, bandNumber, nullptr, progress, valid, use);
  checkValidCells(dem, valid);
  return dem;
}

Dem readDemWindow(const std::string& path, int band, const CellWindow& window, const ProgressRange& progress,
                  const HeightRange& valid) {
  return readBand(path, band, &window, progress, valid);
}

void cropDem(Dem& dem, int col0, int row0, int width, int height) {
  if (col0 < 0 || row0 < 0 || width < 1 || height < 1 || col0 + width > dem.width || row0 + height > dem.height)
    throw Error("internal error: cropping a DEM outside itself");
  for (int r = 0; r < height; ++r) {
    const float* from = dem.z.data() + static_cast<std::size_t>(row0 + r) * dem.width + col0;
    std::copy(from, from + width, dem.z.begin() + static_cast<std::ptrdiff_t>(r) * width);
  }
  dem.z.resize(static_cast<std::size_t>(width) * height);
  dem.z.shrink_to_fit();
  dem.geotransform[0] += col0 * dem.geotransform[1];
  dem.geotransform[3] += row0 * dem.geotransform[5];
  dem.window.colOffset += col0, dem.window.rowOffset += row0;
  dem.width = width, dem.height = height;
}

}  // namespace tinlod
