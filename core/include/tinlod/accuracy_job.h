// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/accuracy_raster.h"
#include "tinlod/accuracy_report.h"
#include "tinlod/feedback.h"
#include "tinlod/height_range.h"
#include "tinlod/hierarchy.h"
#include "tinlod/output_files.h"

namespace tinlod {

// What to measure and where to write it, shared by `tinlod accuracy`, `tinlod build`
// and the QGIS algorithms.
struct AccuracyOutputs {
  AccuracyOptions options;
  std::string rasterPath;      // empty: no raster
  RasterWriteOptions raster;
  int rasterLevel = -1;        // the level of the raster; -1: the coarsest
  std::string reportPath;      // empty: no report; .csv, .json or .html
  // Greedy insertion over the same sampled TIN run to each level's exact vertex count and
  // measured the same way: fills every level's insertRmse and insertRatio (-compare_insert).
  bool compareInsert = false;
  // Replace existing files (runAccuracyJob; tinlod build's own -overwrite covers its
  // accuracy outputs).
  bool overwrite = false;

  bool wanted() const { return !rasterPath.empty() || !reportPath.empty(); }
  // Fails early, before hours of work, on a bad format, extension or level.
  void validate() const;
};

// The staged raster and report of a job's OutputFiles; null when not asked for.
struct AccuracyFiles {
  const StagedFile* raster = nullptr;
  const StagedFile* report = nullptr;
};

// Adds the raster and report `outputs` asks for to `files`: checked now, before the work.
AccuracyFiles stageAccuracyFiles(const AccuracyOutputs& outputs, OutputFiles& files);

// The row of level `level` before it is measured: what the hierarchy `h` says of it (`s`, its
// statistics, or those a catalogue's tiles pool).
LevelAccuracy levelRow(const Hierarchy& h, const std::string& demName, int level, const LevelStats& s);

// Every level of `h` measured against the evaluator's reference, one row each; the
// bands of `rasterLevel` (-1: the coarsest) go to `bands` when it is not null.
std::vector<LevelAccuracy> measureLevels(const AccuracyEvaluator& evaluator, const Hierarchy& h, const std::string& demName,
                                         int rasterLevel, const BandStrips* bands, const ProgressRange& progress);

AccuracyReport makeReport(const AccuracyEvaluator& evaluator, const std::string& title, const std::string& crsName,
                          std::vector<LevelAccuracy> rows);
AccuracyReport makeReport(const AccuracyOptions& options, const std::string& title, const std::string& crsName,
                          std::vector<LevelAccuracy> rows);

// Measures every level of `h` (sampled from `dem`), compares it with greedy insertion at its
// size when asked, and writes the raster and report asked for.
AccuracyReport measureAndWrite(const Dem& dem, const Hierarchy& h, const CrsTransform& toTin, const AccuracyOutputs& outputs,
                               const AccuracyFiles& files, const ProgressRange& progress);

// The whole `tinlod accuracy` job: a DEM and the hierarchy (or TIN) GeoPackage made from
// it. `band` 0 takes the band the file was sampled from; `sourceSrs` names the DEM's CRS
// when its file has none; no `validHeights` takes the range the file was sampled with, so
// that the same cells are nodata (the default range for files that record none).
AccuracyReport runAccuracyJob(const std::string& demPath, const std::string& hierarchyPath, const AccuracyOutputs& outputs,
                              int band, const std::string& sourceSrs, const Feedback& feedback,
                              const std::optional<HeightRange>& validHeights = std::nullopt);

// "dem.tif" from "/data/dem.tif": how reports name a DEM.
std::string demName(const std::string& path);

// A CRS's name for reports ("WGS 84 / UTM zone 32N"), "no CRS" without one.
std::string crsNameOf(const std::string& wkt);

}  // namespace tinlod
