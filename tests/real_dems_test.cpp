// SPDX-License-Identifier: GPL-3.0-or-later
// Every DEM in ../shared/data (or $TINLOD_TEST_DATA) gives a valid TIN. Skipped, with
// a message, where the folder is absent.
#include <gtest/gtest.h>

#include <gdal_priv.h>

#include <cstdio>
#include <filesystem>
#include <set>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

struct RealDem {
  const char* file;
  const char* sourceSrs;  // for files that carry no CRS (see the data folder's README)
  const char* expectedCrs;
  // The study's 0.99 m is about a whole cell of a 1 m LiDAR DEM, where points pass their
  // neighbours and grid footprints stop being exact (tinlod warns); those run at 0.1 m.
  double jitter = 0.99;
};

const RealDem kDems[] = {
    {"boulder_srtmgl3_144.asc", "EPSG:4326", "EPSG:32613"},
    {"tntn_sf_valid_raster.tif", "", "EPSG:3857"},
    {"bavaria_dgm5_bottomup.tif", "", "EPSG:31468"},
    {"dc_lidar2m_dtm.tif", "", "EPSG:26918"},
    {"mn_pothole_lidar1m.tif", "", "EPSG:26915", 0.1},
    {"fort_worth_3s.tif", "", "EPSG:32614"},
    {"zion_srtm3.tif", "", "EPSG:32612"},
    {"mandakini_90m.bil", "", "EPSG:32644"},
    {"mandakini_90m.tif", "", "EPSG:32644"},
    {"gabilan_mesa_lidar1m.tif", "", "EPSG:32610", 0.1},
    {"big_tujunga_30m.tif", "", "EPSG:32611"},
    {"N47E009.hgt", "", "EPSG:32632"},
    {"swiss_alps_N46E008.tif", "", "EPSG:32632"},
    {"vancouver_N49W123.tif", "", "EPSG:32610"},
    {"dead_sea_N31E035.tif", "", "EPSG:32636"},
    {"meghalaya_50m.tif", "", "EPSG:32646"},
    {"alps_2x2_N46E007_N47E008.tif", "", "EPSG:32632"},
    {"patagonia_coast_S46W066.tif", "", "EPSG:32720"},
};

void PrintTo(const RealDem& dem, std::ostream* os) { *os << dem.file; }

class RealDemTest : public ::testing::TestWithParam<RealDem> {};

TEST_P(RealDemTest, GivesAValidDelaunayTinCoveringTheValidExtent) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const RealDem& p = GetParam();
  const Feedback quiet;
  const Dem dem = readDem(dir + "/" + p.file, 1, ProgressRange(quiet, 0, 1));
  SampleOptions o;
  o.sourceSrs = p.sourceSrs;
  o.jitter = p.jitter;
  const Tin tin = sampleTin(dem, o, ProgressRange(quiet, 0, 1));

  EXPECT_NE(tin.crsName.find(p.expectedCrs), std::string::npos) << tin.crsName;
  EXPECT_FALSE(tin.crsWkt.empty());
  const std::size_t valid = dem.validCount();
  EXPECT_GE(tin.vertices.size(), valid / 9 - valid / 200);  // one per 3 x 3 block, at least
  EXPECT_LE(tin.vertices.size(), valid);
  test::expectValidTin(dem, tin, o.jitter, p.sourceSrs);
  const test::Topology t = test::analyseTopology(tin);
  const test::GridCoverage g = test::gridCoverage(dem, tin);
  std::printf("  %s: %zu valid cells, %zu vertices, %zu triangles, %zu components, %zu boundary loops, "
              "%.1f cells covered of extent %.1f (+%.0f boundary blocks), %.1f km2\n",
              p.file, valid, tin.vertices.size(), tin.triangles.size(), t.components, t.boundaryLoops,
              g.tinCells, g.extentCells, g.boundaryBlocks, totalArea(tin) / 1e6);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealDemTest, ::testing::ValuesIn(kDems),
                         [](const ::testing::TestParamInfo<RealDem>& info) {
                           std::string name = info.param.file;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// A raster of the folder that kDems does not list (one added since) gets the same checks
// with the defaults: sampled into a valid TIN, or refused with a message (a DEM without
// a CRS in degrees needs -s_srs, which only the list can give).
TEST(RealDems, EveryRasterOfTheFolderNotListedGivesAValidTinOrAClearError) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  std::set<std::string> listed;
  for (const RealDem& d : kDems) listed.insert(d.file);
  GDALAllRegister();
  std::size_t seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    GDALDatasetUniquePtr raster(GDALDataset::Open(entry.path().c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!raster) continue;
    raster.reset();
    ++seen;
    if (listed.count(name)) continue;
    const Feedback quiet;
    const ProgressRange range(quiet, 0, 1);
    try {
      const Dem dem = readDem(entry.path().string(), 1, range);
      const Tin tin = sampleTin(dem, SampleOptions{}, range);
      test::expectValidTin(dem, tin, SampleOptions{}.jitter);
      std::printf("  %s (not in kDems): %zu vertices in %s\n", name.c_str(), tin.vertices.size(), tin.crsName.c_str());
    } catch (const Error& e) {
      std::printf("  %s (not in kDems): refused: %s\n", name.c_str(), e.what());
      EXPECT_GT(std::string(e.what()).size(), 20u) << name;
    }
  }
  EXPECT_GE(seen, listed.size()) << "the folder holds fewer rasters than kDems lists";
}

TEST(RealDems, LidarWithTheStudysJitterWarnsAndStaysDelaunay) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  test::RecordingFeedback fb;
  const ProgressRange range(fb.feedback(), 0, 1);
  const Dem dem = readDem(dir + "/mn_pothole_lidar1m.tif", 1, range);
  const Tin tin = sampleTin(dem, {}, range);
  EXPECT_TRUE(fb.warned("more than half the cell size"));
  EXPECT_EQ(test::delaunayViolations(tin), 0u);
  EXPECT_EQ(test::trianglesOverNodata(dem, tin), 0u);
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.problem, "");
  EXPECT_EQ(t.eulerCharacteristic(), t.expectedEuler());
}

TEST(RealDems, EnviAndGeoTiffCopiesGiveTheSameTin) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const Feedback quiet;
  const ProgressRange range(quiet, 0, 1);
  const Tin bil = sampleTin(readDem(dir + "/mandakini_90m.bil", 1, range), {}, range);
  const Tin tif = sampleTin(readDem(dir + "/mandakini_90m.tif", 1, range), {}, range);
  EXPECT_EQ(bil.triangles, tif.triangles);
  ASSERT_EQ(bil.vertices.size(), tif.vertices.size());
  for (std::size_t i = 0; i < bil.vertices.size(); ++i) EXPECT_NEAR(bil.vertices[i].z, tif.vertices[i].z, 1e-3);
}

}  // namespace
}  // namespace tinlod
