// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/build_summary_text.h"

namespace tinlod {

std::string coarsestCellsText(const BuildSummary& s) {
  return s.cellsGivenUp >= 0 ? std::to_string(s.cellsGivenUp) + " valid cells given up by its outline"
                             : std::to_string(-s.cellsGivenUp) + " valid cells more than level 0 covers";
}

std::string levelZeroCoverText(const BuildSummary& s) {
  if (s.validCells <= std::size_t(s.levelZeroCells)) return "";
  return "Level 0 covers " + std::to_string(s.levelZeroCells) + " of the DEM's " + std::to_string(s.validCells) +
         " valid cells: the others are beside nodata, in valid areas too thin for a triangle (one cell wide) or at "
         "their tips, within the jitter of the TIN";
}

}  // namespace tinlod
