// SPDX-License-Identifier: GPL-3.0-or-later
// Tiles sample exactly what a run over the whole raster does off the lines they share: the
// same random cell of every block and the same jitter, bit for bit; on a shared line, both
// tiles sample the same cells, about one a block.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>

#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/sample_job.h"
#include "tinlod/sampler.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_borders.h"
#include "tinlod/tile_reader.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);
using Cell = std::pair<std::int64_t, std::int64_t>;  // whole-raster row, column

// A hilly DEM with a void, whose width and height are not multiples of the block.
Dem wholeDem() {
  Dem dem = test::makeDem(61, 47, 10, [](int r, int c) {
    if ((r - 20) * (r - 20) + (c - 33) * (c - 33) < 30) return NAN;
    return float(100 + 5 * std::sin(r * 0.3) + 3 * std::cos(c * 0.21) + 0.01 * r * c);
  });
  dem.window.fullWidth = dem.width, dem.window.fullHeight = dem.height, dem.window.fullGeotransform = dem.geotransform;
  return dem;
}

// What readTile would read: the tile's window of `whole`.
Dem tileOf(const Dem& whole, const TileSpec& tile) {
  const CellWindow w = tileWindow({whole.width, whole.height}, tile);
  Dem dem = whole;
  cropDem(dem, w.xoff, w.yoff, w.xsize, w.ysize);
  return dem;
}

std::vector<TileSpec> allTiles(const Dem& whole, int size) {
  std::vector<TileSpec> tiles;
  for (int c = 0; c < TileSpec::count(whole.width, size); ++c)
    for (int r = 0; r < TileSpec::count(whole.height, size); ++r) tiles.push_back({size, c, r});
  return tiles;
}

bool onGridLine(const Dem& whole, int size, const Cell& c) {
  return (c.first % size == 0 && c.first > 0 && c.first < whole.height - 1) ||
         (c.second % size == 0 && c.second > 0 && c.second < whole.width - 1);
}

TEST(TileSampling, TilesSampleTheWholeRunsCellsOffTheirLinesAndTheSameSparseCellsOnThem) {
  const Dem whole = wholeDem();
  for (int size : {6, 15, 30}) {
    std::set<Cell> expected;
    for (const SampleCell& c : sampleCells(whole, 3, 11, kRange))
      if (!onGridLine(whole, size, {c.row, c.col})) expected.insert({c.row, c.col});
    std::set<Cell> offLines;
    std::map<Cell, int> lineSightings;  // a line cell: how many tiles sampled it
    std::map<Cell, int> windows;        // a line cell: how many tiles read it
    std::size_t lineCells = 0;
    for (const TileSpec& t : allTiles(whole, size)) {
      const Dem dem = tileOf(whole, t);
      for (const SampleCell& c : sampleCells(dem, 3, 11, kRange)) {
        const Cell g{dem.globalRow(c.row), dem.globalCol(c.col)};
        if (onGridLine(whole, size, g)) ++lineSightings[g];
        else offLines.insert(g);
      }
      for (int r = 0; r < dem.height; ++r)
        for (int c = 0; c < dem.width; ++c) {
          const Cell g{dem.globalRow(r), dem.globalCol(c)};
          if (onGridLine(whole, size, g) && dem.valid(r, c)) ++windows[g], lineCells += windows[g] == 1;
        }
    }
    EXPECT_EQ(offLines, expected) << "tile size " << size;
    for (const auto& [cell, seen] : lineSightings)
      EXPECT_EQ(seen, windows[cell]) << "line cell " << cell.first << "," << cell.second << ", tile size " << size;
    // About one cell a block of a line, as the interior has one a block: not every cell.
    EXPECT_LT(lineSightings.size() * 2, lineCells) << "tile size " << size;
    EXPECT_GT(lineSightings.size() * 4, lineCells) << "tile size " << size;
  }
}

TEST(TileSampling, OtherSeedPicksOtherCells) {
  const Dem whole = wholeDem();
  std::set<Cell> a, b;
  for (const SampleCell& c : sampleCells(whole, 3, 11, kRange)) a.insert({c.row, c.col});
  for (const SampleCell& c : sampleCells(whole, 3, 12, kRange)) b.insert({c.row, c.col});
  EXPECT_NE(a, b);
}

struct Place {
  double x, y;
  bool operator==(const Place& o) const { return std::memcmp(this, &o, sizeof(Place)) == 0; }
};

std::map<Cell, Place> places(const Dem& dem, const Tin& tin) {
  std::map<Cell, Place> m;
  for (const TinVertex& v : tin.vertices) m[{dem.globalRow(v.row), dem.globalCol(v.col)}] = {v.x, v.y};
  return m;
}

TEST(TileSampling, VerticesLieExactlyWhereTheWholeRunPutsThemAndBorderVerticesAlikeInBothTiles) {
  const Dem whole = wholeDem();
  SampleOptions o;
  o.seed = 5;
  o.jitter = 0.9;
  const int size = 15;
  const std::map<Cell, Place> wholePlaces = places(whole, sampleTin(whole, o, kRange));
  std::map<Cell, Place> border;
  std::size_t compared = 0, shared = 0;
  for (const TileSpec& t : allTiles(whole, size)) {
    const Dem dem = tileOf(whole, t);
    for (const auto& [cell, place] : places(dem, sampleTin(dem, o, kRange))) {
      if (onGridLine(whole, size, cell)) {
        const auto [it, inserted] = border.emplace(cell, place);
        if (!inserted) {
          EXPECT_TRUE(it->second == place) << "cell " << cell.first << "," << cell.second;
          ++shared;
        }
        continue;
      }
      const auto w = wholePlaces.find(cell);
      ASSERT_NE(w, wholePlaces.end()) << "cell " << cell.first << "," << cell.second << " is not sampled by the whole run";
      EXPECT_TRUE(w->second == place) << "cell " << cell.first << "," << cell.second;
      ++compared;
    }
  }
  EXPECT_GT(compared, 200u);
  EXPECT_GT(shared, 30u);
}

// A tile lists the cells of its edges near a missing cell of the whole raster, beyond the
// tile included, those next to one, and those that are peaks or pits of the whole raster,
// and no others: the border rule samples and pins them alike in both tiles.
TEST(TileReader, EdgeCellsNearAMissingCellAndPeaksAndPitsAreThoseOfTheWholeRaster) {
  const Dem whole = wholeDem();  // its void is around row 20, column 33
  const std::string path = test::tempDir() + "/tile_reader_near.tif";
  writeDemGeoTiff(whole, path);
  const int reach = 4;
  std::size_t anyNear = 0, anyExtreme = 0, anyNext = 0, nearOnLine = 0, nearOnLineSampled = 0;
  for (const TileSpec& tile : allTiles(whole, 30)) {
    const Dem dem = readTile(path, 1, tile, reach, kRange, {});
    const CellWindow w = tileWindow({whole.width, whole.height}, tile);
    ASSERT_TRUE(std::is_sorted(dem.nearNodata.begin(), dem.nearNodata.end()));
    std::size_t listed = 0, extremes = 0;
    for (int r = 0; r < dem.height; ++r)
      for (int c = 0; c < dem.width; ++c) {
        const bool edge = r == 0 || c == 0 || r == dem.height - 1 || c == dem.width - 1;
        bool near = false, next = false;
        for (int dr = -reach; dr <= reach && edge; ++dr)
          for (int dc = -reach; dc <= reach; ++dc) {
            const int rr = w.yoff + r + dr, cc = w.xoff + c + dc;
            const bool missing = rr >= 0 && cc >= 0 && rr < whole.height && cc < whole.width && !whole.valid(rr, cc);
            near = near || missing;
            next = next || (missing && std::abs(dr) <= 1 && std::abs(dc) <= 1);
          }
        EXPECT_EQ(dem.nearNodataAt(r, c), near) << "tile " << tile.col << "," << tile.row << " cell " << r << "," << c;
        EXPECT_EQ(dem.nextToNodataAt(r, c), next) << "tile " << tile.col << "," << tile.row << " cell " << r << "," << c;
        listed += near, anyNext += next;
        // On a shared line (its corners always vertices): every cell next to nodata a vertex,
        // the others near it as the line's blocks say.
        const bool rowEdge = r == 0 || r == dem.height - 1, colEdge = c == 0 || c == dem.width - 1;
        if (dem.valid(r, c) && onSharedLine(dem, r, c) && rowEdge != colEdge) {
          const bool sampled = lineCellSampled(dem, r, c, 3, 11);
          if (next) EXPECT_TRUE(sampled) << "tile " << tile.col << "," << tile.row << " cell " << r << "," << c;
          if (near && !next) ++nearOnLine, nearOnLineSampled += sampled;
        }
        const bool extreme = edge && strictPeakOrPit(whole, w.yoff + r, w.xoff + c);
        EXPECT_EQ(dem.edgePeakOrPitAt(r, c), extreme) << "tile " << tile.col << "," << tile.row << " cell " << r << "," << c;
        extremes += extreme;
      }
    EXPECT_EQ(std::set<std::size_t>(dem.nearNodata.begin(), dem.nearNodata.end()).size(), listed);
    EXPECT_EQ(dem.edgePeaksAndPits.size(), extremes);
    anyNear += listed, anyExtreme += extremes;
  }
  EXPECT_GT(anyNear, anyNext);
  EXPECT_GT(nearOnLineSampled, 0u);
  EXPECT_LT(nearOnLineSampled * 2, nearOnLine);  // about one a block of 3, not every one
  EXPECT_GT(anyNext, 0u);
  EXPECT_GT(anyExtreme, 0u);
}

TEST(TileWindow, TilesShareOneLineAndCoverTheRaster) {
  EXPECT_EQ(TileSpec::count(10, 3), 3);
  EXPECT_EQ(TileSpec::count(11, 3), 4);
  EXPECT_EQ(TileSpec::count(1, 3), 1);
  const CellWindow last = tileWindow({11, 7}, {3, 3, 1});
  EXPECT_EQ(last.xoff, 9);
  EXPECT_EQ(last.xsize, 2);
  EXPECT_EQ(last.yoff, 3);
  EXPECT_EQ(last.ysize, 4);
  EXPECT_THROW(tileWindow({11, 7}, {3, 4, 0}), Error);
}

}  // namespace
}  // namespace tinlod
