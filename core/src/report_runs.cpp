// SPDX-License-Identifier: GPL-3.0-or-later
#include "report_runs.h"

#include <algorithm>
#include <cmath>

#include "text_and_paths.h"

namespace tinlod {
namespace {

// Exact comparison is right: the percentages are parameters copied, never computed. NaN
// (greedy insertion has no delete percentage) is the same as NaN.
bool samePct(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

bool sameRun(const ReportRun& run, const LevelAccuracy& row) {
  return run.dem == row.dem && run.method == row.method && samePct(run.deletePct, row.deletePct) &&
         samePct(run.stopPct, row.stopPct);
}

// Four parts always, so that runs compare part by part; a missing percentage is "".
std::vector<std::string> nameParts(const ReportRun& run) {
  return {run.dem, run.method, std::isnan(run.deletePct) ? "" : "delete " + formatNumber(run.deletePct) + " %",
          std::isnan(run.stopPct) ? "" : "stop " + formatNumber(run.stopPct) + " %"};
}

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& part : parts)
    if (!part.empty()) out += (out.empty() ? "" : ", ") + part;
  return out;
}

// For each part of the name: whether every run has the same text there.
std::vector<bool> sharedParts(const std::vector<ReportRun>& runs) {
  std::vector<bool> shared(4, true);
  for (const ReportRun& run : runs)
    for (std::size_t i = 0; i < shared.size(); ++i) shared[i] = shared[i] && nameParts(run)[i] == nameParts(runs[0])[i];
  return shared;
}

}  // namespace

std::vector<ReportRun> groupRuns(const std::vector<LevelAccuracy>& rows) {
  std::vector<ReportRun> runs;
  for (const LevelAccuracy& row : rows) {
    auto run = std::find_if(runs.begin(), runs.end(), [&](const ReportRun& r) { return sameRun(r, row); });
    if (run == runs.end())
      run = runs.insert(runs.end(), ReportRun{row.dem, row.method, row.deletePct, row.stopPct, {}});
    run->levels.push_back(&row);
  }
  return runs;
}

std::string runName(const ReportRun& run) { return joined(nameParts(run)); }

std::vector<std::string> runLabels(const std::vector<ReportRun>& runs) {
  const std::vector<bool> shared = sharedParts(runs);
  std::vector<std::string> labels;
  for (const ReportRun& run : runs) {
    std::vector<std::string> own;
    const std::vector<std::string> parts = nameParts(run);
    for (std::size_t i = 0; i < parts.size(); ++i)
      if (!shared[i] || runs.size() == 1) own.push_back(parts[i]);
    labels.push_back(joined(own));
  }
  return labels;
}

std::string sharedRunParts(const std::vector<ReportRun>& runs) {
  if (runs.size() < 2) return {};
  const std::vector<bool> shared = sharedParts(runs);
  const std::vector<std::string> parts = nameParts(runs[0]);
  std::vector<std::string> common;
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (shared[i]) common.push_back(parts[i]);
  return joined(common);
}

std::vector<std::string> variableNames(const std::vector<LevelAccuracy>& rows) {
  std::vector<std::string> names;
  for (const LevelAccuracy& row : rows)
    for (const VariableComparison& v : row.variables)
      if (std::find(names.begin(), names.end(), v.name) == names.end()) names.push_back(v.name);
  return names;
}

const VariableComparison* findVariable(const LevelAccuracy& row, const std::string& name) {
  for (const VariableComparison& v : row.variables)
    if (v.name == name) return &v;
  return nullptr;
}

double correlationOf(const LevelAccuracy& row, const std::string& name) {
  const VariableComparison* v = findVariable(row, name);
  return v ? v->correlation : std::nan("");
}

}  // namespace tinlod
