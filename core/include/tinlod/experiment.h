// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/accuracy_report.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy_options.h"
#include "tinlod/sample_options.h"

namespace tinlod {

// The study's experiment: every DEM simplified by every method with every delete
// percentage down to the stop percentage, each level's accuracy measured.
struct ExperimentOptions {
  std::vector<Measure> methods{Measure::Degree, Measure::Normal, Measure::Volume, Measure::Error};
  // Greedy insertion over the same sampled TIN (the study's comparator), run to exactly the
  // vertex count of every level above 0 of every hierarchy; each level's RMSE is then
  // divided by insertion's at its size (LevelAccuracy::insertRatio). Needs a method.
  bool insert = true;
  std::vector<double> deletePcts{10, 20};
  double stopPct = 5;
  SampleOptions sample;
  AccuracyOptions accuracy;
  bool overwrite = false;  // replace existing reports
  void validate() const;  // throws Error naming the option
};

// Runs the experiment and writes one combined report in each of `reportPaths` (.csv, .json
// or .html: one run, several formats), all or none of them. Nothing else is written.
AccuracyReport runExperiment(const std::vector<std::string>& dems, const ExperimentOptions& options,
                             const std::vector<std::string>& reportPaths, const Feedback& feedback);

}  // namespace tinlod
