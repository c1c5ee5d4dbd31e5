// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "accuracy_arguments.h"
#include "commands.h"
#include "sample_arguments.h"
#include "terminal_feedback.h"
#include "tinlod/error.h"
#include "tinlod/experiment.h"

namespace tinlod::cli {
namespace {

const char* const kUsage =
    "tinlod experiment DEM [DEM ...] -report R.html|.csv|.json [-methods m,m,...] [-delete_pcts p,p,...] "
    "[-stop_pct s] [-reference tin|dem] [-step n] [-control c] [sampling options] [-overwrite] [-q]";

const char* const kHelp = R"(Runs the study's experiment: every DEM is sampled once, simplified by every method
with every delete percentage down to the stop percentage, and every level's accuracy
is measured (as tinlod accuracy does). One combined report; no other file is written.

Usage: tinlod experiment DEM [DEM ...] -report R [options]

  -report R          R.html (plots of all runs), R.csv or R.json; repeat it for several formats
  -methods list      comma-separated (default degree,normal,volume,error,insert); insert is
                     greedy insertion over the same sampled TIN, run to exactly the vertex
                     count of every level (above 0) of the other methods' hierarchies and
                     measured the same way; each level then also reports insert's RMSE at
                     its size and the ratio level RMSE / insert RMSE (1: as good as greedy
                     insertion with as many vertices, 2: twice its error). insert needs at
                     least one other method
  -delete_pcts list  comma-separated delete percentages (default 10,20)
  -stop_pct s        stop percentage (default 5)
  -reference r       tin (default, as in the study) or dem
  -step n            test points every n-th DEM cell (default 1)
  -control c         B-spline control points every c test points (default 3)
  Sampling options as tinlod sample: -b, -s_srs, -t_srs, -block, -jitter, -seed,
                     -valid_range
  -overwrite         replace existing report files
  -q                 quiet: no progress, warnings only
)";

// A list option's items: none empty, none twice (each would be run and reported again).
std::vector<std::string> splitList(const std::string& text, const std::string& option, const std::string& example) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty() || std::find(out.begin(), out.end(), item) != out.end())
      throw Error(option + " '" + text + "': " + (item.empty() ? "an empty item" : "'" + item + "' twice") +
                  "; write e.g. " + option + " " + example);
    out.push_back(item);
  }
  if (out.empty()) throw Error(option + " is empty; write e.g. " + option + " " + example);
  return out;
}

}  // namespace

int experimentCommand(std::vector<std::string> args) {
  Arguments a(std::move(args));
  if (a.flag("--help") || a.flag("-h")) {
    std::cout << kHelp;
    return 0;
  }
  ExperimentOptions o;
  const bool methodsGiven = a.given("-methods"), pctsGiven = a.given("-delete_pcts");
  const std::string methods = a.text("-methods", "");
  if (methodsGiven) {
    o.methods.clear();
    o.insert = false;
    for (const std::string& m : splitList(methods, "-methods", "volume,insert")) {
      if (m == "insert")
        o.insert = true;
      else if (m == "degree" || m == "normal" || m == "volume" || m == "error")
        o.methods.push_back(parseMeasure(m));
      else
        throw Error("-methods: unknown method '" + m + "': choose from degree, normal, volume, error and insert");
    }
  }
  const std::string pcts = a.text("-delete_pcts", "");
  if (pctsGiven) {
    o.deletePcts.clear();
    for (const std::string& p : splitList(pcts, "-delete_pcts", "10,20")) {
      char* end = nullptr;  // all of it a number: stod would read "10abc" as 10
      o.deletePcts.push_back(std::strtod(p.c_str(), &end));
      if (*end != '\0' || !std::isfinite(o.deletePcts.back()))
        throw Error("-delete_pcts: '" + p + "' is not a number; write e.g. -delete_pcts 10,20");
    }
  }
  o.stopPct = a.number("-stop_pct", o.stopPct);
  const std::vector<std::string> reports = a.repeated("-report");  // one run, several formats
  o.accuracy.reference = parseReference(a.text("-reference", referenceName(o.accuracy.reference)));
  o.accuracy.step = a.integer("-step", o.accuracy.step);
  o.accuracy.controlSpacing = a.integer("-control", o.accuracy.controlSpacing);
  o.sample = sampleOptions(a);
  o.overwrite = a.flag("-overwrite");
  const bool quiet = a.flag("-q");
  const std::vector<std::string> dems = a.someOperands(kUsage);
  if (reports.empty()) throw Error("-report is required: name the report file, e.g. -report experiment.html");
  const AccuracyReport r = runExperiment(dems, o, reports, terminalFeedback(quiet));
  if (!quiet) std::cout << "Wrote " << r.rows.size() << " levels of " << dems.size() << " DEMs to " << reports.front()
                        << (reports.size() > 1 ? " and " + std::to_string(reports.size() - 1) + " more" : "") << std::endl;
  return 0;
}

}  // namespace tinlod::cli
