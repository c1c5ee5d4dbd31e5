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

// Pieces of a tile whose cells the same tiles hold: the inside with the first row and column
// (only tiles before it hold those), the last column's first cell (the tile above and right
// holds it too), the rest of the last column, the last row, the last corner.
std::vector<CellRect> piecesOf(const CatalogueTile& t) {
  const int c0 = t.xoff, r0 = t.yoff, c1 = t.xoff + t.xsize - 1, r1 = t.yoff + t.ysize - 1;  // c1, r1: its last
  return {{c0, r0, c1, r1}, {c1, r0, c1 + 1, r0 + 1}, {c1, r0 + 1, c1 + 1, r1}, {c0, r1, c1, r1 + 1}, {c1, r1, c1 + 1, r1 + 1}};
}

}  // namespace

std::vector<CellRect> ownedCells(const std::vector<CatalogueTile>& tiles, std::size_t index) {
  std::vector<CellRect> owned;
  for (const CellRect& piece : piecesOf(tiles[index]))
    if (!piece.empty() && ownerOf(tiles, piece.col0, piece.row0) == index) owned.push_back(piece);
  return owned;
}

std::vector<CellRect> cellsLeftBy(const std::vector<CatalogueTile>& tiles, const std::vector<CatalogueTile>& missing,
                                  std::size_t index) {
  // Finished tiles may hold its first row and column too, so those are pieces of their own:
  // its first, inner and last columns by its first, inner and last rows.
  const CatalogueTile& t = missing[index];
  if (t.xsize < 2 || t.ysize < 2) return {};  // a catalogue that does not say which cells it holds
  const int cols[] = {t.xoff, t.xoff + 1, t.xoff + t.xsize - 1, t.xoff + t.xsize};
  const int rows[] = {t.yoff, t.yoff + 1, t.yoff + t.ysize - 1, t.yoff + t.ysize};
  std::vector<CellRect> pieces;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pieces.push_back({cols[j], rows[i], cols[j + 1], rows[i + 1]});
  std::vector<CellRect> owned;
  for (const CellRect& piece : pieces)
    if (!piece.empty() && ownerOf(tiles, piece.col0, piece.row0) == tiles.size() &&
        ownerOf(missing, piece.col0, piece.row0) == index)
      owned.push_back(piece);
  return owned;
}

}  // namespace tinlod
