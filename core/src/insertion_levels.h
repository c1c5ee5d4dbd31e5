// SPDX-License-Identifier: GPL-3.0-or-later
// Private: greedy insertion at the sizes of a hierarchy's levels, the study's comparator.
#pragma once

#include <cstddef>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/tin.h"

namespace tinlod {

// The distinct vertex counts of the levels above level 0 among `levels` (rows of one DEM,
// of one or several hierarchies), largest first: the sizes greedy insertion is run to.
std::vector<std::size_t> insertionCounts(const std::vector<LevelAccuracy>& levels);

// Greedy insertion over the vertices of `sampled` (the study's comparator on the same
// input), stopped at each of `counts` (largest first, as insertionCounts gives them) and
// measured there: one row per count, method "insert", levels 1, 2, ... in that order, no
// delete percentage (NaN). One insertion run serves every count: each is a prefix of the
// next. A count greedy insertion cannot reach (the TIN is exact before it) warns and
// gives a row with the vertices it has.
std::vector<LevelAccuracy> measureInsertionLevels(const AccuracyEvaluator& evaluator, const Dem& dem, const Tin& sampled,
                                                  const CrsTransform& toTin, const std::vector<std::size_t>& counts,
                                                  double stopPct, const ProgressRange& progress);

// Fills insertRmse and insertRatio (rmse / insertRmse) of every row of `levels` above level 0
// from the row of `inserted` with its vertex count (rows of the same DEM).
void compareWithInsertion(std::vector<LevelAccuracy>& levels, const std::vector<LevelAccuracy>& inserted);

}  // namespace tinlod
