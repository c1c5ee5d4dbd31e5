// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tile_borders.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "tinlod/cell_hash.h"
#include "tinlod/error.h"

namespace tinlod {

std::array<bool, 4> sharedSides(const Dem& dem) {
  return {dem.window.colOffset > 0, dem.sharesLastCol(), dem.window.rowOffset > 0, dem.sharesLastRow()};
}

int sidePosition(const Dem& dem, int side) {
  return side == kFirstCol || side == kFirstRow ? 0 : side == kLastCol ? dem.width - 1 : dem.height - 1;
}

namespace {

// Whether the cell lies on a shared side's line: a column for kFirstCol and kLastCol.
bool onSide(const Dem& dem, int side, int row, int col) {
  return (side == kFirstCol || side == kLastCol ? col : row) == sidePosition(dem, side);
}

}  // namespace

bool onSharedLine(const Dem& dem, int row, int col) {
  const std::array<bool, 4> shared = sharedSides(dem);
  for (int s = 0; s < 4; ++s)
    if (shared[s] && onSide(dem, s, row, col)) return true;
  return false;
}

bool onOneSharedLine(const Dem& dem, int rowA, int colA, int rowB, int colB) {
  const std::array<bool, 4> shared = sharedSides(dem);
  for (int s = 0; s < 4; ++s)
    if (shared[s] && onSide(dem, s, rowA, colA) && onSide(dem, s, rowB, colB)) return true;
  return false;
}

namespace {

bool tileCorner(const Dem& dem, int row, int col) {
  return (col == 0 || col == dem.width - 1) && (row == 0 || row == dem.height - 1);
}

}  // namespace

bool pinnedOnLine(const Dem& dem, int row, int col) { return tileCorner(dem, row, col) || dem.nearNodataAt(row, col); }

bool lineCellSampled(const Dem& dem, int row, int col, int block, std::uint64_t seed) {
  // Next to nodata every cell is a vertex, as the outline's cells are in a whole run; the
  // rest of the pinned cells are sampled as the line is, or a line near voids would keep a
  // vertex on every cell for good (all levels of a tiled run of a DEM with voids).
  if (tileCorner(dem, row, col) || dem.nextToNodataAt(row, col)) return true;
  const std::array<bool, 4> shared = sharedSides(dem);
  // On a vertical line its blocks run down it.
  const bool column = (shared[kFirstCol] && onSide(dem, kFirstCol, row, col)) ||
                      (shared[kLastCol] && onSide(dem, kLastCol, row, col));
  // The line's block holding the cell, by the whole raster's block grid; a tile's window
  // starts on a block line, so a block of a line lies whole in both tiles that share it.
  const int along = column ? row : col, offset = column ? dem.window.rowOffset : dem.window.colOffset;
  const int first = static_cast<int>(((offset + along) / block) * block - offset);
  const int last = std::min(first + block, column ? dem.height : dem.width);
  int count = 0, index = -1;
  for (int a = first; a < last; ++a)
    if (column ? dem.valid(a, col) : dem.valid(row, a)) {
      if (a == along) index = count;
      ++count;
    }
  const std::int64_t line = column ? dem.globalCol(col) : dem.globalRow(row);
  const std::uint64_t h = cellHash(seed, line, (offset + along) / block, column ? 3 : 4);
  return count > 0 && index == static_cast<int>(h % static_cast<std::uint64_t>(count));
}

int tileLevelCount(double deletePct, double stopPct) {
  if (deletePct <= 0 || deletePct >= 100 || stopPct <= 0) return 1;
  // A tiny delete percentage gives more levels than an int holds, or infinitely many
  // (1 - deletePct / 100 rounding to 1): the most, which the caller refuses.
  const int most = std::numeric_limits<int>::max();
  const double perLevel = std::log(1.0 - deletePct / 100.0);
  if (!(perLevel < 0)) return most;
  const double levels = std::ceil(std::log(stopPct / 100.0) / perLevel - 1e-9);
  if (!(levels < double(most))) return most;
  return std::max(1, static_cast<int>(levels));
}

bool pinnedBorderCell(const Dem& dem, const TileBorders& borders, int row, int col) {
  return pinnedOnLine(dem, row, col) || (borders.pinPeaksAndPits && dem.edgePeakOrPitAt(row, col)) ||
         (!borders.kept.empty() && borders.kept.count(globalCellKey(dem.globalRow(row), dem.globalCol(col))) > 0);
}

namespace {

TileBorders makeBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, int levels, int block, std::uint64_t seed,
                        double cellArea, bool pinPeaksAndPits, bool agreed, std::unordered_set<std::uint64_t> kept) {
  if (!(cellArea > 0) || !std::isfinite(cellArea))
    throw Error("internal error: a tile's cell area must be positive, not " + std::to_string(cellArea));
  TileBorders b;
  b.block = block, b.seed = seed, b.cellArea = cellArea, b.pinPeaksAndPits = pinPeaksAndPits;
  b.agreed = agreed;
  b.kept = std::move(kept);
  b.levels = levels;
  // A line's class from its index among the raster's lines of its direction: the same for
  // the two tiles that share it.
  const std::array<bool, 4> shared = sharedSides(dem);
  const int lineIndex[4] = {tile.col, tile.col + 1, tile.row, tile.row + 1};
  for (int s = 0; s < 4; ++s)
    if (shared[s]) b.lineClass[s] = (s < 2 ? 0 : 2) + lineIndex[s] % 2;
  b.side.assign(tin.vertices.size(), -1);
  b.pinned.assign(tin.vertices.size(), 0);
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    const TinVertex& v = tin.vertices[i];
    for (int s = 0; s < 4; ++s)
      if (shared[s] && onSide(dem, s, v.row, v.col)) b.side[i] = static_cast<std::int8_t>(s);
    if (b.side[i] >= 0) b.pinned[i] = pinnedBorderCell(dem, b, v.row, v.col);
  }
  return b;
}

}  // namespace

TileBorders tileBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, int levels, int block, std::uint64_t seed,
                        double cellArea, bool pinPeaksAndPits) {
  return makeBorders(dem, tin, tile, levels, block, seed, cellArea, pinPeaksAndPits, false, {});
}

TileBorders agreedTileBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, int levels, int block,
                              std::uint64_t seed, double cellArea, bool pinPeaksAndPits,
                              std::unordered_set<std::uint64_t> kept) {
  return makeBorders(dem, tin, tile, levels, block, seed, cellArea, pinPeaksAndPits, true, std::move(kept));
}

std::vector<std::uint64_t> keptOnSharedLines(const Dem& dem, const std::unordered_set<std::uint64_t>& kept) {
  std::vector<std::uint64_t> out;
  for (const std::uint64_t key : kept) {
    const std::int64_t row = globalCellRow(key) - dem.window.rowOffset;
    const std::int64_t col = globalCellCol(key) - dem.window.colOffset;
    if (row >= 0 && col >= 0 && row < dem.height && col < dem.width && onSharedLine(dem, int(row), int(col)))
      out.push_back(key);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tinlod
