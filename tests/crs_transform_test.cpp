// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <ogr_spatialref.h>

#include <cmath>

#include "test_support.h"
#include "tinlod/crs_transform.h"
#include "tinlod/error.h"
#include "tinlod/sample_job.h"

namespace tinlod {
namespace {

// Northing of a point on a UTM zone's central meridian: k0 times the meridian arc of
// WGS 84 (series in e^2 to the third order, accurate to well under a millimetre).
double utmNorthingOnCentralMeridian(double latDegrees) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f), k0 = 0.9996;
  const double e4 = e2 * e2, e6 = e4 * e2, phi = latDegrees * M_PI / 180;
  const double m = a * ((1 - e2 / 4 - 3 * e4 / 64 - 5 * e6 / 256) * phi -
                        (3 * e2 / 8 + 3 * e4 / 32 + 45 * e6 / 1024) * std::sin(2 * phi) +
                        (15 * e4 / 256 + 45 * e6 / 1024) * std::sin(4 * phi) - (35 * e6 / 3072) * std::sin(6 * phi));
  return k0 * m;
}

// -s_srs EPSG:4326 for a DEM in UTM metres: its coordinates are named, and the fix, where
// PROJ said "Invalid latitude" and tinlod advised -t_srs.
TEST(Crs, AGeographicCrsOnCoordinatesThatAreNoLongitudesIsNamed) {
  const Dem dem = test::makeDem(10, 10, 30, [](int, int) { return 100.0f; });  // UTM 32N, x from 500000
  const std::string error = test::errorOf([&] { CrsTransform::forDem(dem, "EPSG:4326", "", ProgressRange(Feedback{}, 0, 1)); });
  EXPECT_NE(error.find("that are no longitudes and latitudes, so -s_srs EPSG:4326 (WGS 84 (EPSG:4326)) does not fit them: "
                       "leave -s_srs out to use the DEM's own CRS"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("(x 500000 to 500300, y 4.9997e+06 to 5e+06)"), std::string::npos) << error;
}

TEST(Crs, UtmZoneOfAPoint) {
  EXPECT_EQ(utmEpsgFor(9.0, 47.0), 32632);
  EXPECT_EQ(utmEpsgFor(8.99, 47.0), 32632);
  EXPECT_EQ(utmEpsgFor(-122.9, 49.5), 32610);
  EXPECT_EQ(utmEpsgFor(35.5, 31.5), 32636);
  EXPECT_EQ(utmEpsgFor(-65.5, -45.5), 32720);
  EXPECT_EQ(utmEpsgFor(-180.0, 10.0), 32601);
  EXPECT_EQ(utmEpsgFor(179.99, -10.0), 32760);
  EXPECT_EQ(utmEpsgFor(180.0, 10.0), 32601);  // the antimeridian wraps to zone 1
}

TEST(Crs, GeographicDemGoesToUtmAndLandsOnKnownPoints) {
  // Cell (row 0, col 6) has its centre on 9 E, the central meridian of zone 32; the
  // DEM's centre is in zone 32 too.
  const double lon0 = 9.0 - 6.5 / 1200, lat0 = 47.0 + 0.5 / 1200;
  const Dem dem = test::makeGeographicDem(12, 10, lon0, lat0);
  SampleOptions o;
  o.block = 1;
  o.jitter = 0;
  test::RecordingFeedback fb;
  const Feedback feedback = fb.feedback();
  const Tin tin = sampleTin(dem, o, ProgressRange(feedback, 0, 1));
  EXPECT_NE(tin.crsName.find("32632"), std::string::npos) << tin.crsName;
  bool found = false;
  for (const TinVertex& v : tin.vertices)
    if (v.row == 0 && v.col == 6) {
      found = true;
      EXPECT_NEAR(v.x, 500000.0, 1e-6);
      EXPECT_NEAR(v.y, utmNorthingOnCentralMeridian(47.0), 1e-3);
    }
  EXPECT_TRUE(found);
  ASSERT_FALSE(fb.infos.empty());
  EXPECT_NE(fb.infos[0].find("UTM zone 32N"), std::string::npos) << fb.infos[0];
}

TEST(Crs, EquatorOnCentralMeridianIsFalseEasting) {
  const Dem dem = test::makeGeographicDem(4, 4, 3.0 - 1.5 / 1200, 0.0 + 2.5 / 1200);  // zone 31 north
  const CrsTransform t = CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1));
  std::vector<double> x{3.0}, y{0.0};
  t.apply(x, y);
  EXPECT_NEAR(x[0], 500000.0, 1e-6);
  EXPECT_NEAR(y[0], 0.0, 1e-6);
}

TEST(Crs, MetricDemStaysAsItIs) {
  const Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  const CrsTransform t = CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1));
  EXPECT_TRUE(t.isIdentity());
  EXPECT_NE(t.targetName().find("32632"), std::string::npos);
}

TEST(Crs, DistortingCrsDrawsAWarningNamingTheUtmZone) {
  Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  // Web Mercator around San Francisco (37.8 N): distances stretched by 1 / cos(lat).
  dem.geotransform = {-13627000.0, 10.0, 0.0, 4551000.0, 0.0, -10.0};
  dem.crsWkt = test::wktOf(3857);
  test::RecordingFeedback fb;
  CrsTransform::forDem(dem, "", "", ProgressRange(fb.feedback(), 0, 1));
  ASSERT_EQ(fb.warnings.size(), 1u);
  EXPECT_TRUE(fb.warned("stretches distances by 27 %")) << fb.warnings[0];
  EXPECT_TRUE(fb.warned("-t_srs EPSG:32610")) << fb.warnings[0];
  test::RecordingFeedback utm;
  CrsTransform::forDem(dem, "", "EPSG:32610", ProgressRange(utm.feedback(), 0, 1));
  EXPECT_TRUE(utm.warnings.empty());
}

TEST(Crs, TargetSrsIsUsed) {
  const Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  const CrsTransform t = CrsTransform::forDem(dem, "", "EPSG:32633", ProgressRange(Feedback{}, 0, 1));
  EXPECT_FALSE(t.isIdentity());
  EXPECT_NE(t.targetName().find("32633"), std::string::npos);
}

TEST(Crs, GeographicOrUnknownTargetIsAnError) {
  const Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  const ProgressRange quiet(Feedback{}, 0, 1);
  EXPECT_THROW(CrsTransform::forDem(dem, "", "EPSG:4326", quiet), Error);
  EXPECT_THROW(CrsTransform::forDem(dem, "", "not a crs", quiet), Error);
  EXPECT_THROW(CrsTransform::forDem(dem, "nonsense", "", quiet), Error);
}

TEST(Crs, NonMetricProjectedDemGoesToUtm) {
  Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  dem.geotransform = {6000000.0, 30.0, 0.0, 2100000.0, 0.0, -30.0};  // feet, around San Francisco
  dem.crsWkt = test::wktOf(2227);  // California zone 3, US survey feet
  const CrsTransform t = CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1));
  EXPECT_NE(t.targetName().find("32610"), std::string::npos) << t.targetName();
}

TEST(Crs, DemWithoutCrsIsMetricWithAWarning) {
  Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  dem.crsWkt.clear();
  test::RecordingFeedback fb;
  const Feedback feedback = fb.feedback();
  const CrsTransform t = CrsTransform::forDem(dem, "", "", ProgressRange(feedback, 0, 1));
  EXPECT_TRUE(t.isIdentity());
  EXPECT_TRUE(t.targetWkt().empty());
  EXPECT_TRUE(fb.warned("no CRS"));
  EXPECT_FALSE(fb.warned("look like degrees"));
}

TEST(Crs, DegreesWithoutCrsWarnAndSourceSrsFixesIt) {
  Dem dem = test::makeGeographicDem(5, 5, 7.0, 46.0);
  dem.crsWkt.clear();
  test::RecordingFeedback fb;
  const Feedback feedback = fb.feedback();
  EXPECT_TRUE(CrsTransform::forDem(dem, "", "", ProgressRange(feedback, 0, 1)).isIdentity());
  EXPECT_TRUE(fb.warned("-s_srs EPSG:4326"));
  const CrsTransform fixed = CrsTransform::forDem(dem, "EPSG:4326", "", ProgressRange(feedback, 0, 1));
  EXPECT_NE(fixed.targetName().find("32632"), std::string::npos);
  EXPECT_EQ(test::errorOf([&] { CrsTransform::forDem(dem, "", "EPSG:32632", ProgressRange(feedback, 0, 1)); }),
            "'test DEM' has no CRS, so it cannot be transformed to WGS 84 / UTM zone 32N (EPSG:32632): name its CRS "
            "with -s_srs, e.g. -s_srs EPSG:4326 (QGIS: assign the layer's CRS)");
}

TEST(Crs, ALocalCrsIsNoPlaceToTransformFromAndTheErrorSaysSoWithoutWkt) {
  Dem dem = test::makeGeographicDem(5, 5, 7.0, 46.0);
  OGRSpatialReference local;
  local.SetLocalCS("unnamed");
  char* wkt = nullptr;
  local.exportToWkt(&wkt);
  dem.crsWkt = wkt;
  CPLFree(wkt);
  const std::string error =
      test::errorOf([&] { CrsTransform::forDem(dem, "", "EPSG:32632", ProgressRange(Feedback{}, 0, 1)); });
  EXPECT_EQ(error, "'test DEM' has no CRS (only a local one, unnamed), so it cannot be transformed to WGS 84 / UTM "
                   "zone 32N (EPSG:32632): name its CRS with -s_srs, e.g. -s_srs EPSG:4326 (QGIS: assign the layer's CRS)");
  EXPECT_NE(CrsTransform::forDem(dem, "EPSG:4326", "EPSG:32632", ProgressRange(Feedback{}, 0, 1)).targetName().find("32632"),
            std::string::npos);
}

TEST(Crs, ALocalCrsInFeetHasNoUtmZoneToGoToAndSaysSo) {
  Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  OGRSpatialReference local;
  local.SetLocalCS("site grid");
  local.SetLinearUnits("foot", 0.3048);
  char* wkt = nullptr;
  local.exportToWkt(&wkt);
  dem.crsWkt = wkt;
  CPLFree(wkt);
  EXPECT_TRUE(test::contains(test::errorOf([&] { CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1)); }),
                             "has only a local CRS (site grid) in units that are not metres: name its CRS with -s_srs"));
}

}  // namespace
}  // namespace tinlod
