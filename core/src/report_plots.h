// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the accuracy report's plots, one line (or two) per run against the number
// of vertices, as in the study's figures.
#pragma once

#include <string>
#include <vector>

#include "report_runs.h"
#include "svg_plot.h"

namespace tinlod {

struct ReportPlot {
  LinePlot plot;
  std::string caption;  // what to read from it, for the page under the plot
};

// Elevation r and mean curvature r as log10(1 - r), RMSE and max error, RMSE over greedy
// insertion's (when some level has it), and select and delete seconds, each against vertices.
std::vector<ReportPlot> reportPlots(const std::vector<ReportRun>& runs);

// Whether some level of `runs` was compared with greedy insertion at its size.
bool knowsInsertRatio(const std::vector<ReportRun>& runs);

// r with digits enough to show how far it is from 1: 0.99999, 0.9968, 0.5.
std::string correlationText(double r);

}  // namespace tinlod
