// SPDX-License-Identifier: GPL-3.0-or-later
#include "accuracy_arguments.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>

#include "tinlod/error.h"

namespace tinlod::cli {

const char* const kAccuracyHelp = R"(Accuracy (the study's measure, and more):
  -accuracy OUT.tif  accuracy raster of one level on the DEM's grid: band 1 elevation
                     difference (simplified - reference, m), band 2 mean curvature difference,
                     bands 3 and 4 the reference's and the simplified TIN's mean curvature (1/m)
  -level L           the raster's level: 0 the original, -1 the coarsest (default -1)
  -report R          every level's statistics: R.csv, R.json or R.html (a page with plots)
  -reference r       tin: the original TIN, as in the study (default); dem: the DEM itself
  -step n            test points at every n-th DEM cell (default 1: every cell)
  -control c         B-spline control points every c test points (default 3): smaller
                     follows the TIN's facets, larger smooths over its triangles
  -compare_insert    also run greedy insertion over the same samples to exactly each
                     level's vertex count and measure it the same way: the report and the
                     table gain its RMSE and the ratio level RMSE / insert RMSE (1: as good
                     as greedy insertion at equal size, 2: twice its error)
  -of format         GDAL raster format of the raster (default: the one its extension
                     names, GTiff for .tif)
  -co NAME=VALUE     creation option of the raster format (repeatable)
)";

AccuracyOutputs accuracyOutputs(Arguments& a) {
  AccuracyOutputs o;
  o.rasterPath = a.text("-accuracy", "");
  o.rasterLevel = a.integer("-level", -1);
  o.reportPath = a.text("-report", "");
  o.options.reference = parseReference(a.text("-reference", referenceName(o.options.reference)));
  o.options.step = a.integer("-step", o.options.step);
  o.options.controlSpacing = a.integer("-control", o.options.controlSpacing);
  o.compareInsert = a.flag("-compare_insert");
  // As gdal_translate: the format the file's extension names, unless -of says another.
  o.raster.format = a.text("-of", "");
  if (o.raster.format.empty()) o.raster.format = o.rasterPath.empty() ? "GTiff" : rasterFormatFor(o.rasterPath);
  const std::string extension = std::filesystem::path(o.rasterPath).extension().string();
  if (o.raster.format.empty())
    throw Error("-accuracy '" + o.rasterPath + "': " +
                (extension.empty() ? std::string("a name without an extension names no raster format")
                                   : "no GDAL raster format writes files named '" + extension + "'") +
                ": name the file .tif, or give the format with -of");
  o.raster.creationOptions = a.repeated("-co");
  return o;
}

void printAccuracy(const std::vector<LevelAccuracy>& rows, std::ostream& out) {
  const bool insert =
      std::any_of(rows.begin(), rows.end(), [](const LevelAccuracy& r) { return std::isfinite(r.insertRmse); });
  out << std::setw(6) << "level" << std::setw(11) << "vertices" << std::setw(10) << "RMSE m" << std::setw(12)
      << "max err m" << std::setw(12) << "r height" << std::setw(12) << "r mean H" << std::setw(10) << "Moran I";
  if (insert) out << std::setw(12) << "insert RMSE" << std::setw(10) << "/ insert";
  out << "\n";
  for (const LevelAccuracy& row : rows) {
    out << std::setw(6) << row.level << std::setw(11) << row.vertices << std::fixed << std::setprecision(2)
        << std::setw(10) << row.rmse << std::setw(12) << row.maxAbsError << std::setprecision(6) << std::setw(12)
        << correlationOf(row, "elevation") << std::setw(12) << correlationOf(row, "mean_curvature") << std::setprecision(3) << std::setw(10)
        << row.moransI;
    if (insert) out << std::setprecision(2) << std::setw(12) << row.insertRmse << std::setw(10) << row.insertRatio;
    out << std::defaultfloat << "\n";
  }
  if (insert)
    out << "/ insert: the level's RMSE over that of greedy insertion over the same samples with as many vertices\n";
}

}  // namespace tinlod::cli
