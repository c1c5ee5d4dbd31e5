// SPDX-License-Identifier: GPL-3.0-or-later
#include <iostream>

#include "accuracy_arguments.h"
#include "commands.h"
#include "sample_arguments.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"

namespace tinlod::cli {
namespace {

const char* const kUsage =
    "tinlod accuracy DEM TIN.gpkg [-accuracy OUT.tif] [-level L] [-report R.html|.csv|.json] [-reference tin|dem] "
    "[-step n] [-control c] [-compare_insert] [-of format] [-co NAME=VALUE] [-b band] [-s_srs srs] [-valid_range min max] [-overwrite] [-q]";

const char* const kHelp = R"(Measures how well each level of a TIN hierarchy (or a TIN) made by tinlod represents
the original: heights and mean curvature of B-spline surfaces fitted to both, compared
at a grid of test points (the study's measure), with RMSE, mean and maximum error, Moran's
I of the error, and correlations of slope, aspect, Gaussian, profile and plan curvature.

Usage: tinlod accuracy DEM TIN.gpkg [options]

TIN.gpkg is a hierarchy of tinlod build, a TIN of tinlod sample, insert or lod, or the
catalogue of tinlod tiles (all its finished tiles, measured as one hierarchy, a tile at a time).
DEM is the raster the GeoPackage (or the catalogue's tiles) was made from.
  -b band          its band (default: the one the GeoPackage was sampled from)
  -s_srs srs       its CRS, when its file has none (as given to tinlod build)
  -overwrite       replace existing -accuracy and -report files (never the inputs)
  -valid_range min max
                   heights outside min..max metres are nodata (default: the range the
                   GeoPackage was made with, else -12000 9000)
  -q               quiet: no progress or table, warnings only

)";

}  // namespace

int accuracyCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp << kAccuracyHelp;
    return 0;
  }
  if (a.given("-level") && !a.given("-accuracy"))
    terminalFeedback(true).warning("-level chooses the level of the accuracy raster (-accuracy) and is unused without "
                                   "it: the report and the table have every level");
  AccuracyOutputs outputs = accuracyOutputs(a);
  outputs.overwrite = a.flag("-overwrite");
  const int band = a.integer("-b", 0);
  const std::string sourceSrs = a.text("-s_srs", "");
  const std::optional<HeightRange> validHeights = validRange(a);
  const bool quiet = a.flag("-q");
  const std::vector<std::string> files = a.operands(2, kUsage);
  if (quiet && outputs.rasterPath.empty() && outputs.reportPath.empty())  // minutes of work, and nothing to show
    throw Error("-q without -accuracy or -report would measure and show nothing: give one of them, or leave out -q "
                "for the table");
  const AccuracyReport report = runAccuracyJob(files[0], files[1], outputs, band, sourceSrs, terminalFeedback(quiet), validHeights);
  if (!quiet) {
    std::cout << "Reference: " << (report.reference == "tin" ? "the original TIN (level 0)" : "the DEM") << "\n";
    printAccuracy(report.rows, std::cout);
  }
  return 0;
}

}  // namespace tinlod::cli
