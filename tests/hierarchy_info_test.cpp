// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <string>

#include "tinlod/hierarchy_info.h"

namespace tinlod {
namespace {

// A 1 cm LiDAR TIN's errors read "0.03" and "0.01" to the two decimals metres of an SRTM TIN
// need: as many decimals as show them.
TEST(HierarchyInfo, ErrorsShowAsManyDecimalsAsTheirSizeNeeds) {
  HierarchyInfo info;
  info.path = "lidar.gpkg", info.kind = "hierarchy", info.crsName = "ETRS89 / UTM zone 32N (EPSG:25832)";
  LevelStats level;
  level.maxError = 0.0418, level.rmse = 0.0049;
  info.levels = {level};
  EXPECT_NE(toText(info).find("  0.0418   0.0049"), std::string::npos) << toText(info);
  info.levels[0].maxError = 0.418, info.levels[0].rmse = 0.049;
  EXPECT_NE(toText(info).find("  0.418    0.049"), std::string::npos) << toText(info);
  info.levels[0].maxError = 12.3456, info.levels[0].rmse = 1.234;
  EXPECT_NE(toText(info).find("  12.35     1.23"), std::string::npos) << toText(info);
}

}  // namespace
}  // namespace tinlod
