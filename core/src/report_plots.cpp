// SPDX-License-Identifier: GPL-3.0-or-later
#include "report_plots.h"

#include <algorithm>
#include <cmath>

#include "number_text.h"

namespace tinlod {
namespace {

// What one plot takes from a level: the y value (NaN to leave the level out) and how
// to say it in the marker's tooltip.
struct Quantity {
  double (*value)(const LevelAccuracy&);
  std::string (*describe)(double);
};

std::string metres(double v) { return significantNumber(v, 4) + " m"; }
std::string seconds(double v) { return significantNumber(v, 3) + " s"; }

// Below this, 1 - r is the rounding of sums over up to millions of test points, not a
// difference: the reference against itself comes out as 0.9999999999999999, which would
// plot at -16 and squash every other point against the top of the chart.
constexpr double kRoundingOfR = 1e-13;

// log10(1 - r) of `variable`: NaN where it is missing or r is 1 within rounding (the
// reference itself).
template <const char* Variable>
double logOneMinusR(const LevelAccuracy& l) {
  const VariableComparison* v = findVariable(l, Variable);
  return v && 1 - v->correlation > kRoundingOfR ? std::log10(1 - v->correlation) : NAN;
}

std::string rOf(double logOneMinusR) { return "r = " + correlationText(1 - std::pow(10.0, logOneMinusR)); }

constexpr char kElevation[] = "elevation";
constexpr char kMeanCurvature[] = "mean_curvature";

double rmse(const LevelAccuracy& l) { return l.rmse; }
double insertRatio(const LevelAccuracy& l) { return l.insertRatio; }
std::string ratio(double v) { return "RMSE " + significantNumber(v, 3) + " x greedy insertion's"; }
double maxError(const LevelAccuracy& l) { return l.maxAbsError; }
// Level 0 is the original TIN: nothing was selected or deleted to make it.
double selectSeconds(const LevelAccuracy& l) { return l.level >= 1 ? l.selectSeconds : NAN; }
double deleteSeconds(const LevelAccuracy& l) { return l.level >= 1 ? l.deleteSeconds : NAN; }

PlotLine lineOf(const ReportRun& run, int index, const std::string& label, const Quantity& q, bool dashed) {
  PlotLine line{index, dashed, {}};
  for (const LevelAccuracy* l : run.levels) {
    const double y = q.value(*l);
    if (std::isnan(y)) continue;
    line.points.push_back({static_cast<double>(l->vertices), y,
                           label + ": level " + std::to_string(l->level) + ", " + groupedCount(l->vertices) +
                               " vertices, " + q.describe(y)});
  }
  return line;
}

// One vertex axis for all plots, so they line up when compared: logarithmic when the
// report's levels span more than a factor of 20 (a time plot without level 0 may not).
AxisKind vertexAxis(const std::vector<ReportRun>& runs) {
  std::vector<double> vertices;
  for (const ReportRun& run : runs)
    for (const LevelAccuracy* l : run.levels) vertices.push_back(static_cast<double>(l->vertices));
  return spansWideRange(vertices) ? AxisKind::Log : AxisKind::Linear;
}

// One line per run of `solid`, and a dashed one of `dashed` when given.
LinePlot plotOf(const std::vector<ReportRun>& runs, const Quantity& solid, const Quantity* dashed) {
  LinePlot plot;
  plot.subtitle = sharedRunParts(runs);
  plot.runLabels = runLabels(runs);
  plot.x = {"Vertices", TickStyle::Count, vertexAxis(runs), false};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int index = static_cast<int>(i);
    plot.lines.push_back(lineOf(runs[i], index, plot.runLabels[i], solid, false));
    if (dashed) plot.lines.push_back(lineOf(runs[i], index, plot.runLabels[i], *dashed, true));
  }
  return plot;
}

ReportPlot correlationPlot(const std::vector<ReportRun>& runs, double (*value)(const LevelAccuracy&),
                           const std::string& title, const std::string& caption) {
  ReportPlot out{plotOf(runs, {value, rOf}, nullptr), caption};
  out.plot.title = title;
  out.plot.note = "lower is better";
  out.plot.y = {"log10(1 - r)", TickStyle::Plain, AxisKind::Linear, false};
  out.plot.yIsLogOneMinusR = true;
  return out;
}

ReportPlot pairPlot(const std::vector<ReportRun>& runs, const Quantity& solid, const Quantity& dashed,
                    const std::string& solidKey, const std::string& dashedKey) {
  ReportPlot out{plotOf(runs, solid, &dashed), {}};
  out.plot.solidKey = solidKey;
  out.plot.dashedKey = dashedKey;
  return out;
}

ReportPlot errorPlot(const std::vector<ReportRun>& runs) {
  ReportPlot out = pairPlot(runs, {rmse, metres}, {maxError, metres}, "RMSE", "largest |error|");
  out.plot.title = "Elevation error against vertices";
  out.plot.note = "lower is better";
  out.plot.y = {"Error (m)", TickStyle::Plain, AxisKind::Auto, true};
  out.caption =
      "Root mean square (solid) and largest absolute (dashed) difference between each level's "
      "height and the reference's at the test points, in metres.";
  return out;
}

ReportPlot insertRatioPlot(const std::vector<ReportRun>& runs) {
  ReportPlot out{plotOf(runs, {insertRatio, ratio}, nullptr), {}};
  out.plot.title = "RMSE over greedy insertion's at the same size";
  out.plot.note = "lower is better";
  out.plot.y = {"RMSE / insert RMSE", TickStyle::Plain, AxisKind::Linear, true};
  out.caption =
      "Each level's RMSE divided by that of greedy insertion over the same sampled TIN run to exactly the "
      "level's number of vertices and measured at the same test points: 1 is as good as greedy insertion, "
      "2 twice its error.";
  return out;
}

ReportPlot timePlot(const std::vector<ReportRun>& runs) {
  ReportPlot out =
      pairPlot(runs, {selectSeconds, seconds}, {deleteSeconds, seconds}, "selecting vertices", "deleting them");
  out.plot.title = "Time per level against vertices";
  out.plot.y = {"Seconds", TickStyle::Plain, AxisKind::Auto, true};
  out.caption =
      "Seconds each level spent choosing the vertices to delete (solid) and deleting them and "
      "retriangulating (dashed). Level 0, the original TIN, has neither.";
  return out;
}

}  // namespace

std::string correlationText(double r) {
  if (!std::isfinite(r)) return "\u2013";
  if (r >= 1) return "1";
  const int digits = std::clamp(static_cast<int>(std::ceil(-std::log10(1 - r))) + 2, 3, 12);
  return significantNumber(r, digits);
}

bool knowsInsertRatio(const std::vector<ReportRun>& runs) {
  for (const ReportRun& run : runs)
    for (const LevelAccuracy* l : run.levels)
      if (std::isfinite(l->insertRatio)) return true;
  return false;
}

std::vector<ReportPlot> reportPlots(const std::vector<ReportRun>& runs) {
  std::vector<ReportPlot> plots{
      correlationPlot(runs, logOneMinusR<kElevation>, "Elevation: log10(1 - r) against vertices",
                      "How closely each level's heights follow the reference's at the test points: "
                      "\u22125 is r = 0.99999, \u22122 is r = 0.99 (the right axis gives r). Lower is better."),
      correlationPlot(runs, logOneMinusR<kMeanCurvature>, "Mean curvature: log10(1 - r) against vertices",
                      "The same for mean curvature from the B-spline surfaces. A second derivative, it "
                      "shows simplification much earlier than elevation does."),
      errorPlot(runs)};
  if (knowsInsertRatio(runs)) plots.push_back(insertRatioPlot(runs));
  plots.push_back(timePlot(runs));
  return plots;
}

}  // namespace tinlod
