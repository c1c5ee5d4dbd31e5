// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_support.h"

#include <ogr_spatialref.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tinlod/error.h"

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

std::string sourceDir() { return TINLOD_SOURCE_DIR; }

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

std::string polarDemFile(const std::string& name, double lon0, int width, int height, double cell) {
  // One hill and a valley across the DEM, rough by +-20 m as a real one is.
  Dem dem = makeDem(width, height, 1, [width, height](int r, int c) {
    const double rough = std::sin(r * 12.9898 + c * 78.233) * 43758.5453;
    return float(500 + 500 * std::sin(6.3 * c / width) * std::cos(4.1 * r / height) + 40 * (rough - std::floor(rough) - 0.5));
  });
  dem.geotransform = {lon0, cell, 0, 90, 0, -cell};
  dem.crsWkt = wktOf(4326);
  const std::string path = tempDir() + "/" + name;
  writeDemGeoTiff(dem, path);
  return path;
}

Dem makeGeographicDem(int width, int height, double lon0, double lat0) {
  Dem dem = makeDem(width, height, 1.0, [](int r, int c) { return float(100 + r + 2 * c); });
  dem.geotransform = {lon0, 1.0 / 1200, 0.0, lat0, 0.0, -1.0 / 1200};
  dem.crsWkt = wktOf(4326);
  return dem;
}

std::string errorOf(const std::function<void()>& run) {
  try {
    run();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not a tinlod::Error: ") + e.what();
  }
  return "no error";
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

CommandRun runCommand(const std::string& command) {
  const std::string dir = tempDir();
  const int status = std::system((command + " >" + dir + "/out 2>" + dir + "/err").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(dir + "/out"), readFile(dir + "/err")};
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

std::string smallSyntheticDemFile() {
  static const std::string path = [] {
    const std::string p = tempDir() + "/small_dem.tif";
    writeDemGeoTiff(smallSyntheticDem(), p);
    return p;
  }();
  return path;
}

std::string degreesWithoutCrs(const std::string& dir) {
  const std::string path = dir + "/nocrs.asc";
  std::ofstream out(path);
  out << "ncols 60\nnrows 50\nxllcorner -105.3\nyllcorner 40.0\ncellsize 0.000833333333\nNODATA_value -9999\n";
  for (int r = 0; r < 50; ++r) {
    for (int c = 0; c < 60; ++c) out << 1600 + r + 2 * c + 3 * std::sin(0.4 * r) * std::cos(0.3 * c) << ' ';
    out << '\n';
  }
  return path;
}

Dem demUnder(Tin& tin, double cell) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const TinVertex& v : tin.vertices) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
  const int width = static_cast<int>(std::ceil((x1 - x0) / cell)) + 1, height = static_cast<int>(std::ceil((y1 - y0) / cell)) + 1;
  // Cell (row, col) is centred at (x0 + col cell, y1 - row cell).
  Dem dem = makeDem(width, height, cell, [](int, int) { return NAN; });
  dem.geotransform = {x0 - cell / 2, cell, 0, y1 + cell / 2, 0, -cell};
  for (TinVertex& v : tin.vertices) {
    const double c = (v.x - x0) / cell, r = (y1 - v.y) / cell;
    v.col = static_cast<int>(std::lround(c)), v.row = static_cast<int>(std::lround(r));
    v.dcol = static_cast<float>(c - v.col), v.drow = static_cast<float>(r - v.row);
  }
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      const double x = x0 + col * cell, y = y1 - row * cell;
      for (const Triangle& t : tin.triangles) {
        const TinVertex &a = tin.vertices[t[0]], &b = tin.vertices[t[1]], &c = tin.vertices[t[2]];
        const double d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / d;
        const double wc = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / d;
        if (wb < -1e-12 || wc < -1e-12 || wb + wc > 1 + 1e-12) continue;
        dem.z[static_cast<std::size_t>(row) * width + col] = static_cast<float>(a.z + wb * (b.z - a.z) + wc * (c.z - a.z));
        break;
      }
    }
  return dem;
}

}  // namespace tinlod::test
