// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/tin.h"

namespace tinlod {

// A tile of a raster cut into tile x tile cells; neighbouring tiles share one column or
// row of cells, on which both sample every valid cell: the border line.
struct TileSpec {
  int size = 0;  // cells per tile side, a multiple of the sampling block
  int col = 0, row = 0;

  // Tiles across and down a raster of width x height cells.
  static int count(int cells, int size) { return cells <= 1 ? 1 : (cells - 2) / size + 1; }
};

// The sides of a tile, by where they lie in its window.
enum TileSide : int { kFirstCol = 0, kLastCol = 1, kFirstRow = 2, kLastRow = 3 };

// What the simplifier needs to thin a tile's border lines exactly as its neighbours do.
// A border vertex goes only by the border rule (HierarchyBuilder), which reads the line's
// own vertices and is the same in both tiles; every level of every tile of a job is made,
// so each tile has `levels` levels.
struct TileBorders {
  int levels = 0;
  // By side: which of the four level classes thins the line (a line is thinned at levels
  // 1 + class, 5 + class, ...; the two lines of a tile's pair of opposite sides have
  // different classes, so no two lines of a tile are thinned at the same level); -1: the
  // side is the raster's own edge, simplified as in a whole run.
  std::array<int, 4> lineClass{-1, -1, -1, -1};
  std::vector<std::int8_t> side;     // by vertex: the shared side it lies on, or -1
  std::vector<std::uint8_t> pinned;  // by vertex: a border vertex that never goes (pinnedBorderCell)
  // With -fix_peaks_pits: a line cell that is a strict peak or pit of the whole raster
  // (Dem::edgePeaksAndPits, which both tiles read alike) never goes either.
  bool pinPeaksAndPits = false;
  int block = 3;                     // the sampling's, for lineCellSampled
  std::uint64_t seed = 1;
  // One cell's area in the TIN's CRS (at the whole raster's centre): the border rule's
  // estimate of a line vertex's volume is in the units of the volume measure.
  double cellArea = 0;
  // With -method error -max_error, only with `agreed`: a line vertex the border rule takes
  // goes when its deletion keeps this tile's cells within the bound, and is *refused*
  // otherwise (Hierarchy::borderRefused). The driver then keeps it (`kept`, by
  // globalCellKey) in both tiles and builds them again, until no tile refuses one: the two
  // tiles check the two sides of the line, which neither sees whole.
  bool agreed = false;
  std::unordered_set<std::uint64_t> kept;
  // With `outlineListed` (pinLineOutlineOnly), the line cells in `lineOutline` (globalCellKey)
  // are pinned instead of every cell near nodata: those on the outline of either tile's
  // level 0 (lineOutlineCells of both).
  bool outlineListed = false;
  std::unordered_set<std::uint64_t> lineOutline;
};

// A cell of the whole raster as one number: its row in the high half, its column in the low.
inline std::uint64_t globalCellKey(std::int64_t row, std::int64_t col) {
  return (std::uint64_t(row) << 32) | std::uint32_t(col);
}
inline std::int64_t globalCellRow(std::uint64_t key) { return std::int64_t(key >> 32); }
inline std::int64_t globalCellCol(std::uint64_t key) { return std::int64_t(key & 0xffffffffu); }

// How near (in cells) a missing cell pins a border vertex: a level-0 triangle reaches about
// two blocks from its vertices, and the nodata filter drops those over missing cells.
inline int pinningDistance(int block) { return 3 * block; }

// By side (TileSide): whether the tile shares it with a neighbouring tile.
std::array<bool, 4> sharedSides(const Dem& dem);

// The column (kFirstCol, kLastCol) or row (kFirstRow, kLastRow) of the tile a side lies on.
int sidePosition(const Dem& dem, int side);

// Whether a cell of a tile lies on a line it shares with a neighbouring tile.
bool onSharedLine(const Dem& dem, int row, int col);

// Whether two cells of a tile lie on one line it shares with a neighbouring tile.
bool onOneSharedLine(const Dem& dem, int rowA, int colA, int rowB, int colB);

// Whether a cell of a shared line never goes (when it is a vertex): a tile corner, or a cell
// near nodata (Dem::nearNodata), where how a tile's level 0 meets its line depends on cells
// the other tile does not read.
bool pinnedOnLine(const Dem& dem, int row, int col);

// Whether a cell of a shared line never goes in this job: pinnedOnLine (or, when
// TileBorders::lineOutline is given, a tile corner or a cell it lists), a peak or pit kept by
// -fix_peaks_pits, or a cell the tiles agreed to keep (TileBorders::kept).
bool pinnedBorderCell(const Dem& dem, const TileBorders& borders, int row, int col);

// Whether a valid cell of a shared line is a vertex: the tile's corners, every cell next to
// nodata (Dem::nextToNodata: the outline, as a whole run samples it), and one valid cell per
// block of the line, chosen by a hash of the seed and the block's place in the whole raster:
// the same cells in both tiles, about as dense as the interior's samples.
bool lineCellSampled(const Dem& dem, int row, int col, int block, std::uint64_t seed);

// The cells of a side's line that are vertices in a whole tile (valid and lineCellSampled),
// as {row, col} of the tile, in order along the line: what the border rule reads.
std::vector<std::array<int, 2>> lineVertexCells(const Dem& dem, int side, int block, std::uint64_t seed);

// A tile's vertex as a job's union counts it: 1, a half on a line two tiles share, a quarter
// at a corner four tiles share; so a job's tiles' shares add up to their union's vertices.
// `shared`: the tile's sharedSides.
inline double unionShare(const std::array<bool, 4>& shared, const Dem& dem, const TinVertex& v) {
  const bool onColumn = (shared[kFirstCol] && v.col == 0) || (shared[kLastCol] && v.col == dem.width - 1);
  const bool onRow = (shared[kFirstRow] && v.row == 0) || (shared[kLastRow] && v.row == dem.height - 1);
  return (onColumn ? 0.5 : 1.0) * (onRow ? 0.5 : 1.0);
}

// Levels that a whole run with these percentages makes when nothing stops it early.
int tileLevelCount(double deletePct, double stopPct);

// The tile of `dem` (a window of its raster, as readTile gives it) for `tin`; `cellArea` as
// TileBorders::cellArea (throws Error unless it is positive and finite), and
// `pinPeaksAndPits` as TileBorders::pinPeaksAndPits.
TileBorders tileBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, int levels, int block, std::uint64_t seed,
                        double cellArea, bool pinPeaksAndPits = false);
// As above, the line cells `kept` (globalCellKey) pinned as well, the border's deletions
// under a bound agreed (TileBorders::agreed).
TileBorders agreedTileBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, int levels, int block,
                              std::uint64_t seed, double cellArea, bool pinPeaksAndPits,
                              std::unordered_set<std::uint64_t> kept);

// The sampled cells of the tile's shared lines (tile corners aside) on the outline of its
// level 0 `tin` (globalCellKey, sorted): those the nodata filter left out of the TIN, or
// took a triangle from (the cell's triangles are not one fan between its two neighbours on
// the line). Only these need pinning, where the other tile cannot see how this one meets
// the line: a line vertex off the outline at level 0 never comes onto it (an outline edge
// joins two earlier outline vertices), so both tiles delete it by the line's rule alone.
std::vector<std::uint64_t> lineOutlineCells(const Dem& dem, const Tin& tin, int block, std::uint64_t seed);

// Pins the line cells `outline` lists instead of every cell near nodata: the union of both
// tiles' lineOutlineCells (tinlod tiles gathers them from the surveys). Throws Error when it lacks
// one of this tile's own, `source` naming where the list came from.
void pinLineOutlineOnly(TileBorders& borders, const Dem& dem, const Tin& tin, std::unordered_set<std::uint64_t> outline,
                        const std::string& source);

// The cells of `cells` (globalCellKey) that lie on the tile's shared lines, sorted.
std::vector<std::uint64_t> cellsOnSharedLines(const Dem& dem, const std::unordered_set<std::uint64_t>& cells);

}  // namespace tinlod
