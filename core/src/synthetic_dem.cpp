// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/synthetic_dem.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gdal_handles.h"
#include "tinlod/error.h"
#include "tinlod/output_files.h"

namespace tinlod {
namespace {

constexpr float kNodata = -9999.0f;

// Hash-based value noise: smooth, deterministic, and the same on every platform.
double latticeValue(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t h = seed ^ (std::uint64_t(i) * 0x9E3779B97F4A7C15ULL) ^ (std::uint64_t(j) * 0xC2B2AE3D27D4EB4FULL);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33;
  return double(h >> 11) * 0x1.0p-53;
}

double smooth(double t) { return t * t * (3 - 2 * t); }

double valueNoise(double x, double y, std::uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  const double u = smooth(x - fx), v = smooth(y - fy);
  const double a = latticeValue(i, j, seed), b = latticeValue(i + 1, j, seed);
  const double c = latticeValue(i, j + 1, seed), d = latticeValue(i + 1, j + 1, seed);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

// Hills of several octaves on a ridge rising to the north-east (heights in metres).
double terrain(double x, double y, std::uint64_t seed) {
  double z = 0, amplitude = 400, frequency = 1.0 / 2500.0;
  for (int octave = 0; octave < 6; ++octave) {
    z += amplitude * valueNoise(x * frequency, y * frequency, seed + octave);
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  const double ridge = 300 * std::exp(-std::pow((x - y * 0.6 - 3000) / 1500.0, 2));
  return 600 + z + ridge + 0.03 * (x + y);
}

}  // namespace

Dem makeSyntheticDem(const SyntheticDemOptions& o, const ProgressRange& progress) {
  if (o.width < 2 || o.height < 2 || !(o.cellSize > 0))
    throw Error("a synthetic DEM needs at least 2 x 2 cells of positive size");
  Dem dem;
  dem.path = "synthetic DEM";
  dem.width = o.width;
  dem.height = o.height;
  dem.hasGeotransform = true;
  dem.geotransform = {400000.0, o.cellSize, 0.0, 5200000.0 + o.height * o.cellSize, 0.0, -o.cellSize};
  OGRSpatialReference utm32;
  utm32.importFromEPSG(32632);
  char* wkt = nullptr;
  utm32.exportToWkt(&wkt);
  dem.crsWkt = wkt;
  CPLFree(wkt);

  const double w = o.width * o.cellSize, h = o.height * o.cellSize;
  const double lakeX = 0.3 * w, lakeY = 0.35 * h, lakeR = 0.12 * std::min(w, h);
  const double lakeLevel = terrain(lakeX, lakeY, o.seed) - 30;
  const double voidX = 0.72 * w, voidY = 0.6 * h, voidR = 0.07 * std::min(w, h);
  dem.z.resize(std::size_t(o.width) * o.height);
  for (int row = 0; row < o.height; ++row) {
    if (row % 64 == 0) progress.report(double(row) / o.height, "Making the terrain");
    for (int col = 0; col < o.width; ++col) {
      const double x = (col + 0.5) * o.cellSize, y = (o.height - row - 0.5) * o.cellSize;
      double z = terrain(x, y, o.seed);
      const double lake = std::hypot(x - lakeX, y - lakeY) / lakeR;
      if (o.withLake && lake < 1.5)  // flat water, with shores blending into the hills
        z = lakeLevel + std::max(0.0, z - lakeLevel) * smooth(std::max(0.0, lake - 1) / 0.5);
      const double hole = std::hypot((x - voidX) / 1.6, y - voidY) / voidR;
      dem.z[std::size_t(row) * o.width + col] = (o.withVoid && hole < 1) ? NAN : float(z);
    }
  }
  return dem;
}

void writeDemGeoTiff(const Dem& dem, const std::string& path, bool overwrite, const ProgressRange& progress) {
  OutputFiles files(overwrite);
  const StagedFile& file = files.add(path, "output");
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  const char* options[] = {"COMPRESS=DEFLATE", "TILED=YES", nullptr};
  CPLPushErrorHandler(CPLQuietErrorHandler);  // GDAL would name the staging file
  DatasetPtr ds(driver->Create(file.staging.c_str(), dem.width, dem.height, 1, GDT_Float32,
                               const_cast<char**>(options)));  // closed on a cancel too
  CPLPopErrorHandler();
  if (!ds) throw Error("cannot create '" + path + "': " + inUserTerms(file, CPLGetLastErrorMsg()));
  double gt[6];
  for (int i = 0; i < 6; ++i) gt[i] = dem.geotransform[i];
  ds->SetGeoTransform(gt);
  if (!dem.crsWkt.empty()) ds->SetProjection(dem.crsWkt.c_str());
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(kNodata);
  // A strip of tile rows at a time: progress, and a cancel between strips.
  constexpr int kStrip = 256;
  std::vector<float> values;
  CPLErr err = CE_None;
  for (int row = 0; row < dem.height && err == CE_None; row += kStrip) {
    progress.report(0.9 * row / dem.height, "Writing the DEM");
    const int rows = std::min(kStrip, dem.height - row);
    values.assign(dem.z.begin() + std::ptrdiff_t(row) * dem.width, dem.z.begin() + std::ptrdiff_t(row + rows) * dem.width);
    for (float& v : values)
      if (std::isnan(v)) v = kNodata;
    err = band->RasterIO(GF_Write, 0, row, dem.width, rows, values.data(), dem.width, rows, GDT_Float32, 0, 0);
  }
  progress.report(0.9, "Writing the DEM");
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  ds.reset();  // closing writes the last blocks
  CPLPopErrorHandler();
  if (err != CE_None || CPLGetLastErrorType() >= CE_Failure)
    throw Error("cannot write '" + path + "': " + writeFailureInUserTerms(file, CPLGetLastErrorMsg()));
  files.commit();
}

}  // namespace tinlod
