// SPDX-License-Identifier: GPL-3.0-or-later
// The report as JSON: the same numbers as the CSV, nested as runs of levels, for
// scripts that want the structure rather than a flat table.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "accuracy_report_formats.h"
#include "number_text.h"
#include "text_and_paths.h"
#include "report_runs.h"

namespace tinlod {
namespace {

// JSON has no NaN or infinity: a statistic without enough points is null.
std::string jsonNumber(double value) { return std::isfinite(value) ? roundTripNumber(value) : "null"; }

// Two-space indented JSON with the commas where they belong, so the writing code below
// reads as the document's structure.
class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}
  void beginObject() { open(nullptr, '{'); }
  void beginObject(const std::string& key) { open(&key, '{'); }
  void beginArray(const std::string& key) { open(&key, '['); }
  void end(char bracket) {
    const bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline();
    out_ << bracket;
  }
  void text(const std::string& key, const std::string& value) { raw(key, jsonString(value)); }
  void number(const std::string& key, double value) { raw(key, jsonNumber(value)); }
  void count(const std::string& key, long long value) { raw(key, std::to_string(value)); }

 private:
  void open(const std::string* key, char bracket) {
    item(key);
    out_ << bracket;
    first_.push_back(true);
  }
  void raw(const std::string& key, const std::string& json) {
    item(&key);
    out_ << json;
  }
  void item(const std::string* key) {
    if (!first_.empty()) {
      out_ << (first_.back() ? "" : ",");
      first_.back() = false;
      newline();
    }
    if (key) out_ << jsonString(*key) << ": ";
  }
  void newline() { out_ << '\n' << std::string(2 * first_.size(), ' '); }

  std::ostream& out_;
  std::vector<bool> first_;  // per open bracket: nothing written inside it yet
};

void writeVariable(JsonWriter& json, const VariableComparison& v) {
  json.beginObject(v.name);
  json.count("n", static_cast<long long>(v.count));
  json.number("r", v.correlation);
  json.number("mean_reference", v.meanReference);
  json.number("mean_simplified", v.meanSimplified);
  json.number("std_reference", v.stdReference);
  json.number("std_simplified", v.stdSimplified);
  json.end('}');
}

void writeLevel(JsonWriter& json, const LevelAccuracy& l) {
  json.beginObject();
  json.count("level", l.level);
  json.count("vertices", static_cast<long long>(l.vertices));
  json.count("triangles", static_cast<long long>(l.triangles));
  json.number("select_s", l.selectSeconds);
  json.number("delete_s", l.deleteSeconds);
  json.number("certified_error_m", l.certifiedError);
  json.count("test_points", static_cast<long long>(l.testPoints));
  json.number("rmse_m", l.rmse);
  json.number("mean_error_m", l.meanError);
  json.number("max_abs_error_m", l.maxAbsError);
  json.number("max_error_x", l.maxErrorX);
  json.number("max_error_y", l.maxErrorY);
  json.number("morans_i", l.moransI);
  json.number("insert_rmse_m", l.insertRmse);
  json.number("rmse_ratio_to_insert", l.insertRatio);
  json.beginObject("variables");
  for (const VariableComparison& v : l.variables) writeVariable(json, v);
  json.end('}');
  json.end('}');
}

void writeRun(JsonWriter& json, const ReportRun& run) {
  json.beginObject();
  json.text("dem", run.dem);
  json.text("method", run.method);
  json.number("delete_pct", run.deletePct);
  json.number("stop_pct", run.stopPct);
  json.beginArray("levels");
  for (const LevelAccuracy* level : run.levels) writeLevel(json, *level);
  json.end(']');
  json.end('}');
}

}  // namespace

void writeJsonReport(const AccuracyReport& report, std::ostream& out) {
  JsonWriter json(out);
  json.beginObject();
  json.text("title", report.title);
  json.text("reference", report.reference);
  json.text("crs", report.crsName);
  json.count("step", report.step);
  json.count("control_spacing", report.controlSpacing);
  json.text("generator", report.generator);
  json.beginArray("runs");
  for (const ReportRun& run : groupRuns(report.rows)) writeRun(json, run);
  json.end(']');
  json.end('}');
  out << '\n';
}

}  // namespace tinlod
