// SPDX-License-Identifier: GPL-3.0-or-later
// Private: greedy insertion as a method of the experiment.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tinlod/accuracy_evaluator.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem.h"
#include "tinlod/tin.h"

namespace tinlod {

// The vertex counts of a hierarchy that deletes `deletePct` of the vertices per level from
// `original` down to `stopPct` of them: the counts greedy insertion is compared at.
std::vector<std::size_t> levelCounts(std::size_t original, double deletePct, double stopPct);

// Greedy insertion over the vertices of `sampled` (the study's comparator on the same
// input), measured at each of `counts` as level 1, 2, ... (counts in decreasing order, as
// levels coarsen). One insertion run serves every count: each is a prefix of the next.
std::vector<LevelAccuracy> measureInsertionLevels(const AccuracyEvaluator& evaluator, const Dem& dem, const Tin& sampled,
                                                  const CrsTransform& toTin, const std::vector<std::size_t>& counts,
                                                  double deletePct, double stopPct, const ProgressRange& progress);

}  // namespace tinlod
