// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_support.h"

#include <ogr_spatialref.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace tinlod::test {
namespace {

struct TempRoot {
  fs::path path = fs::temp_directory_path() / ("tinlod-tests-" + std::to_string(getpid()));
  ~TempRoot() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

std::string wktOf(int epsg) {
  OGRSpatialReference srs;
  srs.importFromEPSG(epsg);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string out = wkt;
  CPLFree(wkt);
  return out;
}

std::string dataDir() {
  const char* env = std::getenv("TINLOD_TEST_DATA");
  const fs::path dir = env ? fs::path(env) : fs::path(TINLOD_SOURCE_DIR) / ".." / "shared" / "data";
  return fs::is_directory(dir) ? fs::canonical(dir).string() : std::string();
}

std::string tempDir() {
  static TempRoot root;
  static int counter = 0;
  const fs::path dir = root.path / std::to_string(++counter);
  fs::create_directories(dir);
  return dir.string();
}

Feedback RecordingFeedback::feedback() {
  Feedback f;
  f.warning = [this](const std::string& m) { warnings.push_back(m); };
  f.info = [this](const std::string& m) { infos.push_back(m); };
  return f;
}

bool RecordingFeedback::warned(const std::string& fragment) const {
  return std::any_of(warnings.begin(), warnings.end(),
                     [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
}

Dem makeDem(int width, int height, double cell, const std::function<float(int, int)>& heightAt) {
  Dem dem;
  dem.path = "test DEM";
  dem.width = width;
  dem.height = height;
  dem.hasGeotransform = true;
  dem.geotransform = {500000.0, cell, 0.0, 5000000.0, 0.0, -cell};
  dem.crsWkt = wktOf(32632);
  dem.z.resize(std::size_t(width) * height);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) dem.z[std::size_t(r) * width + c] = heightAt(r, c);
  return dem;
}

Dem makeGeographicDem(int width, int height, double lon0, double lat0) {
  Dem dem = makeDem(width, height, 1.0, [](int r, int c) { return float(100 + r + 2 * c); });
  dem.geotransform = {lon0, 1.0 / 1200, 0.0, lat0, 0.0, -1.0 / 1200};
  dem.crsWkt = wktOf(4326);
  return dem;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

Dem smallSyntheticDem() {
  SyntheticDemOptions o;
  o.width = 360;
  o.height = 300;
  o.cellSize = 25;
  return makeSyntheticDem(o);
}

std::string smallSyntheticDemFile() {
  static const std::string path = [] {
    const std::string p = tempDir() + "/small_dem.tif";
    writeDemGeoTiff(smallSyntheticDem(), p);
    return p;
  }();
  return path;
}

}  // namespace tinlod::test
