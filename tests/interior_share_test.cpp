// SPDX-License-Identifier: GPL-3.0-or-later
// The warning of an interior emptied behind an outline that stays, and its -stop_pct.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "interior_share.h"
#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/hierarchy_info.h"

namespace tinlod {
namespace {

std::vector<LevelStats> levels(const std::vector<std::array<std::size_t, 2>>& verticesAndOutline) {
  std::vector<LevelStats> out;
  for (const auto& [v, o] : verticesAndOutline) {
    LevelStats l;
    l.level = static_cast<std::int32_t>(out.size()), l.vertices = v, l.outlineVertices = o, l.rmse = 1.0 + out.size();
    out.push_back(l);
  }
  return out;
}

TEST(InteriorShare, AnInteriorKeptAsAskedIsNotWarned) {
  // 5 % of 1000 vertices, 20 of them on the outline: the inside keeps 30 of 980 (3.1 %).
  EXPECT_EQ(starvedInteriorWarning(levels({{1000, 20}, {500, 20}, {100, 20}, {50, 20}}), 5), "");
  EXPECT_EQ(starvedInteriorWarning(levels({{1000, 20}}), 5), "");
}

TEST(InteriorShare, AnEmptiedInteriorIsWarnedWithTheStopPctThatKeepsItsShare) {
  // Inside: 800, 500, 200, 60 (7.5 %), 30 (3.75 %), 10 (1.25 %, under half of 5 %).
  const auto l = levels({{1000, 200}, {700, 200}, {400, 200}, {260, 200}, {230, 200}, {210, 200}});
  EXPECT_EQ(starvedInteriorWarning(l, 5),
            "the coarsest level keeps 10 of level 0's 800 vertices off the outline (1.25 %), far under the 5 % asked "
            "for: the outline's vertices stay, so the levels went on deleting the inside alone; -stop_pct 26.0 stops at "
            "level 3, which keeps 7.5 % of them (RMSE 4 m against 6 m)");
  // Level 3's 260 vertices are 26 % of 1000: ceil(26 % of 1000) = 260, under level 2's 400.
  // 10 % asked for: level 2 is the last to keep it (200 of 800).
  EXPECT_NE(starvedInteriorWarning(l, 10).find("-stop_pct 40.0 stops at level 2, which keeps 25.0 %"), std::string::npos);
}

TEST(InteriorShare, ADecimalMoreWhenOneCannotTellTwoLevelsApart) {
  // Levels 1 and 2 hold 20,000 and 19,700 of 1,000,000 vertices: 2.0 % would keep level 1's
  // 20,000 and make no level 2; 1.97 % stops right after it. Inside: 981,000, 1,000, 700
  // (0.07 % of 981,000 is 686.7), 300.
  const auto l = levels({{1000000, 19000}, {20000, 19000}, {19700, 19000}, {19300, 19000}});
  EXPECT_NE(starvedInteriorWarning(l, 0.07).find("-stop_pct 1.97 stops at level 2"), std::string::npos)
      << starvedInteriorWarning(l, 0.07);
}

// A DEM of 300 x 300 cells with a void of 2 x 2 cells every 10 cells: 900 voids, each ringed.
std::string peppered() {
  static const std::string path = [] {
    const Dem dem = test::makeDem(300, 300, 30, [](int col, int row) {
      if (col % 10 >= 4 && col % 10 < 6 && row % 10 >= 4 && row % 10 < 6) return NAN;
      return float(500 + 200 * std::sin(col / 23.0) * std::cos(row / 31.0) + 0.05 * ((col * 7919 + row * 104729) % 1000));
    });
    const std::string p = test::tempDir() + "/peppered.tif";
    writeDemGeoTiff(dem, p);
    return p;
  }();
  return path;
}

TEST(InteriorShare, ABuildOfAPepperedDemSaysHowToKeepItsInteriorAndThatStopPctDoesIt) {
  const std::string dir = test::tempDir();
  test::RecordingFeedback fb;
  runBuildJob(peppered(), dir + "/h.gpkg", {}, {}, false, fb.feedback());
  std::smatch m;
  std::string warning;
  for (const std::string& w : fb.warnings)
    if (w.find("vertices off the outline") != std::string::npos) warning = w;
  const std::regex advice(R"(-stop_pct ([0-9.]+) stops at level ([0-9]+), which keeps ([0-9.]+) %)");
  ASSERT_TRUE(std::regex_search(warning, m, advice)) << "warnings: " << fb.warnings.size() << " " << warning;
  const double pct = std::stod(m[1]);
  const int level = std::stoi(m[2]);
  const HierarchyInfo first = readHierarchyInfo(dir + "/h.gpkg");
  const auto inside = [](const LevelStats& l) { return double(l.vertices - l.outlineVertices); };
  EXPECT_LT(inside(first.levels.back()), 0.025 * inside(first.levels.front()));
  // Taken: the build stops at that level, with the same levels up to it, and says nothing more.
  HierarchyOptions o;
  o.stopPct = pct;
  test::RecordingFeedback again;
  runBuildJob(peppered(), dir + "/advised.gpkg", {}, o, false, again.feedback());
  const HierarchyInfo advised = readHierarchyInfo(dir + "/advised.gpkg");
  ASSERT_EQ(advised.levels.size(), std::size_t(level) + 1);
  // The same levels up to it, the last included: the figures the warning gave are the run's.
  for (int L = 0; L <= level; ++L) {
    EXPECT_EQ(advised.levels[L].vertices, first.levels[L].vertices) << "level " << L;
    EXPECT_EQ(advised.levels[L].rmse, first.levels[L].rmse) << "level " << L;
  }
  EXPECT_GE(inside(advised.levels.back()), 0.05 * inside(advised.levels.front()));
  EXPECT_NEAR(100 * inside(advised.levels.back()) / inside(advised.levels.front()), std::stod(m[3]), 0.05);
  for (const std::string& w : again.warnings) EXPECT_EQ(w.find("vertices off the outline"), std::string::npos) << w;
}

// The figures docs/cli/build.md quotes.
TEST(InteriorShare, SwissAlpsWithItsVoidsIsToldTheStopPctOfTheDocs) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  test::RecordingFeedback fb;
  runBuildJob(data + "/swiss_alps_N46E008.tif", test::tempDir() + "/swiss.gpkg", {}, {}, false, fb.feedback());
  EXPECT_TRUE(fb.warned("the coarsest level keeps 346 of level 0's 180156 vertices off the outline (0.19 %), far under "
                        "the 5 % asked for: the outline's vertices stay, so the levels went on deleting the inside alone; "
                        "-stop_pct 13.089 stops at level 10, which keeps 5.4 % of them (RMSE 54.2621 m against 178.744 m)"));
}

}  // namespace
}  // namespace tinlod
