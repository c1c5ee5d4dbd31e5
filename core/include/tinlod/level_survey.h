// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace tinlod {

// What one level's selection saw in a tile: how many candidates of each importance, and
// how many of those it could take (independence blocks the others). A tiled run's first pass
// gathers these from every tile to set one importance threshold per level for the whole
// raster, so that its second pass deletes what a run over the whole raster would: the least
// important vertices anywhere, not a quota of each tile's.
struct LevelSurvey {
  std::int32_t level = 0;
  std::size_t vertices = 0;  // before the level
  std::size_t picked = 0;    // the tile's own picks (not the border rule's)
  std::size_t considered = 0;  // candidates the pick went through (picked, or blocked by a neighbour)
  double last = 0;           // the importance of the last pick
  std::vector<std::uint64_t> histogram;  // candidates by surveyBin of their importance
  std::vector<std::uint64_t> pickedHistogram;  // the tile's own picks, by the same bins
  // A level without a threshold: the picks of a walk through every candidate, the delete
  // percentage's and on past them (none deleted), by the same bins.
  std::vector<std::uint64_t> walkHistogram;
  double unionVertices = 0;  // `vertices` as a job's union counts them (tile_borders.h: unionShare)
  double borderPicked = 0;   // the border rule's picks, as the union counts them
};

// Importances in bins of 1/200 of a decade from 1e-12 to 1e15; bin 0 holds 0 and below 1e-12.
constexpr int kSurveyBins = 1 + 27 * 200;
inline int surveyBin(double importance) {
  if (!(importance > 1e-12)) return 0;
  const int b = 1 + static_cast<int>(std::floor((std::log10(importance) + 12) * 200));
  return b < 1 ? 1 : b >= kSurveyBins ? kSurveyBins - 1 : b;
}
// The smallest importance above every importance in the bin.
inline double surveyBinTop(int bin) { return bin == 0 ? 1e-12 : std::pow(10.0, bin / 200.0 - 12); }
// The lower end of the bin whose top is `top` (a threshold from the surveys); -infinity
// for bin 0, which holds every importance below 1e-12.
inline double surveyBinBottom(double top) { return top <= 1e-12 ? -INFINITY : top * std::pow(10.0, -1.0 / 200); }

// The survey as JSON: {"levels": [{"level", "vertices", "picked", "considered", "last",
// "histogram": [[bin, count], ...], "picked_histogram": [[bin, count], ...],
// "walk_histogram": [[bin, count], ...] (a level without a threshold), "union_vertices",
// "border_picked"}, ...],
// "line_outline": [[row, col], ...]} (bins with a
// count only; line_outline: the tile's lineOutlineCells, as globalCellKey).
std::string surveyJson(const std::vector<LevelSurvey>& levels, const std::vector<std::uint64_t>& lineOutline);

}  // namespace tinlod
