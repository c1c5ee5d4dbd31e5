// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
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

  // What bounds the cells that go, beside the share: nothing; their volume estimate (a
  // volume in the TIN's area units times metres: the level's threshold), so that a line
  // stays dense where the terrain is rough, as the interior does; or their deviation
  // (metres: -max_error), which a cell's own error after its deletion is.
  struct Limit {
    enum Kind { kNone, kVolume, kDeviation } kind = kNone;
    double below = INFINITY;
  };

  // The cells that go at `level`, dropped from the lines: on the lines the level thins,
  // never a line's ends, a corner or a cell near nodata, never two neighbours on a line;
  // those whose height is nearest the line between their neighbours first, at most `share`
  // of a line's cells. Each comes with its deviation (metres) or, under a volume limit,
  // its volume estimate, and its vertex in this tile (kNoVertex where this tile's level 0
  // left it out: only the other tile deletes it). Cells above the limit stay.
  std::vector<std::pair<double, VertexId>> take(int level, double share, Limit limit);
  // As above, where this tile may refuse a cell's vertex (`accept` false: its deletion
  // would take the tile's cells beyond a bound). A refused cell is pinned and the line's
  // choice made again without it, as if it had been pinned from the start: so a build that
  // keeps it from the start (the next round, TileBorders::kept) makes the same choices.
  // The refused vertices are added to `refused`.
  std::vector<std::pair<double, VertexId>> take(int level, double share, Limit limit,
                                                const std::function<bool(VertexId)>& accept,
                                                std::vector<VertexId>& refused);

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
  struct Choice {
    double importance;  // the deviation, or the volume estimate under a volume limit
    std::size_t at;     // in the line's cells
  };
  // The cells the line's rule takes, by the line alone; `drop` removes them from the line.
  std::vector<Choice> choose(const Line& line, double share, Limit limit) const;
  static void drop(Line& line, const std::vector<Choice>& chosen);
  double cellArea_ = 1;  // of one cell of the whole raster, in the TIN's area units

  std::vector<Line> lines_;
};

}  // namespace tinlod
