// SPDX-License-Identifier: GPL-3.0-or-later
// The report as CSV: one row per level and run, for spreadsheets, R and pandas.
#include <cmath>
#include <string>
#include <vector>

#include "accuracy_report_formats.h"
#include "number_text.h"
#include "report_runs.h"

namespace tinlod {
namespace {

const char* const kLevelColumns[] = {"dem",         "method",    "delete_pct",   "stop_pct",        "level",
                                     "vertices",    "triangles", "select_s",     "delete_s",        "certified_error_m",
                                     "test_points", "rmse_m",    "mean_error_m", "max_abs_error_m", "max_error_x",
                                     "max_error_y", "morans_i",  "insert_rmse_m", "rmse_ratio_to_insert"};
const char* const kVariableSuffixes[] = {"_n", "_r", "_mean_ref", "_mean_simplified", "_std_ref", "_std_simplified"};

// RFC 4180: a field with a separator, quote or line break is quoted, quotes doubled.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// NaN (a statistic without enough points) is an empty field, which spreadsheets and
// pandas read as missing; infinity has no portable spelling either.
std::string csvNumber(double value) { return std::isfinite(value) ? roundTripNumber(value) : std::string(); }

std::vector<std::string> levelFields(const LevelAccuracy& r) {
  return {r.dem,
          r.method,
          csvNumber(r.deletePct),
          csvNumber(r.stopPct),
          std::to_string(r.level),
          std::to_string(r.vertices),
          std::to_string(r.triangles),
          csvNumber(r.selectSeconds),
          csvNumber(r.deleteSeconds),
          csvNumber(r.certifiedError),
          std::to_string(r.testPoints),
          csvNumber(r.rmse),
          csvNumber(r.meanError),
          csvNumber(r.maxAbsError),
          csvNumber(r.maxErrorX),
          csvNumber(r.maxErrorY),
          csvNumber(r.moransI),
          csvNumber(r.insertRmse),
          csvNumber(r.insertRatio)};
}

// A row without the variable gets empty fields, so every row has every column.
std::vector<std::string> variableFields(const VariableComparison* v) {
  if (!v) return std::vector<std::string>(std::size(kVariableSuffixes));
  return {std::to_string(v->count),     csvNumber(v->correlation),  csvNumber(v->meanReference),
          csvNumber(v->meanSimplified), csvNumber(v->stdReference), csvNumber(v->stdSimplified)};
}

void writeLine(std::ostream& out, const std::vector<std::string>& fields) {
  for (std::size_t i = 0; i < fields.size(); ++i) out << (i ? "," : "") << csvField(fields[i]);
  out << '\n';
}

std::vector<std::string> header(const std::vector<std::string>& variables) {
  std::vector<std::string> fields(std::begin(kLevelColumns), std::end(kLevelColumns));
  for (const std::string& name : variables)
    for (const char* suffix : kVariableSuffixes) fields.push_back(name + suffix);
  return fields;
}

}  // namespace

void writeCsvReport(const AccuracyReport& report, std::ostream& out) {
  const std::vector<std::string> variables = variableNames(report.rows);
  writeLine(out, header(variables));
  for (const LevelAccuracy& row : report.rows) {
    std::vector<std::string> fields = levelFields(row);
    for (const std::string& name : variables) {
      const std::vector<std::string> more = variableFields(findVariable(row, name));
      fields.insert(fields.end(), more.begin(), more.end());
    }
    writeLine(out, fields);
  }
}

}  // namespace tinlod
