// SPDX-License-Identifier: GPL-3.0-or-later
#include "tile_ownership.h"

#include <utility>

namespace tinlod {
namespace {

bool holds(const CatalogueTile& t, int col, int row) {
  return col >= t.xoff && col < t.xoff + t.xsize && row >= t.yoff && row < t.yoff + t.ysize;
}

// The tile furthest right, then furthest down, of those holding the cell.
std::size_t ownerOf(const std::vector<CatalogueTile>& tiles, int col, int row) {
  std::size_t best = tiles.size();
  for (std::size_t i = 0; i < tiles.size(); ++i)
    if (holds(tiles[i], col, row) &&
        (best == tiles.size() ||
         std::pair(tiles[i].xoff, tiles[i].yoff) > std::pair(tiles[best].xoff, tiles[best].yoff)))
      best = i;
  return best;
}

}  // namespace

std::vector<CellRect> ownedCells(const std::vector<CatalogueTile>& tiles, std::size_t index) {
  const CatalogueTile& t = tiles[index];
  const int c0 = t.xoff, r0 = t.yoff, c1 = t.xoff + t.xsize - 1, r1 = t.yoff + t.ysize - 1;  // c1, r1: its last
  // Pieces whose cells the same tiles hold: the inside with the first row and column (only
  // tiles before it hold those), the last column's first cell (the tile above and right
  // holds it too), the rest of the last column, the last row, the last corner.
  const CellRect pieces[] = {{c0, r0, c1, r1}, {c1, r0, c1 + 1, r0 + 1}, {c1, r0 + 1, c1 + 1, r1},
                             {c0, r1, c1, r1 + 1}, {c1, r1, c1 + 1, r1 + 1}};
  std::vector<CellRect> owned;
  for (const CellRect& piece : pieces)
    if (!piece.empty() && ownerOf(tiles, piece.col0, piece.row0) == index) owned.push_back(piece);
  return owned;
}

}  // namespace tinlod
