// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tinlod/output_files.h"

namespace tinlod {

// One terrain variable compared between the reference and a simplified surface.
struct VariableComparison {
  std::string name;          // "elevation", "mean_curvature", "gaussian_curvature", "slope", "aspect",
                             // "profile_curvature", "plan_curvature"
  std::size_t count = 0;     // test points compared
  double correlation = 0;    // r (circular r for aspect)
  double meanReference = 0, meanSimplified = 0;
  double stdReference = 0, stdSimplified = 0;
};

// The accuracy of one level of one run (one DEM, one method, one delete percentage).
struct LevelAccuracy {
  std::string dem;           // file name of the DEM
  std::string method;        // degree, volume, normal, error, insert
  double deletePct = 0, stopPct = 0;  // deletePct NaN for greedy insertion, which deletes nothing
  int level = 0;
  std::size_t vertices = 0, triangles = 0;
  double selectSeconds = 0, deleteSeconds = 0;
  double certifiedError = 0;  // the build's own maximum vertical error against level 0
  std::size_t testPoints = 0;
  double rmse = 0, meanError = 0, maxAbsError = 0, maxErrorX = 0, maxErrorY = 0;
  double moransI = 0;        // of the elevation error field
  // Greedy insertion over the same sampled TIN run to exactly this level's vertex count and
  // measured at the same test points (tinlod experiment; -compare_insert): its RMSE, and
  // rmse / insertRmse, above 1 when the level is further from the reference than greedy
  // insertion at equal size. NaN when not measured (level 0, the insertion's own rows).
  double insertRmse = std::numeric_limits<double>::quiet_NaN();
  double insertRatio = std::numeric_limits<double>::quiet_NaN();
  std::vector<VariableComparison> variables;
};

// The comparison of variable `name` in `row`, or nullptr.
const VariableComparison* findVariable(const LevelAccuracy& row, const std::string& name);

// Its correlation r, NaN when the row has no such variable.
double correlationOf(const LevelAccuracy& row, const std::string& name);

struct AccuracyReport {
  std::string title;
  std::string reference;     // "tin" (the original TIN, as in the study) or "dem"
  std::string crsName;       // the CRS of the locations
  int step = 1;              // test points every `step` DEM cells
  int controlSpacing = 3;    // B-spline control points every `controlSpacing` test points
  std::string generator;     // "tinlod 0.1.0"
  std::vector<LevelAccuracy> rows;
};

// Writes the report in the format its extension names: .csv (one row per level and
// run), .json, or .html (a self-contained page with SVG plots). Atomic: the file
// appears complete or not at all. Throws Error for another extension.
void writeAccuracyReport(const AccuracyReport& report, const std::string& path);
// The same into a file of a job's OutputFiles, moved into place with the job's other outputs.
void writeAccuracyReport(const AccuracyReport& report, const StagedFile& file);

// Throws Error, naming -report, for a path writeAccuracyReport could not write: an unknown
// extension, a missing or read-only folder. For checks before long work.
void checkAccuracyReportPath(const std::string& path);

// The extensions writeAccuracyReport understands, for messages: ".csv, .json or .html".
bool isAccuracyReportPath(const std::string& path);

}  // namespace tinlod
