// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "tinlod/importance.h"

namespace tinlod {

// The finest level is 0, the coarsest at most kMaxLevel: a hierarchy's triangles keep
// their levels in 16 bits.
constexpr int kMaxLevel = 32766;

// Options of the delete simplification, shared by `tinlod build` and the QGIS algorithm.
struct HierarchyOptions {
  Measure measure = Measure::Volume;  // how importance is measured
  double deletePct = 20;              // at most this % of the current vertices deleted per level
  double stopPct = 5;                 // stop when this % of the original vertices remain
  int maxLevels = 0;                  // stop after this many levels above level 0; 0: no limit
                                      // (a level that would delete under 1 % is never made)
  int maxDegree = 11;                 // degree measure: only vertices of at most this degree go
  double maxError = INFINITY;         // error measure: no valid DEM cell may end further than
                                      //   max(this, level 0's own distance there) from a level (metres)
  bool keepOutline = false;           // never delete outline vertices (data's outline, holes' edges)
  double outlineTolerance = NAN;      // metres the outline may move at level 1 (growing with the
                                      //   levels as the vertex spacing does); NaN: one DEM cell
  bool thresholdMode = false;         // the study's threshold mode: one pass per level, every
  double threshold = 0;               //   independent vertex with importance below `threshold`
  bool fixPeaksPits = false;          // keep strict local maxima and minima of the DEM (3 x 3)
  std::string fixedPoints;            // vector file of points to keep (snapped to the nearest vertex)
  // A tile's second pass: level k deletes every independent vertex whose importance is below
  // levelThresholds[k - 1] (set for the whole raster from the first pass's surveys).
  std::vector<double> levelThresholds;
  // Of the candidates in the survey bin just below levelThresholds[k - 1] (ties, a flat sea
  // of zeros), only this share may go at level k (least important first); empty: all.
  std::vector<double> levelShares;
  // Record each level's LevelSurvey in the hierarchy, and of the levels only their counts
  // (levels, vertexLevel; errors against the DEM for level 0 only): its triangles, groups,
  // links, rings and base triangles stay empty.
  bool survey = false;
  // A tile of a job with -method error -max_error: the file of line cells to keep (one
  // "row col" of the whole raster per line) that the tiles agreed on so far. Given (even
  // empty), the border rule deletes line vertices under the bound (TileBorders::agreed);
  // not given, a bounded tile's line vertices all stay.
  std::string borderKeep;
  // A tile of a job whose surveys listed the lines' outline cells: the file of them (one
  // "row col" of the whole raster per line), which alone of the line cells near nodata stay
  // (TileBorders::lineOutline). Not given, every line cell near nodata stays.
  std::string lineOutline;

  // Throws Error naming the option when a value is out of range.
  void validate() const;
};

}  // namespace tinlod
