// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tile_borders.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

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

std::vector<std::array<int, 2>> lineVertexCells(const Dem& dem, int side, int block, std::uint64_t seed) {
  const bool column = side == kFirstCol || side == kLastCol;  // a column of cells, ordered by row
  const int at = sidePosition(dem, side), n = column ? dem.height : dem.width;
  std::vector<std::array<int, 2>> cells;
  for (int i = 0; i < n; ++i) {
    const int row = column ? i : at, col = column ? at : i;
    if (dem.valid(row, col) && lineCellSampled(dem, row, col, block, seed)) cells.push_back({row, col});
  }
  return cells;
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
  const std::uint64_t key = globalCellKey(dem.globalRow(row), dem.globalCol(col));
  const bool pinned = borders.outlineListed
                          ? tileCorner(dem, row, col) || borders.lineOutline.count(key) > 0
                          : pinnedOnLine(dem, row, col);
  return pinned || (borders.pinPeaksAndPits && dem.edgePeakOrPitAt(row, col)) ||
         (!borders.kept.empty() && borders.kept.count(key) > 0);
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

namespace {

// The triangles and neighbours of a tile's line vertices.
class LineStars {
 public:
  LineStars(const Dem& dem, const Tin& tin) : starOf_(tin.vertices.size(), -1) {
    for (VertexId v = 0; v < tin.vertices.size(); ++v)
      if (onSharedLine(dem, tin.vertices[v].row, tin.vertices[v].col)) {
        vertexOf_.emplace(globalCellKey(tin.vertices[v].row, tin.vertices[v].col), v);
        starOf_[v] = static_cast<std::int32_t>(stars_.size());
        stars_.emplace_back();
      }
    for (const Triangle& t : tin.triangles)
      for (int i = 0; i < 3; ++i)
        if (starOf_[t[i]] >= 0) {
          Star& s = stars_[starOf_[t[i]]];
          ++s.triangles;
          s.neighbours.push_back(t[(i + 1) % 3]), s.neighbours.push_back(t[(i + 2) % 3]);
        }
    for (Star& s : stars_) {
      std::sort(s.neighbours.begin(), s.neighbours.end());
      s.neighbours.erase(std::unique(s.neighbours.begin(), s.neighbours.end()), s.neighbours.end());
    }
  }

  // Whether the cell at (row, col) of the tile is a vertex whose triangles make one fan
  // from the cell at `before` to the one at `after`, its neighbours on the line.
  bool fan(const std::array<int, 2>& before, int row, int col, const std::array<int, 2>& after) const {
    const VertexId v = vertexAt(row, col), a = vertexAt(before[0], before[1]), b = vertexAt(after[0], after[1]);
    if (v == kNone || a == kNone || b == kNone) return false;
    const Star& s = stars_[starOf_[v]];
    // One fan: a triangle fewer than neighbours; two or more pieces would have two fewer.
    return s.triangles + 1 == static_cast<int>(s.neighbours.size()) &&
           std::binary_search(s.neighbours.begin(), s.neighbours.end(), a) &&
           std::binary_search(s.neighbours.begin(), s.neighbours.end(), b);
  }

 private:
  static constexpr VertexId kNone = ~VertexId{0};
  struct Star {
    int triangles = 0;
    std::vector<VertexId> neighbours;
  };
  VertexId vertexAt(int row, int col) const {
    const auto found = vertexOf_.find(globalCellKey(row, col));
    return found == vertexOf_.end() ? kNone : found->second;
  }
  std::unordered_map<std::uint64_t, VertexId> vertexOf_;  // by cell of the tile
  std::vector<std::int32_t> starOf_;
  std::vector<Star> stars_;
};

}  // namespace

std::vector<std::uint64_t> lineOutlineCells(const Dem& dem, const Tin& tin, int block, std::uint64_t seed) {
  const LineStars stars(dem, tin);
  const std::array<bool, 4> shared = sharedSides(dem);
  std::vector<std::uint64_t> out;
  for (int side = 0; side < 4; ++side) {
    if (!shared[side]) continue;
    const std::vector<std::array<int, 2>> cells = lineVertexCells(dem, side, block, seed);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto [row, col] = cells[i];
      if (tileCorner(dem, row, col)) continue;  // pinned in any case
      if (i == 0 || i + 1 == cells.size() || !stars.fan(cells[i - 1], row, col, cells[i + 1]))
        out.push_back(globalCellKey(dem.globalRow(row), dem.globalCol(col)));
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void pinLineOutlineOnly(TileBorders& borders, const Dem& dem, const Tin& tin, std::unordered_set<std::uint64_t> outline,
                        const std::string& source) {
  for (const std::uint64_t key : lineOutlineCells(dem, tin, borders.block, borders.seed))
    if (!outline.count(key))
      throw Error(source + " does not list the line cell " + std::to_string(globalCellRow(key)) + " " +
                  std::to_string(globalCellCol(key)) +
                  " (row and column of the raster), on this tile's outline at level 0: the list is not this job's");
  borders.outlineListed = true;
  borders.lineOutline = std::move(outline);
  for (std::size_t i = 0; i < tin.vertices.size(); ++i)
    if (borders.side[i] >= 0) borders.pinned[i] = pinnedBorderCell(dem, borders, tin.vertices[i].row, tin.vertices[i].col);
}

std::vector<std::uint64_t> cellsOnSharedLines(const Dem& dem, const std::unordered_set<std::uint64_t>& cells) {
  std::vector<std::uint64_t> out;
  for (const std::uint64_t key : cells) {
    const std::int64_t row = globalCellRow(key) - dem.window.rowOffset;
    const std::int64_t col = globalCellCol(key) - dem.window.colOffset;
    if (row >= 0 && col >= 0 && row < dem.height && col < dem.width && onSharedLine(dem, int(row), int(col)))
      out.push_back(key);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tinlod
