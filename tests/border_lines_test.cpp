// SPDX-License-Identifier: GPL-3.0-or-later
// The border rule with the raster's volume threshold: a shared line loses only the cells
// whose volume estimate (the deviation from the line between their neighbours, as a cone
// over a span x span rhombus) is below the level's threshold, as both tiles on the line
// compute it alike.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <unordered_set>

#include "border_lines.h"
#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/sample_job.h"
#include "tinlod/tile_reader.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);
constexpr int kSize = 60, kLineCol = 60, kBlock = 3;
constexpr std::uint64_t kSeed = 7;
constexpr double kCellArea = 2;

// Tile `col`'s window of `whole`, as readTile reads it.
Dem tileDem(const Dem& whole, int col) {
  const CellWindow w = tileWindow({whole.width, whole.height}, {kSize, col, 0});
  Dem dem = whole;
  cropDem(dem, w.xoff, w.yoff, w.xsize, w.ysize);
  return dem;
}

// The rows of the line's sampled cells, in order (its ends included): the line the rule reads.
std::vector<int> lineRows(const Dem& whole) {
  const Dem left = tileDem(whole, 0);
  std::vector<int> rows;
  for (int r = 0; r < left.height; ++r)
    if (lineCellSampled(left, r, kLineCol, kBlock, kSeed)) rows.push_back(int(left.globalRow(r)));
  return rows;
}

// A plane, but for two spikes on the line: 10 m at its 6th sampled cell, 20 m at its 12th.
Dem wholeDem() {
  Dem flat = test::makeDem(2 * kSize + 1, kSize + 1, 10, [](int, int) { return 0.f; });
  flat.window.fullWidth = flat.width, flat.window.fullHeight = flat.height, flat.window.fullGeotransform = flat.geotransform;
  const std::vector<int> rows = lineRows(flat);
  const std::map<int, double> spikes{{rows.at(5), 10.0}, {rows.at(11), 20.0}};
  Dem dem = test::makeDem(2 * kSize + 1, kSize + 1, 10, [&](int r, int c) {
    return float(100 + 0.5 * r + 0.25 * c + (c == kLineCol && spikes.count(r) ? spikes.at(r) : 0));
  });
  dem.window = flat.window;
  return dem;
}

struct TileLine {
  Dem dem;
  Tin tin;
  TileBorders borders;
};

Tin sampled(const Dem& dem) {
  SampleOptions o;
  o.block = kBlock;
  o.seed = kSeed;
  return sampleTin(dem, o, kRange);
}

TileLine tile(const Dem& whole, int col) {
  TileLine t{tileDem(whole, col), {}, {}};
  t.tin = sampled(t.dem);
  t.borders = tileBorders(t.dem, t.tin, {kSize, col, 0}, 10, kBlock, kSeed, kCellArea);
  return t;
}

// What the line's first thinning takes within `limit`: whole-raster row -> importance.
std::map<int, double> taken(const TileLine& t, BorderLines::Limit limit) {
  const int side = t.dem.window.colOffset == 0 ? kLastCol : kFirstCol;
  BorderLines lines(t.tin, t.dem, t.borders);
  std::map<int, double> out;
  for (const auto& [importance, v] : lines.take(1 + t.borders.lineClass[side], 0.5, limit)) {
    EXPECT_NE(v, BorderLines::kNoVertex);
    if (v != BorderLines::kNoVertex) out[int(t.dem.globalRow(t.tin.vertices[v].row))] = importance;
  }
  return out;
}

BorderLines::Limit volumeBelow(double v) { return {BorderLines::Limit::kVolume, v}; }

// The deviation of the cell at `i` of the line from the line between its neighbours, by hand.
double deviationAt(const Dem& whole, const std::vector<int>& rows, std::size_t i) {
  auto z = [&](std::size_t k) { return double(whole.at(rows[k], kLineCol)); };
  const double f = double(rows[i] - rows[i - 1]) / (rows[i + 1] - rows[i - 1]);
  return std::fabs(z(i) - (z(i - 1) + f * (z(i + 1) - z(i - 1))));
}

// The estimate of the cell at `i` of the line, by hand.
double volumeAt(const Dem& whole, const std::vector<int>& rows, std::size_t i) {
  auto z = [&](std::size_t k) { return double(whole.at(rows[k], kLineCol)); };
  const double f = double(rows[i] - rows[i - 1]) / (rows[i + 1] - rows[i - 1]);
  const double deviation = std::fabs(z(i) - (z(i - 1) + f * (z(i + 1) - z(i - 1))));
  const double span = rows[i + 1] - rows[i - 1];
  return deviation * span * span * kCellArea / 6;
}

TEST(BorderLines, BelowTheThresholdOnlyCellsOfLittleVolumeGoAndTheSpikesStay) {
  const Dem whole = wholeDem();
  const std::vector<int> rows = lineRows(whole);
  ASSERT_GE(rows.size(), 15u);
  const std::map<int, double> gone = taken(tile(whole, 0), volumeBelow(1e-6));
  EXPECT_GE(gone.size(), 4u);
  // Cells 4 to 6 and 10 to 12 deviate (the spikes and their neighbours); none of them goes.
  for (std::size_t i : {4, 5, 6, 10, 11, 12}) EXPECT_EQ(gone.count(rows[i]), 0u) << "cell " << i;
  for (const auto& [row, importance] : gone) EXPECT_LT(importance, 1e-6) << "row " << row;
}

TEST(BorderLines, ImportanceIsTheVolumeEstimateAndTheThresholdCutsBetweenTheSpikes) {
  const Dem whole = wholeDem();
  const std::vector<int> rows = lineRows(whole);
  const double spike5 = volumeAt(whole, rows, 5), spike11 = volumeAt(whole, rows, 11);
  ASSERT_GT(spike5, 0);
  const std::map<int, double> all = taken(tile(whole, 0), volumeBelow(1e12));
  ASSERT_GE(all.size(), 5u);
  for (const auto& [row, importance] : all) {
    const std::size_t i = std::find(rows.begin(), rows.end(), row) - rows.begin();
    ASSERT_LT(i + 1, rows.size());
    EXPECT_NEAR(importance, volumeAt(whole, rows, i), 1e-9 * (1 + importance)) << "row " << row;
  }
  // A threshold between the two spikes' estimates lets the smaller go, never the larger.
  ASSERT_LT(spike5, spike11);
  const std::map<int, double> gone = taken(tile(whole, 0), volumeBelow(0.5 * (spike5 + spike11)));
  EXPECT_EQ(gone.count(rows[11]), 0u);
  EXPECT_EQ(gone.count(rows[5]), 1u);
}

TEST(BorderLines, BothTilesOnTheLineTakeTheSameCells) {
  const Dem whole = wholeDem();
  for (double below : {1e-6, 50.0, 1e12}) {
    for (const auto kind : {BorderLines::Limit::kVolume, BorderLines::Limit::kDeviation}) {
      const BorderLines::Limit limit{kind, below};
      const std::map<int, double> left = taken(tile(whole, 0), limit), right = taken(tile(whole, 1), limit);
      EXPECT_FALSE(left.empty());
      EXPECT_EQ(left, right) << "below " << below;
    }
  }
}

// Under -max_error a cell goes only if its own deviation is within it: the spikes stay.
TEST(BorderLines, UnderADeviationLimitOnlyCellsWithinItGoAndTheSpikesStay) {
  const Dem whole = wholeDem();
  const std::vector<int> rows = lineRows(whole);
  const double spike5 = deviationAt(whole, rows, 5), spike11 = deviationAt(whole, rows, 11);
  ASSERT_LT(spike5, spike11);
  const std::map<int, double> gone = taken(tile(whole, 0), {BorderLines::Limit::kDeviation, 0.5 * (spike5 + spike11)});
  EXPECT_GE(gone.size(), 4u);
  EXPECT_EQ(gone.count(rows[11]), 0u);
  for (const auto& [row, importance] : gone) {
    const std::size_t i = std::find(rows.begin(), rows.end(), row) - rows.begin();
    ASSERT_LT(i + 1, rows.size());
    EXPECT_DOUBLE_EQ(importance, deviationAt(whole, rows, i)) << "row " << row;
    EXPECT_LE(importance, 0.5 * (spike5 + spike11));
  }
}

// A cell the tiles agreed to keep is pinned in both and never taken.
TEST(BorderLines, AKeptCellNeverGoesInEitherTile) {
  const Dem whole = wholeDem();
  const BorderLines::Limit all{BorderLines::Limit::kDeviation, 1e12};
  const std::map<int, double> before = taken(tile(whole, 0), all);
  ASSERT_FALSE(before.empty());
  const int keptRow = before.begin()->first;
  for (int col : {0, 1}) {
    TileLine t = tile(whole, col);
    t.borders = agreedTileBorders(t.dem, t.tin, {kSize, col, 0}, 10, kBlock, kSeed, kCellArea, false,
                                  {globalCellKey(keptRow, kLineCol)});
    EXPECT_TRUE(t.borders.agreed);
    const std::map<int, double> after = taken(t, all);
    EXPECT_EQ(after.count(keptRow), 0u) << "tile " << col;
    EXPECT_FALSE(after.empty());
    EXPECT_EQ(cellsOnSharedLines(t.dem, t.borders.kept), std::vector<std::uint64_t>{globalCellKey(keptRow, kLineCol)});
    std::size_t pinned = 0;
    for (std::size_t v = 0; v < t.tin.vertices.size(); ++v)
      if (t.dem.globalRow(t.tin.vertices[v].row) == keptRow && t.dem.globalCol(t.tin.vertices[v].col) == kLineCol)
        pinned += t.borders.pinned[v];
    EXPECT_EQ(pinned, 1u) << "tile " << col;
  }
}

// What the lines take level by level: whole-raster row -> the level it goes at.
std::map<int, int> levelsTaken(const TileLine& t, BorderLines& lines, const std::function<bool(VertexId)>& accept,
                               std::set<int>& refusedRows) {
  std::map<int, int> out;
  const auto rowOf = [&](VertexId v) { return int(t.dem.globalRow(t.tin.vertices[v].row)); };
  for (int level = 1; level <= 12; ++level) {
    std::vector<VertexId> refused;
    for (const auto& [importance, v] : lines.take(level, 0.5, {BorderLines::Limit::kDeviation, 1e12}, accept, refused))
      out[rowOf(v)] = level;
    for (VertexId v : refused) refusedRows.insert(rowOf(v));
  }
  return out;
}

// A cell refused when the rule takes it is pinned and the line chosen again: the levels
// then taken are those of a tile that kept it from the start (the next round's), so the
// round after the refusals finds the same lines.
TEST(BorderLines, ARefusedCellIsAsIfKeptFromTheStart) {
  const Dem whole = wholeDem();
  const std::vector<int> rows = lineRows(whole);
  TileLine t = tile(whole, 0);
  std::set<int> refused, none;
  BorderLines refusing(t.tin, t.dem, t.borders);
  // Refuse every third row the rule takes: some at level 1, some later.
  int asked = 0;
  const std::map<int, int> taken = levelsTaken(t, refusing, [&](VertexId) { return ++asked % 3 != 0; }, refused);
  ASSERT_GE(refused.size(), 3u);
  std::unordered_set<std::uint64_t> kept;
  for (int row : refused) kept.insert(globalCellKey(row, kLineCol));
  t.borders = agreedTileBorders(t.dem, t.tin, {kSize, 0, 0}, 10, kBlock, kSeed, kCellArea, false, kept);
  BorderLines keeping(t.tin, t.dem, t.borders);
  const std::map<int, int> fromTheStart = levelsTaken(t, keeping, [](VertexId) { return true; }, none);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(taken, fromTheStart);
  for (int row : refused) EXPECT_EQ(taken.count(row), 0u) << "row " << row;
  // Without the refusals the lines go otherwise: the test tells them apart.
  TileLine plain = tile(whole, 0);
  BorderLines all(plain.tin, plain.dem, plain.borders);
  EXPECT_NE(levelsTaken(plain, all, [](VertexId) { return true; }, none), taken);
}

// The volume estimate is in the TIN's area units: a tile made without them would thin its
// lines by a wrong estimate, silently.
TEST(BorderLines, ATileNeedsItsCellArea) {
  const Dem dem = tileDem(wholeDem(), 0);
  const Tin tin = sampled(dem);
  for (double bad : {0.0, -1.0, double(NAN), double(INFINITY)})
    EXPECT_THROW(tileBorders(dem, tin, {kSize, 0, 0}, 10, kBlock, kSeed, bad), Error) << bad;
  EXPECT_EQ(tileBorders(dem, tin, {kSize, 0, 0}, 10, kBlock, kSeed, kCellArea).cellArea, kCellArea);
}

}  // namespace
}  // namespace tinlod
