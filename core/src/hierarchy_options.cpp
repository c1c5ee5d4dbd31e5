// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/hierarchy_options.h"

#include <cmath>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

void HierarchyOptions::validate() const {
  // Under 1 % a whole run makes no level (one must delete at least 1 % of its vertices): such
  // a run ended with level 0 alone, blaming fixed and outline vertices.
  if (!(deletePct >= 1 && deletePct <= 100))
    throw Error("-delete_pct must be from 1 to 100 (got " + formatNumber(deletePct) +
                "): a whole run makes no level that deletes under 1 % of its vertices; the study used 10 and 20");
  if (!(stopPct >= 0 && stopPct < 100))
    throw Error("-stop_pct must be from 0 to less than 100 (got " + formatNumber(stopPct) + "); the study used 5");
  if (maxLevels < 0 || maxLevels > kMaxLevel)
    throw Error("-max_levels must be 0 (no limit) or from 1 to " + std::to_string(kMaxLevel) + " (got " +
                std::to_string(maxLevels) + ")");
  if (maxDegree < 3) throw Error("-max_degree must be 3 or more (got " + std::to_string(maxDegree) + "); Kirkpatrick used 11");
  if (!(maxError > 0)) throw Error("-max_error must be more than 0 metres");
  if (thresholdMode && !(threshold > 0))
    throw Error("-threshold must be more than 0 (got " + formatNumber(threshold) +
                "); it is in the method's units: cubic metres for volume, metres for error, a degree for degree, "
                "1 - flatness for normal");
  if (!std::isnan(outlineTolerance) && !(outlineTolerance >= 0 && std::isfinite(outlineTolerance)))
    throw Error("-outline_tolerance must be 0 or more metres (got " + formatNumber(outlineTolerance) +
                "); leave it out for one DEM cell, or use -keep_outline to keep every outline vertex");
  // A degree limit changed for another method would be ignored; the default cannot be told
  // from one given (the command line checks that), and does no harm.
  if (maxDegree != HierarchyOptions{}.maxDegree && measure != Measure::Degree)
    throw Error("-max_degree applies only to -method degree (got -max_degree " + std::to_string(maxDegree) + " with -method " +
                measureName(measure) + ")");
  if (maxError != INFINITY && measure != Measure::Error)
    throw Error("-max_error applies to the error method only: add -method error");
  if (!borderKeep.empty() && (measure != Measure::Error || maxError == INFINITY))
    throw Error("-border_keep applies to tiles built with -method error -max_error (tinlod tiles gives it): "
                "other methods thin a tile's lines by a rule that needs no agreement");
}

}  // namespace tinlod
