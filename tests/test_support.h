// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/feedback.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tin.h"

namespace tinlod::test {

// ../shared/data beside the checkout, or $TINLOD_TEST_DATA; empty when absent.
std::string dataDir();
// The project's checkout, for tests that hold documentation to the code.
std::string sourceDir();

// A fresh folder for one test, removed when the test binary ends.
std::string tempDir();

// A Feedback that records warnings and information and never cancels.
struct RecordingFeedback {
  std::vector<std::string> warnings;
  std::vector<std::string> infos;
  Feedback feedback();
  bool warned(const std::string& fragment) const;
};

// An in-memory DEM in UTM zone 32N (EPSG:32632) with north-up cells of `cell` metres;
// `height(row, col)` gives the height, NaN for nodata.
Dem makeDem(int width, int height, double cell, const std::function<float(int, int)>& heightAt);

// A DEM of `cell` metres under a hand-made TIN (in a metric CRS), whose heights are the
// TIN's own at each cell centre (NaN off it), with each vertex placed in its grid (row,
// col, dcol, drow), as the sampler places the vertices it makes.
Dem demUnder(Tin& tin, double cell);

// A DEM whose cells are 1/1200 degree in EPSG:4326, upper-left corner at (lon0, lat0).
Dem makeGeographicDem(int width, int height, double lon0, double lat0);

// Rough hills in EPSG:4326 over longitudes lon0 to lon0 + width * cell and latitudes 90 - height *
// cell to the pole, written as a GeoTIFF `name` in a new temporary folder; its path.
std::string polarDemFile(const std::string& name, double lon0, int width, int height, double cell);

std::string readFile(const std::string& path);

// A shell command's exit code and what it printed on stdout and stderr.
struct CommandRun {
  int exitCode = -1;
  std::string out, err;
};
CommandRun runCommand(const std::string& command);
bool contains(const std::string& text, const std::string& fragment);

// The message of the tinlod::Error `run` throws; "no error" when it throws none, and the
// kind of anything else it throws.
std::string errorOf(const std::function<void()>& run);

// A small synthetic DEM for quick tests: 360 x 300 cells of 25 m, with its lake and void.
Dem smallSyntheticDem();
// The same DEM as a GeoTIFF, written once per test binary.
std::string smallSyntheticDemFile();

// A 60 x 50 ASCII grid of 1/1200 degree near Boulder, written into `dir` without a .prj: a
// file in degrees with no CRS, as SRTM's .asc often are. Returns its path.
std::string degreesWithoutCrs(const std::string& dir);

// The WKT of an EPSG CRS.
std::string wktOf(int epsg);

}  // namespace tinlod::test
