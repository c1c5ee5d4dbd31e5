// SPDX-License-Identifier: GPL-3.0-or-later
// Private: which tile of a catalogue answers for each cell, so that the jobs that work a
// tile at a time count every cell (and every vertex) once.
#pragma once

#include <cstddef>
#include <vector>

#include "tile_catalogue.h"

namespace tinlod {

// Cells [col0, col1) x [row0, row1) of the raster.
struct CellRect {
  int col0 = 0, row0 = 0, col1 = 0, row1 = 0;
  bool empty() const { return col0 >= col1 || row0 >= row1; }
  bool contains(int col, int row) const { return col >= col0 && col < col1 && row >= row0 && row < row1; }
};

// The cells tile `index` answers for, as disjoint rectangles: a cell several tiles hold (on
// a line they share) goes to the one of them furthest right, then furthest down, among the
// tiles listed, so a tile missing from the catalogue leaves its lines to its neighbours.
std::vector<CellRect> ownedCells(const std::vector<CatalogueTile>& tiles, std::size_t index);

// The cells of tile `index` of `missing` (tiles not finished) that no tile of `tiles` holds,
// shared among the missing tiles by the same rule: each cell of the raster's tiles is then
// either a finished tile's or a missing tile's, once.
std::vector<CellRect> cellsLeftBy(const std::vector<CatalogueTile>& tiles, const std::vector<CatalogueTile>& missing,
                                  std::size_t index);

}  // namespace tinlod
