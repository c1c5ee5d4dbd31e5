// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cstddef>
#include <string>

#include "tinlod/feedback.h"

namespace tinlod {

struct LocateSummary {
  std::size_t points = 0, located = 0;  // located: on the TIN (not outside, not in a hole)
  int level = 0;
  double seconds = 0;                   // the point location itself
  std::size_t tilesRead = 0;            // a catalogue's tile hierarchies read (a tile again once dropped)
  // A catalogue's tiles not finished, as unfinishedTiles says them ("" when none): a point
  // there is not located though it may lie on the job's TIN.
  std::string unfinishedTiles;
};

// `tinlod locate`: every point feature of the first layer of `pointsPath` with its
// attributes, plus 'elevation' (the TIN's height at `level`, linear in the containing
// triangle) and 'triangle' (the id of that triangle in the hierarchy's 'triangles'
// layer), both null for a point outside the TIN or in a hole; written as layer 'points'
// of `outPath` in the points' own CRS. `level` -1 is the coarsest; a level outside the
// hierarchy fails before the work.
LocateSummary runLocateJob(const std::string& hierarchyPath, const std::string& pointsPath, const std::string& outPath,
                           int level, bool overwrite, const Feedback& feedback);

}  // namespace tinlod
