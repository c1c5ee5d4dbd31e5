// SPDX-License-Identifier: GPL-3.0-or-later
// The accuracy outputs of `tinlod build` and `tinlod accuracy`: raster, report, errors.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "test_support.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/build_job.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::string smallDem() { return test::smallSyntheticDemFile(); }

struct Built {
  std::string dir = test::tempDir();
  std::string gpkg = dir + "/h.gpkg";
  BuildSummary summary;
};

// One build with a raster and a CSV report, shared by the tests that read them.
const Built& built() {
  static const Built b = [] {
    Built out;
    AccuracyOutputs a;
    a.rasterPath = out.dir + "/acc.tif";
    a.reportPath = out.dir + "/acc.csv";
    out.summary = runBuildJob(smallDem(), out.gpkg, {}, {}, false, {}, a);
    return out;
  }();
  return b;
}

std::size_t lineCount(const std::string& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(AccuracyJob, BuildMeasuresEveryLevelAndLevelZeroIsExact) {
  const Built& b = built();
  ASSERT_EQ(b.summary.accuracy.size(), static_cast<std::size_t>(b.summary.levels) + 1);
  EXPECT_EQ(b.summary.accuracy.front().rmse, 0);
  const LevelAccuracy& top = b.summary.accuracy.back();
  EXPECT_GT(top.rmse, 0);
  EXPECT_LE(top.maxAbsError, top.certifiedError + 1e-6);  // test points lie on level 0, whose error is certified
  EXPECT_EQ(lineCount(b.dir + "/acc.csv"), b.summary.accuracy.size() + 1);
}

TEST(AccuracyJob, TheRasterIsOnTheDemsGridWithNamedBandsNodataAndStatistics) {
  const Built& b = built();
  GDALAllRegister();
  std::unique_ptr<GDALDataset> dem(GDALDataset::Open(smallDem().c_str(), GDAL_OF_RASTER));
  std::unique_ptr<GDALDataset> acc(GDALDataset::Open((b.dir + "/acc.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(acc);
  EXPECT_EQ(acc->GetRasterXSize(), dem->GetRasterXSize());
  EXPECT_EQ(acc->GetRasterYSize(), dem->GetRasterYSize());
  ASSERT_EQ(acc->GetRasterCount(), 4);
  double g1[6], g2[6];
  dem->GetGeoTransform(g1);
  acc->GetGeoTransform(g2);
  for (int i = 0; i < 6; ++i) EXPECT_DOUBLE_EQ(g1[i], g2[i]);
  EXPECT_TRUE(acc->GetSpatialRef()->IsSame(dem->GetSpatialRef()));
  for (int k = 1; k <= 4; ++k) {
    GDALRasterBand* band = acc->GetRasterBand(k);
    int has = 0;
    EXPECT_EQ(band->GetNoDataValue(&has), kAccuracyNodata);
    EXPECT_TRUE(has);
    EXPECT_NE(std::string(band->GetDescription()), "");
    EXPECT_NE(band->GetMetadataItem("STATISTICS_MEAN"), nullptr) << "band " << k;
  }
  EXPECT_NE(std::string(acc->GetRasterBand(1)->GetDescription()).find("elevation difference"), std::string::npos);
}

TEST(AccuracyJob, TheAccuracyCommandReadsTheHierarchyBackAndAgreesWithTheBuild) {
  const Built& b = built();
  AccuracyOutputs a;
  a.reportPath = b.dir + "/again.json";
  const AccuracyReport r = runAccuracyJob(smallDem(), b.gpkg, a, 0, "", {});
  ASSERT_EQ(r.rows.size(), b.summary.accuracy.size());
  for (std::size_t L = 0; L < r.rows.size(); ++L) {
    EXPECT_EQ(r.rows[L].vertices, b.summary.accuracy[L].vertices);
    EXPECT_NEAR(r.rows[L].rmse, b.summary.accuracy[L].rmse, 1e-9) << "level " << L;
  }
  EXPECT_TRUE(fs::exists(a.reportPath));
}

TEST(AccuracyJob, HierarchyReaderRestoresEveryLevelsTriangleCount) {
  const Built& b = built();
  const StoredHierarchy s = readHierarchy(b.gpkg, ProgressRange(Feedback{}, 0, 1));
  ASSERT_EQ(s.hierarchy.levels.size(), b.summary.accuracy.size());
  for (const LevelStats& l : s.hierarchy.levels)
    EXPECT_EQ(s.hierarchy.levelTriangles(l.level).size(), l.triangles) << "level " << l.level;
}

TEST(AccuracyJob, HierarchyReaderRestoresTheGroupsAndTheirLinks) {
  const Built& b = built();
  const Hierarchy& h = readHierarchy(b.gpkg, ProgressRange(Feedback{}, 0, 1)).hierarchy;
  const Dem dem = readDem(smallDem(), 1, ProgressRange(Feedback{}, 0, 1));
  const Tin tin = sampleTin(dem, SampleOptions{}, ProgressRange(Feedback{}, 0, 1));
  Hierarchy built = buildHierarchy(tin, dem, {}, HierarchyOptions{}, ProgressRange(Feedback{}, 0, 1));
  linkGroups(built);
  ASSERT_EQ(h.groups.size(), built.groups.size());
  ASSERT_EQ(h.triangles.size(), built.triangles.size());
  // Both are linked by linkGroups, each range in triangle order.
  auto ids = [](std::pair<const std::uint32_t*, const std::uint32_t*> r) {
    return std::vector<std::uint32_t>(r.first, r.second);
  };
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    EXPECT_EQ(h.groups[g].vertex, built.groups[g].vertex);
    EXPECT_EQ(h.groups[g].level, built.groups[g].level);
    EXPECT_DOUBLE_EQ(h.groups[g].error, built.groups[g].error);
    EXPECT_EQ(ids(h.accept(h.groups[g])), ids(built.accept(built.groups[g]))) << "group " << g;
    EXPECT_EQ(ids(h.reject(h.groups[g])), ids(built.reject(built.groups[g]))) << "group " << g;
  }
  for (std::size_t t = 0; t < h.triangles.size(); ++t) {
    EXPECT_EQ(h.triangles[t].group, built.triangles[t].group);
    EXPECT_EQ(h.triangles[t].replacedBy, built.triangles[t].replacedBy);
  }
}

TEST(AccuracyJob, BadOutputsFailBeforeAnyWorkAndNameTheOption) {
  AccuracyOutputs a;
  a.reportPath = test::tempDir() + "/r.txt";
  try {
    runBuildJob(smallDem(), test::tempDir() + "/h.gpkg", {}, {}, false, {}, a);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-report"), std::string::npos) << e.what();
  }
  AccuracyOutputs f;
  f.rasterPath = test::tempDir() + "/a.xyz";
  f.raster.format = "NoSuchFormat";
  EXPECT_THROW(f.validate(), Error);
  AccuracyOutputs level;
  level.reportPath = test::tempDir() + "/r.csv";
  level.rasterPath = test::tempDir() + "/r.tif";
  level.rasterLevel = 99;
  EXPECT_THROW(runAccuracyJob(smallDem(), built().gpkg, level, 0, "", {}), Error);
  EXPECT_FALSE(fs::exists(level.reportPath));
}

TEST(AccuracyJob, AnotherDemThanTheTinsIsRefused) {
  const Dem far = test::makeDem(50, 40, 25, [](int, int) { return 1.0f; });  // elsewhere in UTM 32N
  const std::string path = test::tempDir() + "/far.tif";
  writeDemGeoTiff(far, path);
  AccuracyOutputs a;
  a.reportPath = test::tempDir() + "/r.csv";
  EXPECT_THROW(runAccuracyJob(path, built().gpkg, a, 0, "", {}), Error);
}

TEST(AccuracyJob, ADemWithoutCrsIsReadWithTheSourceSrsTheBuildWasGiven) {
  Dem dem = test::makeGeographicDem(60, 50, 7.0, 46.0);
  dem.crsWkt.clear();
  const std::string path = test::tempDir() + "/degrees_without_crs.tif", gpkg = test::tempDir() + "/degrees.gpkg";
  writeDemGeoTiff(dem, path);
  SampleOptions sample;
  sample.sourceSrs = "EPSG:4326";
  runBuildJob(path, gpkg, sample, {}, true, {}, AccuracyOutputs());
  AccuracyOutputs a;
  a.reportPath = test::tempDir() + "/degrees.csv";
  a.rasterPath = test::tempDir() + "/degrees_accuracy.tif";
  a.overwrite = true;
  const AccuracyReport r = runAccuracyJob(path, gpkg, a, 0, "", {});
  ASSERT_FALSE(r.rows.empty());
  EXPECT_GT(r.rows.size(), 2u);
  EXPECT_TRUE(std::isfinite(r.rows.back().rmse)) << "every level measured at the DEM's test points";
  // The raster and the report are in the CRS the DEM was read in, not in none as its file.
  EXPECT_EQ(r.crsName, "WGS 84");
  {
    GDALDatasetUniquePtr raster(GDALDataset::Open(a.rasterPath.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(raster);
    ASSERT_NE(raster->GetSpatialRef(), nullptr) << "the accuracy raster has no CRS";
    EXPECT_STREQ(raster->GetSpatialRef()->GetAuthorityCode(nullptr), "4326");
  }
  a.rasterPath.clear();

  // Another DEM with a CRS of its own keeps it: the same heights on the TIN's UTM grid would
  // lie nowhere near the TIN read as degrees.
  const CrsTransform toUtm = CrsTransform::forDem(dem, "EPSG:4326", "EPSG:32632", ProgressRange(Feedback{}, 0, 1));
  std::vector<double> x{dem.centreX(0)}, y{dem.centreY(0)};
  toUtm.apply(x, y);
  Dem metric = test::makeDem(40, 40, 50, [](int r, int c) { return float(100 + r + 2 * c); });
  metric.geotransform = {std::floor(x[0]), 50.0, 0.0, std::ceil(y[0]), 0.0, -50.0};
  const std::string utm = test::tempDir() + "/utm_dem.tif";
  writeDemGeoTiff(metric, utm);
  a.reportPath = test::tempDir() + "/utm.csv";
  EXPECT_EQ(test::errorOf([&] { runAccuracyJob(utm, gpkg, a, 0, "", {}); }), "no error");

  // Another -s_srs than the build's is warned of before the test points are found off the TIN.
  test::RecordingFeedback fb;
  EXPECT_THROW(runAccuracyJob(path, gpkg, a, 0, "EPSG:32612", fb.feedback()), Error);
  EXPECT_TRUE(fb.warned("-s_srs EPSG:32612 is not the EPSG:4326 '" + gpkg + "' was built with")) << "no such warning";
}

// A DEM in degrees is sampled in its UTM zone: the accuracy reads each vertex back onto the
// DEM's grid, where those on the raster's edge came back a rounding outside it and the
// cells on the edge outside every triangle (112 of zion_srtm3's 212,505 cells in a trial).
TEST(AccuracyJob, ADemInDegreesIsMeasuredAtEveryCellTheLevelsTableCounts) {
  Dem dem = test::makeGeographicDem(150, 120, 7.0123, 46.0456);
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c)
      dem.z[std::size_t(r) * dem.width + c] = float(500 + 40 * std::sin(c / 9.0) * std::cos(r / 7.0) + 0.3 * c);
  const std::string path = test::tempDir() + "/degrees_edges.tif", gpkg = test::tempDir() + "/degrees_edges.gpkg";
  writeDemGeoTiff(dem, path);
  runBuildJob(path, gpkg, {}, {}, true, {});
  const StoredHierarchy stored = readHierarchy(gpkg, ProgressRange(Feedback{}, 0, 1));
  AccuracyOutputs a;
  a.options.reference = Reference::Dem;
  a.reportPath = test::tempDir() + "/degrees_edges.csv";
  a.overwrite = true;
  const AccuracyReport r = runAccuracyJob(path, gpkg, a, 0, "", {});
  ASSERT_EQ(r.rows.size(), stored.hierarchy.levels.size());
  EXPECT_EQ(stored.hierarchy.levels.front().cells, 150 * 120) << "level 0 covers every cell, the edges' included";
  for (std::size_t L = 0; L < r.rows.size(); ++L) {
    EXPECT_EQ(r.rows[L].testPoints, std::size_t(stored.hierarchy.levels[L].cells)) << "level " << L;
    EXPECT_NEAR(r.rows[L].rmse, stored.hierarchy.levels[L].rmse, 1e-6) << "level " << L;
    EXPECT_NEAR(r.rows[L].maxAbsError, stored.hierarchy.levels[L].maxError, 1e-6) << "level " << L;
  }
}

TEST(AccuracyJob, RealDemsInDegreesAreMeasuredAtEveryCellTheLevelsTableCounts) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  for (const std::string name : {"zion_srtm3.tif", "mandakini_90m.tif"}) {  // the second with nodata holes
    const std::string gpkg = test::tempDir() + "/" + name + ".gpkg";
    runBuildJob(data + "/" + name, gpkg, {}, {}, true, {});
    const StoredHierarchy stored = readHierarchy(gpkg, ProgressRange(Feedback{}, 0, 1));
    AccuracyOutputs a;
    a.options.reference = Reference::Dem;
    a.reportPath = test::tempDir() + "/" + name + ".csv";
    a.overwrite = true;
    const AccuracyReport r = runAccuracyJob(data + "/" + name, gpkg, a, 0, "", {});
    ASSERT_EQ(r.rows.size(), stored.hierarchy.levels.size()) << name;
    for (std::size_t L = 0; L < r.rows.size(); ++L) {
      EXPECT_EQ(r.rows[L].testPoints, std::size_t(stored.hierarchy.levels[L].cells)) << name << " level " << L;
      EXPECT_NEAR(r.rows[L].rmse, stored.hierarchy.levels[L].rmse, 1e-6) << name << " level " << L;
    }
  }
}

TEST(AccuracyJob, TooFewTestPointsOnTheTinAreRefusedWithNothingWritten) {
  AccuracyOutputs a;
  a.reportPath = test::tempDir() + "/few.csv";
  a.options.step = 1000;  // one test point of the 360 x 300 DEM: figures of zeros and NaN
  EXPECT_EQ(test::errorOf([&] { runAccuracyJob(smallDem(), built().gpkg, a, 0, "", {}); }),
            "-step 1000 leaves 1 test point on the DEM's 360 x 300 cells, and the figures need 3: give a smaller -step");
  EXPECT_FALSE(fs::exists(a.reportPath));
}

TEST(AccuracyJob, ATestGridTooSmallForTheSurfacesSaysSo) {
  // 4 x 3 test points: no B-spline surface point, every correlation nan, without a word.
  AccuracyOutputs a;
  a.reportPath = test::tempDir() + "/small.csv";
  a.options.step = 100;
  test::RecordingFeedback fb;
  const AccuracyReport r = runAccuracyJob(smallDem(), built().gpkg, a, 0, "", fb.feedback());
  ASSERT_EQ(fb.warnings.size(), 1u);
  EXPECT_EQ(fb.warnings[0], "the test grid of 4 x 3 points is too small for B-spline surfaces with control points every 3: "
                            "they reach 0 of its points, and a correlation needs 3: the height and curvature correlations "
                            "are not measured (nan); give a smaller -step or -control");
  // With control points at every test point, on 5 x 4 test points, the surfaces reach the
  // inner 2 x 1: still too few (3c + 1 across and down is not enough).
  a.options.controlSpacing = 1, a.options.step = 75;
  a.overwrite = true;
  test::RecordingFeedback every;
  runAccuracyJob(smallDem(), built().gpkg, a, 0, "", every.feedback());
  ASSERT_EQ(every.warnings.size(), 1u);
  EXPECT_NE(every.warnings[0].find("with control points every 1: they reach 2 of its points"), std::string::npos) << every.warnings[0];
  a.options.controlSpacing = 3;
  EXPECT_GT(r.rows[0].testPoints, 0u);
  // 12 x 10 test points hold one: measured, and no warning.
  a.options.step = 30;
  a.overwrite = true;
  test::RecordingFeedback enough;
  runAccuracyJob(smallDem(), built().gpkg, a, 0, "", enough.feedback());
  EXPECT_TRUE(enough.warnings.empty()) << enough.warnings[0];
}

// A level the hierarchy does not have is refused from its levels table, before anything
// is read or measured: no progress at all.
TEST(AccuracyJob, ALevelTheHierarchyDoesNotHaveFailsBeforeAnyWork) {
  AccuracyOutputs a;
  a.rasterPath = test::tempDir() + "/level.tif";
  a.rasterLevel = 40;
  bool progressed = false;
  Feedback watching;
  watching.progress = [&progressed](double, const std::string&) { return progressed = true; };
  const int top = static_cast<int>(readHierarchyInfo(built().gpkg).levels.size()) - 1;
  EXPECT_EQ(test::errorOf([&] { runAccuracyJob(smallDem(), built().gpkg, a, 0, "", watching); }),
            "-level 40 does not exist: the hierarchy has levels 0 to " + std::to_string(top));
  EXPECT_FALSE(progressed);
  EXPECT_FALSE(fs::exists(a.rasterPath));
}

TEST(AccuracyJob, CancelLeavesNoRasterOrReport) {
  const std::string dir = test::tempDir() + "/cancel";
  fs::create_directories(dir);
  AccuracyOutputs a;
  a.rasterPath = dir + "/acc.tif";
  a.reportPath = dir + "/acc.html";
  Feedback cancelling;
  cancelling.progress = [](double f, const std::string&) { return f < 0.3; };
  EXPECT_THROW(runAccuracyJob(smallDem(), built().gpkg, a, 0, "", cancelling), Cancelled);
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace tinlod
