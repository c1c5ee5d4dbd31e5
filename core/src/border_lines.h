// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "tinlod/dem.h"
#include "tinlod/tile_borders.h"
#include "tinlod/tin.h"

namespace tinlod {

// The border lines a tile shares with its neighbours, each as the valid cells on it in
// order along it (every one is a vertex of level 0, of one tile at least). The border rule
// reads only these cells (their heights, places and nearness to nodata), never the tile's
// triangles, importances or progress: the two tiles on a line delete the same vertices at
// the same levels, so their level k meet without a crack.
class BorderLines {
 public:
  static constexpr VertexId kNoVertex = ~VertexId{0};

  BorderLines() = default;
  BorderLines(const Tin& base, const Dem& dem, const TileBorders& tile);

  // The cells that go at `level`, dropped from the lines: on the lines the level thins,
  // never a line's ends, a corner or a cell near nodata, never two neighbours on a line;
  // those whose height is nearest the line between their neighbours first, at most `share`
  // of a line's cells. Each comes with its deviation (metres) and its vertex in this tile
  // (kNoVertex where this tile's level 0 left it out: only the other tile deletes it).
  // With a finite `below` (a volume in the TIN's area units times metres: the level's
  // threshold), only cells whose volume estimate is below it go, smallest first, each with
  // that estimate: a line stays dense where the terrain is rough, as the interior does.
  std::vector<std::pair<double, VertexId>> take(int level, double share, double below = INFINITY);

 private:
  struct Cell {
    VertexId vertex;
    double z, along;  // along: its cell's place on the line, in cells of the whole raster
    bool pinned;
  };
  struct Line {
    int lineClass = 0;
    std::vector<Cell> cells;
  };
  void takeFromLine(Line& line, double share, double below, std::vector<std::pair<double, VertexId>>& out) const;
  double cellArea_ = 1;  // of one cell of the whole raster, in the TIN's area units

  std::vector<Line> lines_;
};

}  // namespace tinlod
