// SPDX-License-Identifier: GPL-3.0-or-later
// Hostile files are data, not instructions: each damage an attack run found in a stored
// hierarchy, and its neighbours, is refused with one Error naming the file, the table and
// the row, by the reader and by the jobs that used to trust it.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <tuple>

#include "gpkg_surgery.h"
#include "test_support.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/build_job.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/locate_job.h"
#include "tinlod/lod_job.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);


std::string readError(const std::string& gpkg) {
  return test::errorOf([&] { readHierarchy(gpkg, kQuiet); });
}

std::string lodError(const std::string& gpkg) {
  LodJobOptions o;
  o.lod.maxError = 0;  // refines every group: every link is followed
  return test::errorOf([&] { runLodJob(gpkg, test::tempDir() + "/lod.gpkg", o, false, {}); });
}

std::string locateError(const std::string& gpkg, const std::string& points) {
  return test::errorOf([&] { runLocateJob(gpkg, points, test::tempDir() + "/located.gpkg", 0, false, {}); });
}

std::string damage(const std::string& gpkg, const std::string& what) { return "'" + gpkg + "' is damaged: " + what; }

const std::string& hierarchy() { return test::smallHierarchy().gpkg; }

long long coarsest() { return test::sqlInteger(hierarchy(), "SELECT max(level) FROM levels"); }

// A triangle made by deleting a vertex (level above 0) and replaced at a coarser level.
long long linkedTriangle() {
  return test::sqlInteger(hierarchy(),
                          "SELECT fid FROM triangles WHERE group_id IS NOT NULL AND replaced_by IS NOT NULL LIMIT 1");
}

TEST(StoredHierarchy, EveryReaderReadsTheIntactFileAndAnEditableCopy) {
  const test::SmallHierarchy& s = test::smallHierarchy();
  for (const std::string& gpkg : {s.gpkg, test::editableCopy(s.gpkg)}) {
    EXPECT_EQ(lodError(gpkg), "no error");
    EXPECT_EQ(locateError(gpkg, s.points), "no error");
    EXPECT_EQ(test::errorOf([&] { runAccuracyJob(s.dem, gpkg, AccuracyOutputs{}, 0, "", {}); }), "no error");
  }
  EXPECT_GE(coarsest(), 3);
  EXPECT_GT(linkedTriangle(), 0);
}

TEST(StoredHierarchy, AFirstLevelBeyondTheLevelsIsRefusedNotUsedAsAnIndex) {
  const std::string top = std::to_string(coarsest());
  const std::string high = test::alteredCopy(hierarchy(), "UPDATE triangles SET first_level = 99 WHERE fid = 1234");
  EXPECT_EQ(lodError(high), damage(high, "triangles row 1234 has first_level 99 but the levels are 0 to " + top));
  const std::string negative = test::alteredCopy(hierarchy(), "UPDATE triangles SET first_level = -1 WHERE fid = 7");
  EXPECT_EQ(readError(negative), damage(negative, "triangles row 7 has first_level -1 but the levels are 0 to " + top));
  const std::string vertex = test::alteredCopy(hierarchy(), "UPDATE vertices SET level = 2147483647 WHERE fid = 3");
  EXPECT_EQ(readError(vertex), damage(vertex, "vertices row 3 has level 2147483647 but the levels are 0 to " + top));
}

TEST(StoredHierarchy, LevelsOutOfOrderAreRefused) {
  const std::string t = std::to_string(linkedTriangle());
  const std::string before =
      test::alteredCopy(hierarchy(), "UPDATE triangles SET last_level = first_level - 1 WHERE fid = " + t);
  EXPECT_NE(readError(before).find("triangles row " + t + " has first_level"), std::string::npos) << readError(before);
  EXPECT_NE(readError(before).find(": its last level is before its first"), std::string::npos) << readError(before);
  const std::string repeated = test::alteredCopy(hierarchy(), "UPDATE levels SET level = 5 WHERE level = 4");
  EXPECT_EQ(test::errorOf([&] { readHierarchyInfo(repeated); }), damage(repeated, "levels row 6 repeats level 5"));
  const std::string gap = test::alteredCopy(hierarchy(), "DELETE FROM levels WHERE level = 3");
  EXPECT_EQ(readError(gap), damage(gap, "its levels table has no row for level 3 but one for level 4"));
  // A triangle keeps its levels in 16 bits: a level beyond them is not read, whatever
  // else the file says.
  const std::string beyond = test::alteredCopy(hierarchy(), "UPDATE levels SET level = 40000 WHERE level = 0");
  EXPECT_EQ(readError(beyond), damage(beyond, "its levels table has level 40000, above the 32766 a hierarchy may have"));
}

TEST(StoredHierarchy, ReplacedByLinksThatWouldMakeACycleAreRefused) {
  // A triangle replaced by the group that made it: lod followed such links for ever.
  const std::string t = std::to_string(linkedTriangle());
  const std::string cycle =
      test::alteredCopy(hierarchy(), "UPDATE triangles SET replaced_by = group_id WHERE fid = " + t);
  const std::string error = lodError(cycle);
  EXPECT_NE(error.find(damage(cycle, "triangles row " + t + " has first_level")), std::string::npos) << error;
  EXPECT_NE(error.find("a broken link, or one that would make a cycle"), std::string::npos) << error;
  // Pointing at a coarser group than the one that replaces it is as broken.
  const std::string coarser = test::alteredCopy(
      hierarchy(), "UPDATE triangles SET replaced_by = (SELECT max(id) FROM groups) WHERE fid = " + t);
  EXPECT_NE(lodError(coarser).find("a broken link, or one that would make a cycle"), std::string::npos)
      << lodError(coarser);
  const std::string nowhere =
      test::alteredCopy(hierarchy(), "UPDATE triangles SET replaced_by = 999999 WHERE fid = " + t);
  const long long groups = test::sqlInteger(hierarchy(), "SELECT count(*) FROM groups");
  EXPECT_EQ(lodError(nowhere),
            damage(nowhere, "triangles row " + t + " has replaced_by 999999 but the group ids are 1 to " +
                                std::to_string(groups)));
}

TEST(StoredHierarchy, AHierarchyWithoutItsLevelsOrGroupsTableIsRefused) {
  // Read as all level 0 before: every triangle of every level at once.
  const std::string noLevels =
      test::alteredCopy(hierarchy(), "DROP TABLE levels; DELETE FROM gpkg_contents WHERE table_name = 'levels'");
  const std::string expected =
      damage(noLevels, "it is a hierarchy (TINLOD_KIND) but has no levels table; build it again with tinlod build");
  EXPECT_EQ(test::errorOf([&] { readHierarchyInfo(noLevels); }), expected);
  EXPECT_EQ(lodError(noLevels), expected);
  const std::string noGroups =
      test::alteredCopy(hierarchy(), "DROP TABLE groups; DELETE FROM gpkg_contents WHERE table_name = 'groups'");
  EXPECT_EQ(
      readError(noGroups),
      damage(noGroups, "it is a hierarchy (TINLOD_KIND) but has no groups table; build it again with tinlod build"));
  const std::string noColumn = test::alteredCopy(hierarchy(), "ALTER TABLE groups DROP COLUMN vertex");
  EXPECT_EQ(readError(noColumn), damage(noColumn, "its groups table has no column vertex"));
}

TEST(StoredHierarchy, TrianglesWithARepeatedVertexAreRefused) {
  const std::string copy = test::alteredCopy(hierarchy(), "UPDATE triangles SET v1 = v0 WHERE fid = 5");
  const long long v0 = test::sqlInteger(copy, "SELECT v0 FROM triangles WHERE fid = 5");
  const long long v2 = test::sqlInteger(copy, "SELECT v2 FROM triangles WHERE fid = 5");
  EXPECT_EQ(readError(copy), damage(copy, "triangles row 5 repeats a vertex (v0, v1, v2 = " + std::to_string(v0) +
                                              ", " + std::to_string(v0) + ", " + std::to_string(v2) + ")"));
  const std::string missing = test::alteredCopy(hierarchy(), "UPDATE triangles SET v2 = NULL WHERE fid = 6");
  EXPECT_EQ(readError(missing), damage(missing, "triangles row 6 has no v2 (NULL)"));
}

TEST(StoredHierarchy, NegativeAndOverflowingCountsAreRefusedOrNotTrusted) {
  const std::string negative = test::alteredCopy(hierarchy(), "UPDATE levels SET vertices = -5 WHERE level = 3");
  EXPECT_EQ(test::errorOf([&] { readHierarchyInfo(negative); }),
            damage(negative, "levels row 4 has vertices -5 but the counts are 0 to 9223372036854775807"));
  const std::string cells =
      test::alteredCopy(hierarchy(), "UPDATE levels SET cells = -9223372036854775808 WHERE level = 0");
  EXPECT_NE(readError(cells).find("levels row 1 has cells -9223372036854775808"), std::string::npos)
      << readError(cells);
  const std::string wrong =
      test::alteredCopy(hierarchy(), "UPDATE levels SET triangles = triangles + 1 WHERE level = 2");
  const long long triangles = test::sqlInteger(hierarchy(), "SELECT triangles FROM levels WHERE level = 2");
  EXPECT_EQ(readError(wrong),
            damage(wrong, "level 2 has " + std::to_string(triangles) + " triangles in the triangles table but " +
                              std::to_string(triangles + 1) + " in the levels table"));
  // The feature counts GDAL takes from gpkg_ogr_contents size nothing: the file reads as it is.
  for (const char* count : {"9000000000000000000", "-3"}) {
    const std::string lying =
        test::alteredCopy(hierarchy(), std::string("UPDATE gpkg_ogr_contents SET feature_count = ") + count);
    EXPECT_EQ(lodError(lying), "no error") << count;
  }
}

TEST(StoredHierarchy, NonFiniteAndAbsurdCoordinatesAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const auto& [x, y, z, shown] :
       {std::tuple{nan, 5.2e6, 100.0, "(nan, 5.2e+06, 100)"}, std::tuple{4e5, 5.2e6, inf, "(400000, 5.2e+06, inf)"},
        std::tuple{1e300, 5.2e6, 100.0, "(1e+300, 5.2e+06, 100)"}}) {
    const std::string copy = test::alteredCopy(
        hierarchy(), "UPDATE vertices SET geom = " + test::pointBlobLiteral(x, y, z, 32632) + " WHERE fid = 5");
    EXPECT_EQ(lodError(copy), damage(copy, std::string("vertices row 5 has a point at ") + shown +
                                               ": coordinates must be finite, x and y within 1e12"));
  }
  const std::string none = test::alteredCopy(hierarchy(), "UPDATE vertices SET geom = NULL WHERE fid = 9");
  EXPECT_EQ(readError(none), damage(none, "vertices row 9 has no point"));
}

TEST(StoredHierarchy, GroupsWithoutTheirTrianglesAndBrokenIdsAreRefused) {
  const std::string noAccept = test::alteredCopy(hierarchy(), "DELETE FROM triangles WHERE replaced_by = 5");
  EXPECT_EQ(lodError(noAccept),
            damage(noAccept, "group 5 has no accept triangle (no triangles row has replaced_by 5)"));
  const std::string noReject = test::alteredCopy(hierarchy(), "DELETE FROM triangles WHERE group_id = 5");
  EXPECT_EQ(lodError(noReject), damage(noReject, "group 5 has no reject triangle (no triangles row has group_id 5)"));
  const std::string twice = test::alteredCopy(hierarchy(), "UPDATE groups SET id = 4 WHERE fid = 3");
  EXPECT_EQ(readError(twice), damage(twice, "groups rows 3 and 4 both have id 4"));
  const std::string levelZero = test::alteredCopy(hierarchy(), "UPDATE groups SET level = 0 WHERE fid = 3");
  EXPECT_EQ(readError(levelZero),
            damage(levelZero, "groups row 3 has level 0 but the levels a vertex can be deleted at are 1 to " +
                                  std::to_string(coarsest())));
  const long long vertices = test::sqlInteger(hierarchy(), "SELECT count(*) FROM vertices");
  const std::string droppedVertex = test::alteredCopy(hierarchy(), "DELETE FROM vertices WHERE fid = 7");
  EXPECT_EQ(readError(droppedVertex),
            damage(droppedVertex, "vertices row " + std::to_string(vertices) + " has id " + std::to_string(vertices) +
                                      " but the table's " + std::to_string(vertices - 1) +
                                      " rows should have ids 1 to " + std::to_string(vertices - 1)));
}

TEST(StoredHierarchy, AVertexLevelThatDisagreesWithItsGroupIsRefused) {
  const long long vertex = test::sqlInteger(hierarchy(), "SELECT vertex FROM groups WHERE fid = 1");
  const long long level = test::sqlInteger(hierarchy(), "SELECT level FROM groups WHERE fid = 1");
  const std::string copy =
      test::alteredCopy(hierarchy(), "UPDATE vertices SET level = level + 1 WHERE id = " + std::to_string(vertex));
  EXPECT_EQ(readError(copy), damage(copy, "vertex " + std::to_string(vertex) + " has level " + std::to_string(level) +
                                              " but group 1 deletes it at level " + std::to_string(level) +
                                              ": its last level must be " + std::to_string(level - 1)));
}

TEST(StoredHierarchy, MetadataThatIsNotWhatTinlodWritesIsRefused) {
  const test::SmallHierarchy& s = test::smallHierarchy();
  const std::string band = test::editableCopy(s.gpkg);
  ASSERT_TRUE(test::setTinlodItem(band, "BAND", "first"));
  EXPECT_EQ(test::errorOf([&] { runAccuracyJob(s.dem, band, AccuracyOutputs{}, 0, "", {}); }),
            damage(band, "its TINLOD_BAND is 'first', not a band number; give -b"));
  const std::string method = test::editableCopy(s.gpkg);
  ASSERT_TRUE(test::setTinlodItem(method, "METHOD", "curvature"));
  EXPECT_EQ(readError(method), damage(method, "its TINLOD_METHOD is 'curvature', not a method tinlod knows"));
  const std::string stop = test::editableCopy(s.gpkg);
  ASSERT_TRUE(test::setTinlodItem(stop, "STOP_PCT", "nan"));
  EXPECT_EQ(readError(stop), damage(stop, "its TINLOD_STOP_PCT is 'nan', not a percentage from 0 to less than 100"));
  const std::string threshold = test::editableCopy(s.gpkg);
  ASSERT_TRUE(test::setTinlodItem(threshold, "DELETE_PCT", "none (threshold mode)"));  // as a threshold build writes it
  EXPECT_EQ(readError(threshold), "no error");
}

TEST(StoredHierarchy, ATruncatedFileIsRefusedWithAnError) {
  for (const double share : {0.3, 0.6, 0.9}) {
    const std::string copy = test::editableCopy(hierarchy());
    fs::resize_file(copy, static_cast<std::uintmax_t>(share * double(fs::file_size(copy))));
    const std::string error = lodError(copy);
    EXPECT_NE(error.find("'" + copy + "'"), std::string::npos) << share << ": " << error;
    EXPECT_EQ(error.find("not a tinlod::Error"), std::string::npos) << error;
  }
}

TEST(StoredHierarchy, LocateRefusesLinesAndMultipointsItCannotGiveOneElevation) {
  const std::string dir = test::tempDir();
  const std::string lines = dir + "/lines.gpkg", several = dir + "/several.gpkg", mixed = dir + "/mixed.gpkg",
                    single = dir + "/single.gpkg";
  test::writeWktLayer(lines, {"LINESTRING (400500 5200500, 401000 5201000)"});
  test::writeWktLayer(several, {"MULTIPOINT ((400500 5200500), (401000 5201000))"});
  test::writeWktLayer(
      mixed, {"POINT (400500 5200500)", "POLYGON ((400500 5200500, 401000 5200500, 401000 5201000, 400500 5200500))"});
  test::writeWktLayer(single, {"MULTIPOINT ((400500 5200500))"});
  EXPECT_EQ(locateError(hierarchy(), lines),
            "points: the layer of '" + lines + "' holds Line String features: a point layer is needed");
  EXPECT_EQ(locateError(hierarchy(), several),
            "points: feature 1 of '" + several +
                "' is a multipoint of 2 points, and locate gives each feature one elevation: split it into single "
                "points first (QGIS: Multipart to singleparts)");
  EXPECT_EQ(locateError(hierarchy(), mixed), "points: feature 2 of '" + mixed + "' is a Polygon, not a point");
  EXPECT_EQ(locateError(hierarchy(), single), "no error");
}

TEST(StoredHierarchy, CentresAndPointsToKeepRefuseOtherGeometries) {
  const test::SmallHierarchy& s = test::smallHierarchy();
  const std::string dir = test::tempDir();
  test::writeWktLayer(dir + "/lines.gpkg", {"LINESTRING (400500 5200500, 401000 5201000)"});
  test::writeWktLayer(dir + "/area.gpkg",
                      {"POLYGON ((400500 5200500, 401000 5200500, 401000 5201000, 400500 5200500))"});
  LodJobOptions lod;
  lod.centresPath = dir + "/lines.gpkg";
  lod.lod.dropoff = 100;
  EXPECT_EQ(test::errorOf([&] { runLodJob(s.gpkg, dir + "/lod.gpkg", lod, false, {}); }),
            "-centers: the layer of '" + dir + "/lines.gpkg' holds Line String features: a point layer is needed");
  HierarchyOptions keep;
  keep.fixedPoints = dir + "/area.gpkg";
  EXPECT_EQ(
      test::errorOf([&] { runBuildJob(s.dem, dir + "/h.gpkg", {}, keep, false, {}); }),
      "-fixed (points to keep): the layer of '" + dir + "/area.gpkg' holds Polygon features: a point layer is needed");
  // -check (which tinlod tiles runs before any tile) refuses it too, reading no DEM.
  EXPECT_EQ(
      test::errorOf([&] { checkBuildJob(s.dem, {}, keep, AccuracyOutputs(), {}, {}, {}); }),
      "-fixed (points to keep): the layer of '" + dir + "/area.gpkg' holds Polygon features: a point layer is needed");
  // A multipoint's points are all centres.
  test::writeWktLayer(dir + "/centres.gpkg", {"MULTIPOINT ((400500 5200500), (401000 5201000))"});
  lod.centresPath = dir + "/centres.gpkg";
  EXPECT_EQ(test::errorOf([&] { runLodJob(s.gpkg, dir + "/lod2.gpkg", lod, false, {}); }), "no error");
}

}  // namespace
}  // namespace tinlod
