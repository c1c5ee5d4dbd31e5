// SPDX-License-Identifier: GPL-3.0-or-later
// What a build's summary says of the cells its levels cover, in the words the command line
// and QGIS's log both use.
#pragma once

#include <string>

#include "tinlod/build_job.h"

namespace tinlod {

// "N valid cells given up by its outline", or, when the coarsest level's outline reaches
// cells beside nodata that level 0's missed (a tip of data one cell wide), "N valid cells more than level 0 covers".
std::string coarsestCellsText(const BuildSummary& s);

// "Level 0 covers N of the DEM's M valid cells: ..." when it does not cover them all (data
// one cell wide beside nodata); "" otherwise, and for a tile.
std::string levelZeroCoverText(const BuildSummary& s);

}  // namespace tinlod
