// SPDX-License-Identifier: GPL-3.0-or-later
// The report as one self-contained HTML page: what was compared, the plots, and a table
// per run. Inline CSS and SVG only, so it opens offline, from an e-mail, in QGIS.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "accuracy_report_formats.h"
#include "number_text.h"
#include "report_plots.h"
#include "report_runs.h"
#include "svg_plot.h"

namespace tinlod {
namespace {

// Old WebKit (QGIS's) has no CSS grid: figures are inline blocks, as many per row as the
// window holds. The page takes the window's whole width: a level table with many variables
// is wider than two figures, and a cap on the page's width cut it.
const char* const kStyle = R"(*{box-sizing:border-box}
body{margin:0;background:#f3f4f6;color:#1f2328;font:15px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
main{padding:28px 20px 40px}
h1{font-size:28px;line-height:1.2;margin:0 0 6px}
h2{font-size:19px;margin:28px 0 12px}
h3{font-size:16px;margin:0 0 2px}
.lead,.sub,figcaption,footer{color:#57606a}
.lead{margin:0;font-size:16px}
.card{background:#fff;border:1px solid #d0d7de;border-radius:8px;padding:16px 20px;margin:0 0 16px}
.about h2{margin-top:0}
.about p{max-width:62em;margin:0 0 14px}
.facts{margin:0}
.facts div{display:inline-block;vertical-align:top;margin:0 36px 6px 0}
.facts dt{font-size:12px;text-transform:uppercase;letter-spacing:.05em;color:#57606a}
.facts dd{margin:0;font-weight:600}
.plots{font-size:0}
.plots h2,.plots figure{font-size:15px}
figure{display:inline-block;vertical-align:top;width:674px;max-width:100%;margin:0 16px 16px 0;padding:16px}
figure svg{display:block;width:100%;height:auto}
figcaption{font-size:13px;margin-top:8px}
.sub{font-size:13px;margin:0 0 10px}
.swatch{display:inline-block;width:12px;height:12px;border-radius:3px;margin-right:8px}
.scroll{overflow-x:auto}
table{border-collapse:collapse;font-size:13px;white-space:nowrap}
th,td{padding:5px 10px;text-align:right;border-bottom:1px solid #eaeef2}
th{background:#f6f8fa;font-weight:600;border-bottom-color:#d0d7de;vertical-align:bottom;white-space:normal;min-width:4.5em}
th.group{text-align:center;border-bottom-color:#eaeef2}
td{font-variant-numeric:tabular-nums}
tbody tr:nth-child(even){background:#fafbfc}
tbody tr:hover{background:#eaf2fb}
tr.base td{color:#57606a}
footer{font-size:13px;margin-top:24px}
@media print{body{background:#fff}.card{border:0}figure{page-break-inside:avoid}}
)";

const char* const kDash = "\u2013";  // an empty cell: the value does not exist

std::string esc(const std::string& text) { return escapeMarkup(text); }

// Three significant digits without an exponent: 0.0123, 1.23, 12.3, 1235. The digits
// are counted after rounding, so 9.999 is 10.0, not 10.00.
std::string measure(double v) {
  if (!std::isfinite(v)) return kDash;
  const std::string rounded = significantNumber(v, 3);
  double r = 0;
  std::from_chars(rounded.data(), rounded.data() + rounded.size(), r);
  if (r == 0) return "0";
  const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(std::fabs(r)))), 0, 6);
  return fixedNumber(r, decimals);
}

std::string referenceText(const std::string& reference) {
  if (reference == "tin") return "the original TIN (level 0)";
  if (reference == "dem") return "the DEM";
  return reference;
}

std::string variableTitle(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

std::string fact(const std::string& term, const std::string& value) {
  return "<div><dt>" + esc(term) + "</dt><dd>" + esc(value) + "</dd></div>\n";
}

std::string testPointSpacing(int step) {
  return step == 1 ? "on every DEM cell" : "every " + std::to_string(step) + " DEM cells";
}

std::string lead(const AccuracyReport& report, const std::vector<ReportRun>& runs) {
  const std::string runCount = std::to_string(runs.size()) + (runs.size() == 1 ? " run" : " runs");
  const std::string levelCount = std::to_string(report.rows.size()) + (report.rows.size() == 1 ? " level" : " levels");
  return "<p class=\"lead\">" +
         esc(runCount + " \u00b7 " + levelCount + " \u00b7 compared with " + referenceText(report.reference)) +
         "</p>\n";
}

std::string about(const AccuracyReport& report, bool comparedWithInsertion) {
  const std::string spacing = testPointSpacing(report.step);
  std::string out = "<section class=\"card about\">\n<h2>What this shows</h2>\n<p>";
  out += esc("Each level of each simplification run is compared with " + referenceText(report.reference) +
             " at test points " + spacing + ". Elevation error is the level's height minus the reference's. " +
             "Slope, aspect and the curvatures come from B-spline surfaces fitted to both, with a control point " +
             "every " + std::to_string(report.controlSpacing) + " test points.");
  out += "</p>\n<p>";
  out +=
      esc("r is the correlation coefficient between the reference's and the level's values at the test "
          "points (Pearson's; circular for aspect): 1 is a perfect match. Good levels all have r close to 1, "
          "so the plots show log10(1 \u2212 r), which spreads them apart: \u22125 is r = 0.99999, \u22123 is "
          "0.999, \u22122 is 0.99. Lower is better. Moran's I of the elevation error is near 1 when errors "
          "cluster in patches and near 0 when they scatter at random.");
  if (comparedWithInsertion)
    out += "</p>\n<p>" +
           esc("RMSE / insert is a level's RMSE divided by that of greedy insertion (Garland and Heckbert) over "
               "the same sampled TIN, run to exactly the level's number of vertices and measured at the same test "
               "points: 1 is as good as greedy insertion at equal size, 2 twice its error.");
  out += "</p>\n<dl class=\"facts\">\n";
  out += fact("Reference", referenceText(report.reference)) + fact("Test points", spacing) +
         fact("B-spline control points", "every " + std::to_string(report.controlSpacing) + " test points");
  if (!report.crsName.empty()) out += fact("Coordinates", report.crsName);
  if (!report.generator.empty()) out += fact("Written by", report.generator);
  return out + "</dl>\n</section>\n";
}

std::string plots(const std::vector<ReportRun>& runs) {
  std::string out = "<section class=\"plots\">\n<h2>Accuracy and time against size</h2>\n";
  for (const ReportPlot& p : reportPlots(runs))
    out += "<figure class=\"card\">\n" + renderSvg(p.plot) + "<figcaption>" + esc(p.caption) +
           "</figcaption>\n</figure>\n";
  return out + "</section>\n";
}

// `span` is " rowspan=\"2\"" for a column without a sub-heading.
std::string headerCell(const std::string& text, const std::string& tooltip, const std::string& span = "") {
  return "<th" + span + (tooltip.empty() ? "" : " title=\"" + esc(tooltip) + "\"") + ">" + esc(text) + "</th>";
}

// Two rows: the correlations share one heading, so each column only names its variable.
// `withInsert`: the columns of the comparison with greedy insertion at equal size.
std::string tableHead(const std::vector<std::string>& variables, bool withInsert) {
  const std::string both = " rowspan=\"2\"";
  std::string out = "<thead><tr>" + headerCell("Level", "0 is the original TIN", both) +
                    headerCell("Vertices", "", both) + headerCell("Triangles", "", both) +
                    headerCell("RMSE (m)", "root mean square elevation error at the test points", both);
  if (withInsert)
    out += headerCell("Insert RMSE (m)",
                      "RMSE of greedy insertion over the same sampled TIN with exactly this level's vertices", both) +
           headerCell("RMSE / insert", "this level's RMSE over greedy insertion's at the same size: above 1 is worse",
                      both);
  out += headerCell("Mean error (m)", "level minus reference: positive when the level is too high", both) +
         headerCell("Max |error| (m)", "largest absolute elevation error; hover a cell for where", both) +
         headerCell("Certified (m)", "the build's own bound on the vertical error against level 0", both) +
         headerCell("Moran's\u00a0I", "spatial autocorrelation of the elevation error", both);
  if (!variables.empty())
    out += "<th colspan=\"" + std::to_string(variables.size()) +
           "\" class=\"group\" title=\"correlation with the reference at the test points\">r with the reference</th>";
  out += headerCell("Select (s)", "seconds choosing the vertices to delete", both) +
         headerCell("Delete (s)", "seconds deleting them and retriangulating", both) + "</tr>\n<tr>";
  for (const std::string& name : variables) out += headerCell(variableTitle(name), "");
  return out + "</tr></thead>\n";
}

std::string cell(const std::string& text) { return "<td>" + esc(text) + "</td>"; }

std::string tableRow(const LevelAccuracy& l, const std::vector<std::string>& variables, bool withInsert) {
  const bool base = l.level == 0;
  std::string out = base ? "<tr class=\"base\">" : "<tr>";
  out += cell(std::to_string(l.level)) + cell(groupedCount(l.vertices)) + cell(groupedCount(l.triangles)) +
         cell(measure(l.rmse));
  if (withInsert) out += cell(measure(l.insertRmse)) + cell(measure(l.insertRatio));
  out += cell(measure(l.meanError));
  out += "<td title=\"" + esc("at " + fixedNumber(l.maxErrorX, 1) + ", " + fixedNumber(l.maxErrorY, 1)) + "\">" +
         esc(measure(l.maxAbsError)) + "</td>";
  out += cell(measure(l.certifiedError)) + cell(std::isfinite(l.moransI) ? fixedNumber(l.moransI, 3) : kDash);
  for (const std::string& name : variables) {
    const VariableComparison* v = findVariable(l, name);
    out += cell(v ? correlationText(v->correlation) : kDash);
  }
  return out + cell(base ? kDash : measure(l.selectSeconds)) + cell(base ? kDash : measure(l.deleteSeconds)) +
         "</tr>\n";
}

std::string testPointText(const ReportRun& run) {
  auto [least, most] = std::minmax_element(run.levels.begin(), run.levels.end(),
                                           [](auto a, auto b) { return a->testPoints < b->testPoints; });
  const std::string count =
      groupedCount((*least)->testPoints) +
      ((*least)->testPoints == (*most)->testPoints ? "" : "\u2013" + groupedCount((*most)->testPoints));
  return std::to_string(run.levels.size()) + (run.levels.size() == 1 ? " level" : " levels") + ", " + count +
         " test points per level";
}

std::string runTable(const ReportRun& run, int index, const std::vector<std::string>& variables, bool withInsert) {
  std::string out = "<div class=\"card\">\n<h3><span class=\"swatch\" style=\"background:" + runColour(index) +
                    "\"></span>" + esc(runName(run)) + "</h3>\n";
  out += "<p class=\"sub\">" + esc(testPointText(run)) + "</p>\n<div class=\"scroll\"><table>\n" +
         tableHead(variables, withInsert) + "<tbody>\n";
  for (const LevelAccuracy* l : run.levels) out += tableRow(*l, variables, withInsert);
  return out + "</tbody></table></div>\n</div>\n";
}

std::string tables(const AccuracyReport& report, const std::vector<ReportRun>& runs) {
  const std::vector<std::string> variables = variableNames(report.rows);
  const bool withInsert = knowsInsertRatio(runs);
  std::string out = "<section>\n<h2>Levels</h2>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) out += runTable(runs[i], static_cast<int>(i), variables, withInsert);
  return out + "</section>\n";
}

}  // namespace

void writeHtmlReport(const AccuracyReport& report, std::ostream& out) {
  const std::string title = report.title.empty() ? "Accuracy of simplified TINs" : report.title;
  const std::vector<ReportRun> runs = groupRuns(report.rows);
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>" << esc(title) << "</title>\n<style>\n"
      << kStyle << "</style>\n</head>\n<body>\n<main>\n"
      << "<header>\n<h1>" << esc(title) << "</h1>\n"
      << lead(report, runs) << "</header>\n"
      << about(report, knowsInsertRatio(runs));
  if (runs.empty())
    out << "<p class=\"card\">The report has no levels: nothing was compared.</p>\n";
  else
    out << plots(runs) << tables(report, runs);
  out << "<footer>"
      << esc("Written by " + (report.generator.empty() ? std::string("tinlod") : report.generator) +
             ". Hover over a point or a max error for details.")
      << "</footer>\n</main>\n</body>\n</html>\n";
}

}  // namespace tinlod
