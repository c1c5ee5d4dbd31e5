// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "test_support.h"
#include "tinlod/sampler.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);

Dem flatDem(int w, int h) {
  return test::makeDem(w, h, 10, [](int, int) { return 1.0f; });
}

std::set<std::pair<int, int>> cellSet(const std::vector<SampleCell>& cells) {
  std::set<std::pair<int, int>> s;
  for (const SampleCell& c : cells) s.insert({c.row, c.col});
  return s;
}

TEST(Sampler, SameSeedGivesSameCellsOtherSeedOthers) {
  const Dem dem = flatDem(60, 45);
  const auto a = cellSet(sampleCells(dem, 3, 42, kRange));
  const auto b = cellSet(sampleCells(dem, 3, 42, kRange));
  const auto c = cellSet(sampleCells(dem, 3, 43, kRange));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Sampler, OutlineWholeAndOneRandomCellPerBlock) {
  const Dem dem = flatDem(31, 20);  // blocks at the right and bottom are partial
  const std::vector<SampleCell> cells = sampleCells(dem, 3, 1, kRange);
  std::map<std::pair<int, int>, int> randomPerBlock, outlinePerBlock;
  std::size_t outline = 0;
  for (const SampleCell& c : cells) {
    const bool onEdge = c.row == 0 || c.col == 0 || c.row == dem.height - 1 || c.col == dem.width - 1;
    EXPECT_EQ(c.outline, onEdge) << c.row << "," << c.col;
    outline += c.outline;
    (c.outline ? outlinePerBlock : randomPerBlock)[{c.row / 3, c.col / 3}]++;
  }
  EXPECT_EQ(outline, std::size_t(2 * (31 + 20) - 4));  // every edge cell, each once
  for (int br = 0; br < 7; ++br)
    for (int bc = 0; bc < 11; ++bc) {
      const std::pair<int, int> block{br, bc};
      EXPECT_LE(randomPerBlock[block], 1);
      // A block without outline cells holds exactly its one random sample.
      if (outlinePerBlock[block] == 0) {
        EXPECT_EQ(randomPerBlock[block], 1) << br << "," << bc;
      }
    }
}

TEST(Sampler, BlockOneTakesEveryValidCell) {
  Dem dem = test::makeDem(5, 4, 10, [](int r, int c) { return (r == 1 && c >= 1 && c <= 3) ? NAN : 5.0f; });
  const std::vector<SampleCell> cells = sampleCells(dem, 1, 9, kRange);
  EXPECT_EQ(cells.size(), 17u);
  for (const SampleCell& c : cells) EXPECT_TRUE(dem.valid(c.row, c.col));
}

TEST(Sampler, NodataNeverSampledAndItsRimIsOutline) {
  const Dem dem = test::makeDem(30, 30, 10, [](int r, int c) { return std::hypot(r - 15, c - 15) < 6 ? NAN : 1.0f; });
  std::size_t rim = 0;
  for (const SampleCell& c : sampleCells(dem, 3, 5, kRange)) {
    ASSERT_TRUE(dem.valid(c.row, c.col));
    if (std::abs(std::hypot(c.row - 15, c.col - 15) - 6.5) < 0.4) {
      EXPECT_TRUE(c.outline);
      ++rim;
    }
  }
  EXPECT_GT(rim, 10u);  // the rim is taken whole: some 40 cells lie within 0.4 of radius 6.5
}

TEST(Sampler, RandomCellIsUniformOverTheBlock) {
  // One 5 x 5 block: its 16 edge cells are outline, so a random pick that lands on
  // one of the 9 inner cells shows up as the only non-outline sample.
  const Dem dem = flatDem(5, 5);
  std::map<std::pair<int, int>, int> hits;
  const int runs = 9000;
  for (int seed = 0; seed < runs; ++seed)
    for (const SampleCell& c : sampleCells(dem, 5, seed, kRange))
      if (!c.outline) hits[{c.row, c.col}]++;
  // The random cell is uniform over all 25 cells; 9 of them are interior.
  int interior = 0;
  for (const auto& [cell, n] : hits) {
    interior += n;
    EXPECT_NEAR(n, runs / 25.0, 4 * std::sqrt(runs / 25.0)) << cell.first << "," << cell.second;
  }
  EXPECT_EQ(hits.size(), 9u);
  EXPECT_NEAR(interior, runs * 9 / 25.0, 4 * std::sqrt(runs * 9 / 25.0 * 16 / 25.0));
}

}  // namespace
}  // namespace tinlod
