// SPDX-License-Identifier: GPL-3.0-or-later
// tinlod build end to end in the core: the GeoPackage a hierarchy is written to.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>

#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/build_summary_text.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_borders.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::string smallDem() {
  static const std::string path = [] {
    SyntheticDemOptions o;
    o.width = 150, o.height = 120, o.cellSize = 25;
    const std::string p = test::tempDir() + "/dem.tif";
    writeDemGeoTiff(makeSyntheticDem(o), p);
    return p;
  }();
  return path;
}

long long count(const std::string& gpkg, const std::string& sql) {
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(gpkg.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) return -1;
  long long n = -1;
  if (OGRLayer* r = ds->ExecuteSQL(sql.c_str(), nullptr, nullptr)) {
    OGRFeature* f = r->GetNextFeature();
    if (f) n = f->GetFieldAsInteger64(0);
    OGRFeature::DestroyFeature(f);
    ds->ReleaseResultSet(r);
  }
  GDALClose(ds);
  return n;
}

std::vector<std::string> layerNames(const std::string& gpkg) {
  std::vector<std::string> names;
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(gpkg.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  for (int i = 0; ds && i < ds->GetLayerCount(); ++i) names.push_back(ds->GetLayer(i)->GetName());
  if (ds) GDALClose(ds);
  return names;
}

// tinlod measures on the DEM's grid; near a pole, or across a DEM that wraps the globe, the
// TIN's CRS turns triangles over against it or bends it far from linear: the figures (544 m
// where the TIN in its CRS is 54 m off) held nowhere.
TEST(BuildJob, ACrsThatTurnsTrianglesOverAgainstTheGridIsRefusedAndOneThatBendsItIsWarnedOf) {
  const std::string stere = "+proj=stere +lat_0=90 +lon_0=0 +k=0.965376 +datum=WGS84 +units=m";
  SampleOptions sample;
  sample.targetSrs = stere;
  const std::string cap = test::polarDemFile("cap.tif", -180, 360, 30, 1.0);  // 60 N to the pole, all the way round
  const std::string out = test::tempDir() + "/cap.gpkg";
  const std::string refused = test::errorOf([&] { runBuildJob(cap, out, sample, {}, true, {}); });
  EXPECT_NE(refused.find("turns "), std::string::npos) << refused;
  EXPECT_NE(refused.find(" of its triangles over against the DEM's grid, where tinlod measures them (a DEM that wraps the "
                         "globe, or reaches a pole): warp the DEM to a projected CRS first (gdalwarp -t_srs)"),
            std::string::npos)
      << refused;
  EXPECT_FALSE(fs::exists(out));
  // A quarter of the cap (0-90 E) does not wrap, but its coarsest triangles bend far from linear.
  test::RecordingFeedback fb;
  runBuildJob(test::polarDemFile("quarter.tif", 0, 90, 30, 1.0), out, sample, {}, true, fb.feedback());
  const auto bent = std::find_if(fb.warnings.begin(), fb.warnings.end(), [](const std::string& w) {
    return w.find("triangles part by up to") != std::string::npos;
  });
  ASSERT_NE(bent, fb.warnings.end()) << (fb.warnings.empty() ? "no warning" : fb.warnings[0]);
  EXPECT_NE(bent->find("read in its CRS ('+proj=stere"), std::string::npos) << *bent;
  EXPECT_NE(bent->find("for figures that hold in the CRS, warp the DEM to it first (gdalwarp -t_srs)"), std::string::npos) << *bent;
  // A DEM in degrees at 46-47 N reads alike on its grid and in its UTM zone: no warning.
  test::RecordingFeedback alps;
  const std::string mid = test::tempDir() + "/mid.tif";
  Dem hills = test::makeGeographicDem(240, 240, 7.0, 47.0);
  for (std::size_t i = 0; i < hills.z.size(); ++i) hills.z[i] = float(800 + 400 * std::sin(i % 240 / 9.0) * std::cos(i / 240 / 7.0));
  writeDemGeoTiff(hills, mid);
  runBuildJob(mid, out, {}, {}, true, alps.feedback());
  for (const std::string& w : alps.warnings) EXPECT_EQ(w.find("part by up to"), std::string::npos) << w;
}

TEST(BuildJob, EveryLevelIsALayerWithTheRecordedCounts) {
  const std::string out = test::tempDir() + "/h.gpkg";
  const BuildSummary s = runBuildJob(smallDem(), out, {}, {}, false, {});
  const HierarchyInfo info = readHierarchyInfo(out);
  EXPECT_EQ(info.kind, "hierarchy");
  ASSERT_EQ(info.levels.size(), std::size_t(s.levels) + 1);
  for (const LevelStats& l : info.levels) {
    const std::string L = std::to_string(l.level);
    EXPECT_EQ(count(out, "SELECT COUNT(*) FROM level_" + L), (long long)l.triangles) << "level " << L;
    EXPECT_EQ(count(out, "SELECT COUNT(*) FROM vertices WHERE level >= " + L), (long long)l.vertices) << "level " << L;
  }
  // Each distinct triangle is stored once; groups link accept and reject triangles.
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM groups"), count(out, "SELECT SUM(deleted) FROM levels"));
  // Two accept triangles more than reject ones for an inner vertex, one for an outline vertex.
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM groups g WHERE (SELECT COUNT(*) FROM triangles t WHERE t.replaced_by = g.id) "
                       "- (SELECT COUNT(*) FROM triangles t WHERE t.group_id = g.id) NOT IN (1, 2)"), 0);
  EXPECT_GT(count(out, "SELECT COUNT(*) FROM groups g WHERE (SELECT COUNT(*) FROM triangles t WHERE t.replaced_by = g.id) "
                       "= (SELECT COUNT(*) FROM triangles t WHERE t.group_id = g.id) + 1"), 0);
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM levels WHERE rmse IS NULL OR cells IS NULL OR outline_vertices IS NULL"), 0);
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM triangles WHERE group_id IS NULL"), (long long)info.levels[0].triangles);
  EXPECT_EQ(info.metadata.at("method"), "volume");
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM levels WHERE method = 'volume' AND delete_pct = 20 AND stop_pct = 5"),
            (long long)info.levels.size());
  EXPECT_EQ(s.coarsestVertices, info.levels.back().vertices);
}

TEST(BuildJob, ReplacingAHierarchyDropsItsOldLevelsAndKeepsOtherLayers) {
  const std::string out = test::tempDir() + "/h.gpkg";
  runBuildJob(smallDem(), out, {}, {}, false, {});
  {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(out.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr));
    ds->CreateLayer("notes", nullptr, wkbNone, nullptr);
    GDALClose(ds);
  }
  HierarchyOptions two;
  two.maxLevels = 2;
  runBuildJob(smallDem(), out, {}, two, true, {});
  const std::vector<std::string> names = layerNames(out);
  EXPECT_NE(std::find(names.begin(), names.end(), "notes"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "level_2"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "level_3"), names.end());
  EXPECT_EQ(readHierarchyInfo(out).levels.size(), 3u);
}

TEST(BuildJob, RunningAgainOntoItsOwnOutputReplacesIt) {
  const std::string out = test::tempDir() + "/h.gpkg";
  runBuildJob(smallDem(), out, {}, {}, false, {});
  const auto firstSize = fs::file_size(out);
  HierarchyOptions other;
  other.measure = Measure::Error;
  other.maxLevels = 3;
  runBuildJob(smallDem(), out, {}, other, true, {});
  EXPECT_EQ(readHierarchyInfo(out).metadata.at("method"), "error");
  EXPECT_EQ(readHierarchyInfo(out).levels.size(), 4u);
  EXPECT_LT(fs::file_size(out), firstSize);  // compacted: no pages of the old levels left
  runBuildJob(smallDem(), out, {}, {}, true, {});  // and once more, as QGIS's Run again does
  EXPECT_EQ(readHierarchyInfo(out).metadata.at("method"), "volume");
}

TEST(BuildJob, SamplingOverAHierarchyDropsItsLevels) {
  const std::string out = test::tempDir() + "/h.gpkg";
  runBuildJob(smallDem(), out, {}, {}, false, {});
  runSampleJob(smallDem(), out, {}, true, {});
  const std::vector<std::string> names = layerNames(out);
  EXPECT_EQ(names, (std::vector<std::string>{"vertices", "triangles"}));
  const HierarchyInfo info = readHierarchyInfo(out);
  EXPECT_EQ(info.kind, "tin");
  EXPECT_EQ(info.metadata.count("method"), 0u);
}

TEST(BuildJob, PeaksPitsAndPointsToKeepAreFixed) {
  const std::string dir = test::tempDir();
  // Two points to keep, in longitude/latitude: transformed to the TIN's UTM zone.
  std::ofstream(dir + "/keep.geojson")
      << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:OGC:1.3:CRS84"}},)"
      << R"("features":[{"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[7.7303,46.9643]}},)"
      << R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[0,0]}}]})";
  HierarchyOptions o;
  o.fixPeaksPits = true;
  o.fixedPoints = dir + "/keep.geojson";
  test::RecordingFeedback fb;
  const std::string out = dir + "/h.gpkg";
  const BuildSummary s = runBuildJob(smallDem(), out, {}, o, false, fb.feedback());
  // Where the point may be: an analyst sees data under a point beside the raster's edge.
  EXPECT_TRUE(fb.warned("1 of the 2 points to keep fall outside the TIN and were ignored: over nodata, or between the "
                        "raster's edge and its outermost cell centres, where the TIN's outline runs"));
  const long long top = s.levels;
  EXPECT_EQ(count(out, "SELECT COUNT(*) FROM vertices WHERE fixed = 1 AND level < " + std::to_string(top)), 0);
  EXPECT_GT(count(out, "SELECT COUNT(*) FROM vertices WHERE fixed = 1 AND outline = 0"), 10);
  // Every peak and pit of the DEM is sampled, and so at the top level; not only those the
  // blocks' random cells hit (60 of the 170 here).
  const Dem dem = readDem(smallDem(), 1, ProgressRange(Feedback{}, 0, 1));
  std::set<std::pair<int, int>> peaks, atTop;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c)
      if (strictPeakOrPit(dem, r, c)) peaks.insert({r, c});
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_VECTOR));
  for (auto& f : *ds->GetLayerByName("vertices"))
    if (f->GetFieldAsInteger("level") == top) atTop.insert({f->GetFieldAsInteger("row"), f->GetFieldAsInteger("col")});
  EXPECT_EQ(peaks.size(), 170u);
  for (const auto& [r, c] : peaks) EXPECT_EQ(atTop.count({r, c}), 1u) << "peak or pit at row " << r << ", col " << c;
}

// Every vertex of a tile's file: where it is, whether it is fixed, the highest level it is in.
struct StoredVertex {
  double x, y;
  bool fixed;
  int level;
};
std::vector<StoredVertex> verticesOf(const std::string& gpkg) {
  std::vector<StoredVertex> out;
  GDALDatasetUniquePtr ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR));
  if (!ds) return out;
  for (auto& f : *ds->GetLayerByName("vertices")) {
    const OGRPoint* p = f->GetGeometryRef()->toPoint();
    out.push_back({p->getX(), p->getY(), f->GetFieldAsInteger("fixed") == 1, f->GetFieldAsInteger("level")});
  }
  return out;
}

// The vertices of the column line at lineX, level by level, are the same in both tiles,
// and there are some at every level.
void expectTheSameLine(const std::vector<std::vector<StoredVertex>>& tiles, double lineX, int top) {
  for (int level = 0; level <= top; ++level) {
    std::vector<std::multiset<double>> onLine(2);
    for (int t = 0; t < 2; ++t)
      for (const StoredVertex& v : tiles[t])
        if (std::fabs(v.x - lineX) < 1e-6 && v.level >= level) onLine[t].insert(v.y);
    EXPECT_FALSE(onLine[0].empty()) << level;
    EXPECT_EQ(onLine[0], onLine[1]) << "level " << level;
  }
}

// In tiles, a point to keep holds its nearest vertex off the tile's shared lines: one on a
// line goes or stays by the border rule alone, alike in both tiles, which the points do
// not change. Points right beside a line, nearest to its vertices, still keep a vertex
// within a block of them up to the top level, and the two tiles' lines stay the same.
TEST(BuildJob, TilesHoldPointsToKeepOffTheirSharedLines) {
  const std::string dir = test::tempDir();
  GDALDatasetUniquePtr dem(GDALDataset::Open(smallDem().c_str(), GDAL_OF_RASTER));
  double gt[6];
  ASSERT_EQ(dem->GetGeoTransform(gt), CE_None);
  const int size = 60;  // tiles (0,0) and (1,0) share the column of cells 60
  const double lineX = gt[0] + 60.5 * gt[1];
  std::vector<std::array<double, 2>> points;
  std::ofstream keep(dir + "/keep.geojson");
  keep << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32632"}},"features":[)";
  for (int row = 4; row < 58; row += 6) {
    points.push_back({lineX - 0.2 * gt[1], gt[3] + (row + 0.5) * gt[5]});
    keep << (row > 4 ? "," : "") << R"({"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[)"
         << std::setprecision(12) << points.back()[0] << "," << points.back()[1] << "]}}";
  }
  keep << "]}";
  keep.close();
  HierarchyOptions o;
  o.fixedPoints = dir + "/keep.geojson";
  std::vector<std::vector<StoredVertex>> tiles;
  for (int col : {0, 1}) {
    test::RecordingFeedback fb;
    const std::string out = dir + "/tile_" + std::to_string(col) + ".gpkg";
    runBuildJob(smallDem(), out, {}, o, false, fb.feedback(), AccuracyOutputs(), HierarchyLayers(), TileSpec{size, col, 0});
    EXPECT_FALSE(fb.warned("points to keep")) << "tile " << col;  // the other tile's points are not off the data
    tiles.push_back(verticesOf(out));
  }
  int top = 0;
  for (const StoredVertex& v : tiles[0]) top = std::max(top, v.level);
  ASSERT_GE(top, 10);
  for (const auto& p : points) {
    double nearest = INFINITY;
    for (const StoredVertex& v : tiles[0])
      if (v.fixed && v.level == top && v.x < lineX) nearest = std::min(nearest, std::hypot(v.x - p[0], v.y - p[1]));
    EXPECT_LT(nearest, 3 * std::fabs(gt[1]) * std::sqrt(2.0)) << "point at " << p[0] << ", " << p[1];
  }
  expectTheSameLine(tiles, lineX, top);
}

// With -fix_peaks_pits, a peak or pit on a shared line stays in both tiles at every level:
// its 3 x 3 cells cross the line, and each tile reads those beyond its window alike.
TEST(BuildJob, TilesKeepPeaksAndPitsOnTheirSharedLines) {
  const std::string dir = test::tempDir();
  const int line = 60;  // tiles (0,0) and (1,0) share the column of cells 60
  // A ridge along the line that rises and falls every few cells: peaks and pits on it.
  const std::string path = dir + "/ridge.tif";
  writeDemGeoTiff(test::makeDem(121, 61, 25, [&](int r, int c) {
    return float(100 + 20 * std::sin(1.1 * r) * std::cos(0.9 * (c - line)) + 0.05 * c);
  }), path);
  const Dem whole = readDem(path, 1, ProgressRange(Feedback{}, 0, 1));
  const double lineX = whole.geotransform[0] + (line + 0.5) * whole.geotransform[1];
  HierarchyOptions o;
  o.fixPeaksPits = true;
  std::vector<std::vector<StoredVertex>> tiles;
  for (int col : {0, 1}) {
    const std::string out = dir + "/peaks_" + std::to_string(col) + ".gpkg";
    runBuildJob(path, out, {}, o, false, {}, AccuracyOutputs(), HierarchyLayers(), TileSpec{line, col, 0});
    tiles.push_back(verticesOf(out));
  }
  int top = 0;
  for (const StoredVertex& v : tiles[0]) top = std::max(top, v.level);
  ASSERT_GE(top, 10);
  for (int t = 0; t < 2; ++t) {
    int peaksAndPits = 0, gone = 0;
    for (const StoredVertex& v : tiles[t]) {
      if (std::fabs(v.x - lineX) > 1e-6) continue;
      const int row = static_cast<int>(std::floor((v.y - whole.geotransform[3]) / whole.geotransform[5]));
      if (strictPeakOrPit(whole, row, line)) {
        ++peaksAndPits;
        EXPECT_TRUE(v.fixed) << "tile " << t << ", row " << row;
        EXPECT_EQ(v.level, top) << "tile " << t << ", row " << row;
      } else {
        gone += v.level < top;
      }
    }
    EXPECT_GE(peaksAndPits, 3) << "tile " << t;
    EXPECT_GT(gone, 3) << "tile " << t;  // the line still thins elsewhere
  }
  expectTheSameLine(tiles, lineX, top);
}

// A coarsest level whose outline reaches valid cells level 0 missed (beside nodata) gives up
// a negative count: said as cells more than level 0 covers, not as "-7 valid cells given up".
TEST(BuildJob, SummaryTextSaysCellsGainedAndLevelZerosCover) {
  BuildSummary s;
  s.cellsGivenUp = 12;
  EXPECT_EQ(coarsestCellsText(s), "12 valid cells given up by its outline");
  s.cellsGivenUp = -7;
  EXPECT_EQ(coarsestCellsText(s), "7 valid cells more than level 0 covers");
  s.validCells = 1610, s.levelZeroCells = 1610;
  EXPECT_EQ(levelZeroCoverText(s), "");
  s.levelZeroCells = 1600;
  EXPECT_EQ(levelZeroCoverText(s).rfind("Level 0 covers 1600 of the DEM's 1610 valid cells: ", 0), 0u) << levelZeroCoverText(s);
}

TEST(BuildJob, BadOptionsFailBeforeAnyWork) {
  int calls = 0;
  Feedback counting;
  counting.progress = [&calls](double, const std::string&) { return ++calls > 0; };
  HierarchyOptions bad;
  bad.deletePct = 150;
  EXPECT_THROW(runBuildJob(smallDem(), test::tempDir() + "/h.gpkg", {}, bad, false, counting), Error);
  EXPECT_EQ(calls, 0);
  HierarchyOptions missing;
  missing.fixedPoints = test::tempDir() + "/none.shp";
  EXPECT_THROW(runBuildJob(smallDem(), test::tempDir() + "/h.gpkg", {}, missing, false, {}), Error);
  // A tile makes every level its delete and stop percentages imply; a hierarchy holds at
  // most kMaxLevel + 1 of them (about 34,800 here).
  HierarchyOptions tooMany;
  tooMany.deletePct = 1, tooMany.stopPct = 1e-150;
  try {
    runBuildJob(smallDem(), test::tempDir() + "/h.gpkg", {}, tooMany, false, counting, AccuracyOutputs(),
                HierarchyLayers(), TileSpec{60, 0, 0});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-max_levels"), std::string::npos) << e.what();
  }
  for (const double deletePct : {1e-8, 1e-15}) {  // under 1 %: refused, as it would make more levels than an int holds
    tooMany.deletePct = deletePct;
    EXPECT_THROW(runBuildJob(smallDem(), test::tempDir() + "/h.gpkg", {}, tooMany, false, counting, AccuracyOutputs(),
                             HierarchyLayers(), TileSpec{60, 0, 0}),
                 Error)
        << deletePct;
  }
  EXPECT_EQ(calls, 0);
}

TEST(BuildJob, CancelLeavesNothingBehind) {
  for (const double stopAt : {0.1, 0.4, 0.8, 0.95}) {
    const std::string dir = test::tempDir();
    Feedback cancelling;
    cancelling.progress = [stopAt](double f, const std::string&) { return f < stopAt; };
    EXPECT_THROW(runBuildJob(smallDem(), dir + "/h.gpkg", {}, {}, false, cancelling), Cancelled);
    EXPECT_TRUE(fs::is_empty(dir)) << stopAt;
  }
}

TEST(BuildJob, CancelWhileImportancesAreRecomputedOnEveryCoreStopsThemAll) {
  const std::string dir = test::tempDir();
  Feedback cancelling;
  cancelling.progress = [](double, const std::string& phase) { return phase != "Selecting level 2"; };
  EXPECT_THROW(runBuildJob(smallDem(), dir + "/h.gpkg", {}, {}, false, cancelling), Cancelled);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(BuildJob, OptionsThatWouldDoNothingAreRefused) {
  const std::string dir = test::tempDir();
  std::ofstream(dir + "/polygon.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":)"
      << R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}]})";
  HierarchyOptions polygon;
  polygon.fixedPoints = dir + "/polygon.geojson";
  EXPECT_THROW(runBuildJob(smallDem(), dir + "/a.gpkg", {}, polygon, false, {}), Error);
  HierarchyOptions zero;
  zero.thresholdMode = true;
  zero.threshold = 0;
  EXPECT_THROW(zero.validate(), Error);
  EXPECT_TRUE(fs::is_empty(dir) || !fs::exists(dir + "/a.gpkg"));
}

TEST(BuildJob, ADegreeLimitIsRefusedWithAnotherMethod) {
  HierarchyOptions o;
  o.measure = Measure::Volume;
  o.maxDegree = 8;
  try {
    o.validate();
    FAIL() << "-max_degree 8 with -method volume was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "-max_degree applies only to -method degree (got -max_degree 8 with -method volume)");
  }
  o.measure = Measure::Degree;
  EXPECT_NO_THROW(o.validate());
}

TEST(BuildJob, TheValidRangeIsRecordedAndRefusedWhenEmpty) {
  const std::string dir = test::tempDir();
  SampleOptions sample;
  sample.validHeights = {-100, 5000};
  runBuildJob(smallDem(), dir + "/h.gpkg", sample, {}, false, {});
  EXPECT_EQ(readHierarchyInfo(dir + "/h.gpkg").metadata.at("valid_range"), "-100..5000 m");
  sample.validHeights = {10, -10};
  EXPECT_THROW(runBuildJob(smallDem(), dir + "/bad.gpkg", sample, {}, false, {}), Error);
  EXPECT_FALSE(fs::exists(dir + "/bad.gpkg"));
}

TEST(BuildJob, StoppingAboveTheTargetForFixedVerticesIsSaidAndNoTinyLevelsAreMade) {
  test::RecordingFeedback fb;
  const std::string out = test::tempDir() + "/h.gpkg";
  HierarchyOptions keep;
  keep.keepOutline = true;  // a small DEM: its outline alone is over 5 %
  runBuildJob(smallDem(), out, {}, keep, false, fb.feedback());
  EXPECT_TRUE(fb.warned("are fixed")) << (fb.warnings.empty() ? "" : fb.warnings[0]);
  EXPECT_TRUE(fb.warned("-keep_outline")) << (fb.warnings.empty() ? "" : fb.warnings[0]);
  // Its outline vertices are fixed: not said to go while the outline moves little.
  EXPECT_FALSE(fb.warned("-outline_tolerance")) << (fb.warnings.empty() ? "" : fb.warnings[0]);
  // The threshold mode, stopped above the target, says so too.
  test::RecordingFeedback thresholded;
  HierarchyOptions threshold;
  threshold.thresholdMode = true;
  threshold.threshold = 1e5;
  runBuildJob(smallDem(), test::tempDir() + "/t.gpkg", {}, threshold, false, thresholded.feedback());
  EXPECT_TRUE(thresholded.warned("is not below -threshold")) << (thresholded.warnings.empty() ? "" : thresholded.warnings[0]);
  // The error method stopped by its bound says so too.
  test::RecordingFeedback bounded;
  HierarchyOptions error;
  error.measure = Measure::Error;
  error.maxError = 1;
  runBuildJob(smallDem(), test::tempDir() + "/e.gpkg", {}, error, false, bounded.feedback());
  EXPECT_TRUE(bounded.warned("-max_error 1 m")) << (bounded.warnings.empty() ? "" : bounded.warnings[0]);
  // Its sample is already further than 1 m from the DEM: said, with the way to a finer one.
  const auto said = [](const test::RecordingFeedback& fb, const std::string& text) {
    return std::any_of(fb.infos.begin(), fb.infos.end(), [&](const std::string& i) { return i.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(said(bounded, "level 0, the sample of one cell per 3 x 3 block, is already up to ")) << bounded.infos.size();
  EXPECT_TRUE(said(bounded, " m from the DEM, more than -max_error 1 m: there the bound is level 0's own distance; -block 1 "
                            "samples every cell"));
  EXPECT_FALSE(said(thresholded, "more than -max_error"));
  const HierarchyInfo info = readHierarchyInfo(out);
  for (std::size_t L = 1; L < info.levels.size(); ++L)
    EXPECT_GE(info.levels[L].deleted * 100, info.levels[L - 1].vertices) << "level " << L;
}

TEST(BuildJob, InfoRefusesFilesTinlodDidNotWrite) {
  EXPECT_THROW(readHierarchyInfo(smallDem()), Error);
  const std::string out = test::tempDir() + "/plain.gpkg";
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(out.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  ds->CreateLayer("triangles", nullptr, wkbPolygon, nullptr);
  GDALClose(ds);
  EXPECT_THROW(readHierarchyInfo(out), Error);
}

}  // namespace
}  // namespace tinlod

namespace tinlod {
namespace {

// -check: what a build would refuse before its long work, with the build's own message
// (Cli.BuildCheck... runs it as a command: nothing written); tinlod tiles runs it once for a
// job instead of failing every tile.
TEST(BuildJob, CheckRefusesWhatTheBuildWouldAndWritesNothing) {
  const auto check = [](const SampleOptions& sample, const HierarchyOptions& options, const TileSpec& tile) {
    return test::errorOf([&] { checkBuildJob(smallDem(), sample, options, AccuracyOutputs(), {}, tile, {}); });
  };
  EXPECT_EQ(check({}, {}, {}), "no error");
  EXPECT_EQ(check({}, {}, {120, 1, 0}), "no error");  // 150 x 120 cells: 2 x 1 tiles
  HierarchyOptions badPct;
  badPct.deletePct = 200;
  EXPECT_TRUE(test::contains(check({}, badPct, {}), "delete_pct must be from 1 to 100 (got 200)"));
  badPct.deletePct = 0.5;  // no level can be made: the run ended with level 0 alone, blaming fixed vertices
  EXPECT_TRUE(test::contains(check({}, badPct, {}), "delete_pct must be from 1 to 100 (got 0.5): a whole run makes no level that deletes under 1 %"));
  EXPECT_TRUE(test::contains(check({}, {}, {120, 9, 0}), "-tile 9,0 is outside the grid"));
  EXPECT_TRUE(test::contains(check({}, {}, {100, 0, 0}), "-tile_size 100 must be a multiple of -block"));
  SampleOptions farJitter;
  farJitter.jitter = 500;  // the DEM's cells are 25 m
  EXPECT_TRUE(test::contains(check(farJitter, {}, {}), "jitter 500 m is not smaller than the cell size"));
  SampleOptions unknownCrs;
  unknownCrs.targetSrs = "EPSG:999999";
  EXPECT_TRUE(test::contains(check(unknownCrs, {}, {}), "target CRS"));
  HierarchyOptions missingFile;
  missingFile.fixedPoints = test::tempDir() + "/no_such_points.gpkg";
  EXPECT_TRUE(test::contains(check({}, missingFile, {}), "does not exist"));
  HierarchyOptions listWithoutTile;
  listWithoutTile.lineOutline = test::tempDir() + "/outline.txt";
  EXPECT_TRUE(test::contains(check({}, listWithoutTile, {}), "-line_outline is for a tile of a job"));
  HierarchyLayers beyond;
  beyond.levelViews = {0, 99};  // a tile makes exactly 14 levels by default: level 99 would be in none
  EXPECT_EQ(test::errorOf([&] { checkBuildJob(smallDem(), {}, {}, AccuracyOutputs(), beyond, {120, 0, 0}, {}); }),
            "-levels 0,99: every tile makes levels 0 to 14 (-max_levels, or -delete_pct and -stop_pct): give levels up "
            "to 14, or last");
  beyond.levelViews = {0, 14, HierarchyLayers::kCoarsest};
  EXPECT_EQ(test::errorOf([&] { checkBuildJob(smallDem(), {}, {}, AccuracyOutputs(), beyond, {120, 0, 0}, {}); }),
            "no error");
}

}  // namespace
}  // namespace tinlod
