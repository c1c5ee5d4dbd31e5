// SPDX-License-Identifier: GPL-3.0-or-later
#include "insertion_levels.h"

#include <chrono>
#include <cmath>

#include "tinlod/accuracy_job.h"
#include "tinlod/insert_job.h"
#include "tinlod/nodata_filter.h"

namespace tinlod {

std::vector<std::size_t> levelCounts(std::size_t original, double deletePct, double stopPct) {
  std::vector<std::size_t> counts;
  const double stop = original * stopPct / 100;
  for (double n = original * (1 - deletePct / 100); n >= stop && n >= 3; n *= 1 - deletePct / 100)
    counts.push_back(static_cast<std::size_t>(std::llround(n)));
  return counts;
}

std::vector<LevelAccuracy> measureInsertionLevels(const AccuracyEvaluator& evaluator, const Dem& dem, const Tin& sampled,
                                                  const CrsTransform& toTin, const std::vector<std::size_t>& counts,
                                                  double deletePct, double stopPct, const ProgressRange& progress) {
  GreedyInserter inserter(makeInsertGrid(dem, toTin, &sampled), progress.sub(0, 0.02));
  std::vector<LevelAccuracy> rows(counts.size());
  // Coarsest first: each count continues the insertion of the one before.
  for (std::size_t k = counts.size(); k-- > 0;) {
    const double done = double(counts.size() - 1 - k) / counts.size();
    const ProgressRange part = progress.sub(0.02 + 0.98 * done, 0.02 + 0.98 * (done + 1.0 / counts.size()));
    const auto start = std::chrono::steady_clock::now();
    inserter.run({0, counts[k], 0}, part.sub(0, 0.3));
    LevelAccuracy& row = rows[k];
    row.selectSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    row.dem = demName(dem.path);
    row.method = "insert";
    row.deletePct = deletePct, row.stopPct = stopPct;
    row.level = static_cast<int>(k) + 1;
    row.certifiedError = inserter.maxError();
    Triangulation triangulation = inserter.triangulation();
    for (Triangle& t : triangulation.triangles)
      for (VertexId& v : t) v = inserter.inserted()[v].candidate;  // the sampled TIN's vertex ids
    // As tinlod sample keeps them: none over a hole, no sliver along a straight edge.
    const std::vector<Triangle> triangles = trianglesOnValidData(dem, triangulation, sampled);
    row.vertices = inserter.vertexCount(), row.triangles = triangles.size();
    evaluator.evaluate(triangles, row, nullptr, part.sub(0.3, 1));
  }
  return rows;
}

}  // namespace tinlod
