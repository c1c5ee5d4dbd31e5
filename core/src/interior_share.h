// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a DEM with many small voids rings each with vertices that may not go (the TIN
// never covers nodata), so -stop_pct is out of reach and the levels go on deleting the
// interior alone: swiss_alps kept 346 of 180,156 interior vertices, RMSE 54 m -> 179 m.
// Said with the -stop_pct that keeps the interior's share instead.
#pragma once

#include <string>
#include <vector>

#include "tinlod/hierarchy.h"

namespace tinlod {

// Empty unless the coarsest level keeps under half of the -stop_pct share of level 0's
// vertices off the outline; else a warning saying so, naming the -stop_pct that stops at
// the last level keeping that share. For a build that stopped above -stop_pct.
std::string starvedInteriorWarning(const std::vector<LevelStats>& levels, double stopPct);

}  // namespace tinlod
