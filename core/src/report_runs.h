// SPDX-License-Identifier: GPL-3.0-or-later
// Private: how the report formats see an AccuracyReport's rows: as runs (one DEM, one
// method, one delete and stop percentage) of levels, and as a set of variable names.
#pragma once

#include <string>
#include <vector>

#include "tinlod/accuracy_report.h"

namespace tinlod {

struct ReportRun {
  std::string dem, method;
  double deletePct = 0, stopPct = 0;
  std::vector<const LevelAccuracy*> levels;  // in the order of the report's rows
};

// The rows grouped by (dem, method, delete %, stop %), runs in order of first appearance:
// a caller may interleave the levels of several runs.
std::vector<ReportRun> groupRuns(const std::vector<LevelAccuracy>& rows);

// "alps.tif, degree, delete 20 %, stop 5 %".
std::string runName(const ReportRun& run);

// Names that tell the runs apart: only the parts of runName that differ between runs
// (all of it for a single run), so legends stay short.
std::vector<std::string> runLabels(const std::vector<ReportRun>& runs);

// The parts of runName that all runs share ("alps.tif, delete 20 %"); empty for a single run,
// whose label already says everything.
std::string sharedRunParts(const std::vector<ReportRun>& runs);

// Every variable name in the rows: the first row's in its order, then any that only later
// rows have, in order of first appearance.
std::vector<std::string> variableNames(const std::vector<LevelAccuracy>& rows);

}  // namespace tinlod
