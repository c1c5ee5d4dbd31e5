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
         " valid cells: the others' centres are beside nodata, just outside the TIN where the jitter moved their vertex "
         "(by less than the jitter), or in valid areas too thin for a triangle";
}

}  // namespace tinlod
