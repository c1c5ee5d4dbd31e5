// SPDX-License-Identifier: GPL-3.0-or-later
// The line cells on a tile's outline at level 0 (lineOutlineCells), which tiles of a job keep
// at every level instead of every line cell near nodata (-line_outline): they are the line
// vertices whose triangles do not cover the half disc on the tile's side, and two tiles that
// keep the union of their lists delete the same line vertices at every level, more of them
// than with every cell near nodata kept.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <unordered_set>

#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_borders.h"
#include "tinlod/tile_reader.h"

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);
constexpr int kSize = 60, kLine = 60, kBlock = 3;  // two tiles across, sharing column 60
constexpr double kPi = 3.14159265358979323846;

bool missing(int r, int c) {
  return (r >= 10 && r <= 13 && c >= 58 && c <= 62) ||  // across the line
         (r >= 28 && r <= 31 && c >= 55 && c <= 57) ||  // three cells left of it
         (r >= 44 && r <= 46 && c >= 62 && c <= 64) ||  // two cells right of it
         (r >= 36 && r <= 38 && c >= 61 && c <= 63) ||  // beside it, on the right,
         ((r == 36 || r == 38) && c == kLine) ||         // round one line cell there
         (r == 52 && c == kLine);                       // one cell on it
}

// Rolling terrain with voids near the line, one of them leaving a line cell to one tile only.
std::string demWithVoids() {
  static const std::string path = [] {
    Dem dem = test::makeDem(2 * kSize + 1, 61, 10, [](int r, int c) {
      return missing(r, c) ? NAN : float(100 + 20 * std::sin(r / 5.0) * std::cos(c / 7.0) + 0.3 * c);
    });
    const std::string p = test::tempDir() + "/line_outline_dem.tif";
    writeDemGeoTiff(dem, p);
    return p;
  }();
  return path;
}

struct Tile {
  Dem dem;
  Tin tin;
};

Tile readTileTin(int col) {
  Tile t{readTile(demWithVoids(), 1, {kSize, col, 0}, pinningDistance(kBlock), kQuiet, HeightRange{}), {}};
  SampleOptions o;
  o.block = kBlock;
  t.tin = sampleTin(t.dem, o, kQuiet);
  return t;
}

// By hand: the line's sampled cells (corners aside) that are no vertex, or whose triangles'
// angles at the vertex add up to less than the half disc (the line's vertices lie on it).
std::set<std::uint64_t> cellsShortOfTheHalfDisc(const Tile& t) {
  const int col = t.dem.window.colOffset == 0 ? t.dem.width - 1 : 0;
  std::set<std::uint64_t> out;
  for (int row = 1; row + 1 < t.dem.height; ++row) {
    if (!t.dem.valid(row, col) || !lineCellSampled(t.dem, row, col, kBlock, SampleOptions{}.seed)) continue;
    double angles = 0;
    bool vertex = false;
    for (const Triangle& tri : t.tin.triangles)
      for (int i = 0; i < 3; ++i) {
        const TinVertex &v = t.tin.vertices[tri[i]], &a = t.tin.vertices[tri[(i + 1) % 3]], &b = t.tin.vertices[tri[(i + 2) % 3]];
        if (v.row != row || v.col != col) continue;
        vertex = true;
        const double ax = a.x - v.x, ay = a.y - v.y, bx = b.x - v.x, by = b.y - v.y;
        angles += std::atan2(std::fabs(ax * by - ay * bx), ax * bx + ay * by);
      }
    if (!vertex || angles < kPi - 1e-9) out.insert(globalCellKey(t.dem.globalRow(row), t.dem.globalCol(col)));
  }
  return out;
}

TEST(LineOutline, TheListedCellsAreTheLineVerticesWhoseTrianglesLeaveAGap) {
  std::size_t listedInBoth = 0;
  for (int col : {0, 1}) {
    const Tile t = readTileTin(col);
    const std::vector<std::uint64_t> listed = lineOutlineCells(t.dem, t.tin, kBlock, SampleOptions{}.seed);
    EXPECT_EQ(std::set<std::uint64_t>(listed.begin(), listed.end()), cellsShortOfTheHalfDisc(t)) << "tile " << col;
    // Every one is near nodata, and fewer than the line's cells near nodata are listed.
    std::size_t near = 0;
    for (int row = 0; row < t.dem.height; ++row) near += t.dem.valid(row, col ? 0 : kSize) && t.dem.nearNodataAt(row, col ? 0 : kSize);
    for (const std::uint64_t key : listed)
      EXPECT_TRUE(t.dem.nearNodataAt(int(globalCellRow(key)), col ? 0 : kSize)) << globalCellRow(key);
    EXPECT_GE(listed.size(), 4u) << "tile " << col;
    EXPECT_LT(listed.size(), near / 2) << "tile " << col;
    listedInBoth += listed.size();
  }
  EXPECT_GT(listedInBoth, 0u);
}

TEST(LineOutline, TheCellBesideAMissingCellOnTheLineIsListedByBothTiles) {
  for (int col : {0, 1}) {
    const Tile t = readTileTin(col);
    const std::vector<std::uint64_t> listed = lineOutlineCells(t.dem, t.tin, kBlock, SampleOptions{}.seed);
    // The cells next to one are all sampled, and the line's edge across it bridges nodata.
    EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), globalCellKey(51, kLine))) << "tile " << col;
    EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), globalCellKey(53, kLine))) << "tile " << col;
  }
}

// The tiles' line vertices (whole-raster rows on column kLine) by level.
std::vector<std::multiset<long long>> lineRowsByLevel(const std::string& file, int tileCol) {
  const Hierarchy h = readHierarchy(file, kQuiet).hierarchy;
  std::vector<std::multiset<long long>> out(h.coarsest() + 1);
  for (VertexId v = 0; v < h.base.vertices.size(); ++v) {
    if (h.base.vertices[v].col != (tileCol ? 0 : kSize)) continue;
    for (int level = 0; level <= std::min<int>(h.vertexLevel[v], h.coarsest()); ++level) out[level].insert(h.base.vertices[v].row);
  }
  return out;
}

std::string buildTile(int col, const std::string& outline) {
  HierarchyOptions o;
  o.lineOutline = outline;
  const std::string file = test::tempDir() + "/line_outline_" + std::to_string(col) + (outline.empty() ? "" : "_listed") + ".gpkg";
  runBuildJob(demWithVoids(), file, {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), {kSize, col, 0});
  return file;
}

std::string writeList(const std::set<std::uint64_t>& cells, const std::string& name) {
  const std::string path = test::tempDir() + "/" + name;
  std::ofstream out(path);
  for (const std::uint64_t key : cells) out << globalCellRow(key) << " " << globalCellCol(key) << "\n";
  return path;
}

TEST(LineOutline, TilesKeepingTheUnionDeleteTheSameLineVerticesAndMoreOfThem) {
  std::set<std::uint64_t> both;
  for (int col : {0, 1}) {
    const Tile t = readTileTin(col);
    for (const std::uint64_t key : lineOutlineCells(t.dem, t.tin, kBlock, SampleOptions{}.seed)) both.insert(key);
  }
  const std::string list = writeList(both, "line_outline.txt");
  const auto left = lineRowsByLevel(buildTile(0, list), 0), right = lineRowsByLevel(buildTile(1, list), 1);
  ASSERT_EQ(left.size(), right.size());
  // Beside a void one tile may lack a line cell the other has: compare the places both hold at level 0.
  std::set<long long> shared;
  for (long long row : left[0])
    if (right[0].count(row)) shared.insert(row);
  for (std::size_t level = 0; level < left.size(); ++level)
    for (long long row : shared) EXPECT_EQ(left[level].count(row), right[level].count(row)) << "level " << level << " row " << row;
  // A line cell only one tile has (the other's level 0 left it out: on the list) stays there.
  std::size_t alone = 0;
  for (const auto* one : {&left, &right})
    for (long long row : (*one)[0])
      if (!shared.count(row)) {
        ++alone;
        EXPECT_TRUE(both.count(globalCellKey(row, kLine))) << "row " << row;
        for (std::size_t level = 0; level < one->size(); ++level) EXPECT_EQ((*one)[level].count(row), 1u) << "level " << level;
      }
  EXPECT_GT(alone, 0u) << "the void beside the line leaves a line cell out of one tile";
  const auto keptAll = lineRowsByLevel(buildTile(0, ""), 0);
  EXPECT_LT(left.back().size() + 5, keptAll.back().size()) << "the list should free line vertices near the voids";
}

// A survey counts the border rule's picks as the union counts them (a half each: the line is
// two tiles'), for the driver to leave them room in each level's share: before, every level
// deleted them on top of it.
TEST(LineOutline, ASurveyCountsTheBorderRulesPicksAsHalvesOfTheUnion) {
  std::unordered_set<std::uint64_t> both;  // as the build pass keeps them: the others near the voids may go
  for (int col : {0, 1}) {
    const Tile t = readTileTin(col);
    for (const std::uint64_t key : lineOutlineCells(t.dem, t.tin, kBlock, SampleOptions{}.seed)) both.insert(key);
  }
  for (int col : {0, 1}) {
    SCOPED_TRACE("tile " + std::to_string(col));
    const Tile t = readTileTin(col);
    HierarchyOptions o;
    o.survey = true;
    TileBorders borders = tileBorders(t.dem, t.tin, {kSize, col, 0}, tileLevelCount(o.deletePct, o.stopPct), kBlock,
                                      SampleOptions{}.seed, 100.0);
    pinLineOutlineOnly(borders, t.dem, t.tin, both, "the union's list");
    const Hierarchy h = buildHierarchy(t.tin, t.dem, {}, o, kQuiet, {}, &borders);
    ASSERT_GT(h.survey.size(), 3u);
    const int line = col ? 0 : kSize;
    double picked = 0;
    for (const LevelSurvey& l : h.survey) {
      std::size_t gone = 0;
      for (VertexId v = 0; v < h.base.vertices.size(); ++v)
        gone += h.base.vertices[v].col == line && h.vertexLevel[v] == l.level - 1;
      EXPECT_EQ(l.borderPicked, 0.5 * double(gone)) << "level " << l.level;
      picked += l.borderPicked;
    }
    EXPECT_GT(picked, 5.0);
  }
}

TEST(LineOutline, AListWithoutTheTilesOwnCellsIsRefusedNamingOne) {
  const std::string list = writeList({globalCellKey(1, kLine)}, "line_outline_stale.txt");
  const std::string error = test::errorOf([&] { buildTile(0, list); });
  EXPECT_TRUE(test::contains(error, "-line_outline: '" + list + "' does not list the line cell ")) << error;
  EXPECT_TRUE(test::contains(error, "the list is not this job's")) << error;
}

TEST(LineOutline, OnlyATileOfABuildPassTakesAList) {
  HierarchyOptions o;
  o.lineOutline = "x.txt";
  EXPECT_TRUE(test::contains(test::errorOf([&] {
    runBuildJob(demWithVoids(), test::tempDir() + "/x.gpkg", {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), {});
  }), "-line_outline is for a tile of a job"));
  o.survey = true;
  EXPECT_TRUE(test::contains(test::errorOf([&] {
    runBuildJob(demWithVoids(), test::tempDir() + "/x.json", {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), {kSize, 0, 0});
  }), "a first -survey lists the tile's own outline cells"));
}

}  // namespace
}  // namespace tinlod
