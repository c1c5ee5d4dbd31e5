// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tile_borders.h"

#include <algorithm>

#include "tinlod/cell_hash.h"

namespace tinlod {

bool onSharedLine(const Dem& dem, int row, int col) {
  return (col == 0 && dem.window.colOffset > 0) || (col == dem.width - 1 && dem.sharesLastCol()) ||
         (row == 0 && dem.window.rowOffset > 0) || (row == dem.height - 1 && dem.sharesLastRow());
}

bool lineCellSampled(const Dem& dem, int row, int col, int block, std::uint64_t seed) {
  const bool firstCol = col == 0 && dem.window.colOffset > 0, lastCol = col == dem.width - 1 && dem.sharesLastCol();
  const bool column = firstCol || lastCol;  // on a vertical line: its blocks run down it
  const bool corner = (col == 0 || col == dem.width - 1) && (row == 0 || row == dem.height - 1);
  if (corner || (!dem.nearNodata.empty() && dem.nearNodata[std::size_t(row) * dem.width + col])) return true;
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
  return std::max(1, static_cast<int>(std::ceil(std::log(stopPct / 100.0) / std::log(1.0 - deletePct / 100.0) - 1e-9)));
}

TileBorders tileBorders(const Dem& dem, const Tin& tin, const TileSpec& tile, std::vector<std::uint8_t> nearNodata,
                        int levels, int block, std::uint64_t seed) {
  TileBorders b;
  b.block = block, b.seed = seed;
  b.nearNodata = std::move(nearNodata);
  b.levels = levels;
  // A line's class from its index among the raster's lines of its direction: the same for
  // the two tiles that share it.
  const bool shared[4] = {dem.window.colOffset > 0, dem.sharesLastCol(), dem.window.rowOffset > 0, dem.sharesLastRow()};
  const int lineIndex[4] = {tile.col, tile.col + 1, tile.row, tile.row + 1};
  for (int s = 0; s < 4; ++s)
    if (shared[s]) b.lineClass[s] = (s < 2 ? 0 : 2) + lineIndex[s] % 2;
  b.side.assign(tin.vertices.size(), -1);
  b.pinned.assign(tin.vertices.size(), 0);
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) {
    const TinVertex& v = tin.vertices[i];
    const bool on[4] = {v.col == 0, v.col == dem.width - 1, v.row == 0, v.row == dem.height - 1};
    int sides = 0, sharedSide = -1;
    for (int s = 0; s < 4; ++s) {
      sides += on[s];
      if (on[s] && shared[s]) sharedSide = s;
    }
    if (sharedSide < 0) continue;
    b.side[i] = static_cast<std::int8_t>(sharedSide);
    b.pinned[i] = sides > 1 || b.nearNodata[static_cast<std::size_t>(v.row) * dem.width + v.col];
  }
  return b;
}

}  // namespace tinlod
