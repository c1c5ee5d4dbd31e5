// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_files.h"
#include "tinlod/experiment.h"

#include <set>
#include <string>

#include "insertion_levels.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/sample_job.h"
#include "tinlod/version.h"

namespace tinlod {

void ExperimentOptions::validate() const {
  if (methods.empty() && !insert) throw Error("-methods: name at least one method (degree, normal, volume, error, insert)");
  if (methods.empty())
    throw Error("-methods: insert runs greedy insertion to the vertex counts of the delete methods' levels: name "
                "degree, normal, volume or error beside it");
  if (deletePcts.empty()) throw Error("-delete_pcts: name at least one delete percentage, e.g. 10,20");
  HierarchyOptions h;
  h.stopPct = stopPct;
  for (double p : deletePcts) {
    h.deletePct = p;
    h.validate();
  }
  sample.validateForHierarchy();
  accuracy.validate();
}

namespace {

// One DEM: the reference is made once and serves every run. Greedy insertion is run to
// every level's vertex count, and each level compared with it at its size. Returns the
// name of the CRS its rows' positions are in (the DEM's as read).
std::string runDem(const std::string& path, const ExperimentOptions& options, std::vector<LevelAccuracy>& rows,
                   const ProgressRange& progress) {
  const Dem dem = readDem(path, options.sample.band, progress.sub(0, 0.02), options.sample.validHeights);
  const Tin tin = sampleTin(dem, options.sample, progress.sub(0.02, 0.05));
  const CrsTransform toTin = CrsTransform::forDem(dem, options.sample.sourceSrs, options.sample.targetSrs, ProgressRange(Feedback{}, 0, 1));
  const AccuracyEvaluator evaluator(dem, tin, toTin, options.accuracy, progress.sub(0.05, 0.1));
  const double runs = double(options.methods.size() * options.deletePcts.size() + (options.insert ? 1 : 0));
  int run = 0;
  std::vector<LevelAccuracy> levels;
  for (Measure m : options.methods)
    for (double pct : options.deletePcts) {
      const ProgressRange part = progress.sub(0.1 + 0.9 * run / runs, 0.1 + 0.9 * (run + 1) / runs);
      ++run;
      HierarchyOptions h;
      h.measure = m, h.deletePct = pct, h.stopPct = options.stopPct;
      progress.inform(demName(path) + ": " + measureName(m) + ", delete " + std::to_string(static_cast<int>(pct)) + " %");
      const Hierarchy hierarchy = buildHierarchy(tin, dem, {}, h, part.sub(0, 0.3));
      for (LevelAccuracy& row : measureLevels(evaluator, hierarchy, demName(path), -1, nullptr, part.sub(0.3, 1)))
        levels.push_back(std::move(row));
    }
  std::vector<LevelAccuracy> inserted;
  if (options.insert) {
    const std::vector<std::size_t> counts = insertionCounts(levels);
    progress.inform(demName(path) + ": greedy insertion to the vertex count of every level (" +
                    std::to_string(counts.size()) + " sizes)");
    inserted = measureInsertionLevels(evaluator, dem, tin, toTin, counts, options.stopPct,
                                      progress.sub(0.1 + 0.9 * run / runs, 1));
    compareWithInsertion(levels, inserted);
  }
  for (std::vector<LevelAccuracy>* part : {&levels, &inserted})
    for (LevelAccuracy& row : *part) rows.push_back(std::move(row));
  return crsNameOf(evaluator.grid().crsWkt);
}

// Each DEM read and sampled once before the work: one that cannot be (not a raster, too
// small, a CRS that cannot be placed) fails the run at its start, not after the DEMs
// before it have taken their minutes or hours.
void checkDems(const std::vector<std::string>& dems, const ExperimentOptions& options, const ProgressRange& progress) {
  for (std::size_t i = 0; i < dems.size(); ++i) {
    const ProgressRange part = progress.sub(double(i) / dems.size(), double(i + 1) / dems.size());
    part.report(0, "Checking " + demName(dems[i]));
    const Dem dem = readDem(dems[i], options.sample.band, part.sub(0, 0.4), options.sample.validHeights);
    sampleTin(dem, options.sample, part.sub(0.4, 1));
  }
}

}  // namespace

AccuracyReport runExperiment(const std::vector<std::string>& dems, const ExperimentOptions& options,
                             const std::vector<std::string>& reportPaths, const Feedback& feedback) {
  options.validate();
  if (dems.empty()) throw Error("name at least one DEM");
  OutputFiles files(options.overwrite, datasetFiles(dems));
  std::vector<const StagedFile*> staged;
  for (const std::string& path : reportPaths) {
    checkAccuracyReportPath(path);
    staged.push_back(&files.add(path, "-report"));
  }
  const ProgressRange all(feedback, 0, 1);
  if (dems.size() > 1) checkDems(dems, options, all.sub(0, 0.05));
  const ProgressRange runs = dems.size() > 1 ? all.sub(0.05, 1) : all;
  std::vector<LevelAccuracy> rows;
  std::set<std::string> crsNames;
  for (std::size_t i = 0; i < dems.size(); ++i)
    crsNames.insert(runDem(dems[i], options, rows, runs.sub(double(i) / dems.size(), double(i + 1) / dems.size())));
  AccuracyReport report;
  // The rows' positions (max_error_x, max_error_y) are each in its DEM's CRS.
  report.crsName = crsNames.size() == 1 ? *crsNames.begin() : "each DEM's own";
  report.title = "The study's experiment over " + std::to_string(dems.size()) + (dems.size() == 1 ? " DEM" : " DEMs");
  report.reference = referenceName(options.accuracy.reference);
  report.step = options.accuracy.step;
  report.controlSpacing = options.accuracy.controlSpacing;
  report.generator = std::string("tinlod ") + kVersion + " experiment";
  report.rows = std::move(rows);
  for (const StagedFile* file : staged) writeAccuracyReport(report, *file);
  files.commit();
  all.finish("Done");
  return report;
}

}  // namespace tinlod
