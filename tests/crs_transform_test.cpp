// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <ogr_spatialref.h>

#include <cmath>

#include "crs_scale.h"
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

namespace {

// A DEM in degrees spanning lon0..lon1 and lat0..lat1 (5 x 5 cells).
Dem degreeDem(double lon0, double lon1, double lat0, double lat1) {
  Dem dem = test::makeDem(5, 5, 10, [](int, int) { return 1.0f; });
  dem.geotransform = {lon0, (lon1 - lon0) / 5, 0.0, lat1, 0.0, -(lat1 - lat0) / 5};
  dem.crsWkt = test::wktOf(4326);
  return dem;
}

// The CRS a warning advises: the text between the quotes after -t_srs.
std::string advisedCrs(const std::string& warning) {
  const std::size_t start = warning.find("-t_srs '");
  if (start == std::string::npos) return {};
  const std::size_t end = warning.find('\'', start + 8);
  return warning.substr(start + 8, end - start - 8);
}

// A DEM of 5 x 5 cells in a projected CRS, its upper-left corner at (x0, y0).
Dem projectedDem(int epsg, double x0, double y0, double cell) {
  Dem dem = test::makeDem(5, 5, cell, [](int, int) { return 1.0f; });
  dem.geotransform = {x0, cell, 0.0, y0, 0.0, -cell};
  dem.crsWkt = test::wktOf(epsg);
  return dem;
}

// What forDem warns of for the DEM and target CRS.
std::vector<std::string> warningsFor(const Dem& dem, const std::string& target = "") {
  test::RecordingFeedback fb;
  CrsTransform::forDem(dem, "", target, ProgressRange(fb.feedback(), 0, 1));
  return fb.warnings;
}

bool has(const std::vector<std::string>& warnings, const std::string& fragment) {
  return warnings.size() == 1 && warnings[0].find(fragment) != std::string::npos;
}

std::vector<LonLat> denseGrid(double lon0, double lon1, double lat0, double lat1) {
  std::vector<LonLat> points;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) points.push_back({lon0 + (lon1 - lon0) * j / 40, lat0 + (lat1 - lat0) * i / 40});
  return points;
}

}  // namespace

TEST(Crs, DistortingCrsDrawsAWarningNamingTheUtmZone) {
  // Web Mercator around San Francisco (37.8 N): distances stretched by 1 / cos(lat).
  const Dem dem = projectedDem(3857, -13627000.0, 4551000.0, 10);
  const std::vector<std::string> warned = warningsFor(dem);
  EXPECT_TRUE(has(warned, "stretches distances by up to 27 %")) << warned.size();
  EXPECT_TRUE(has(warned, "-t_srs EPSG:32610"));
  EXPECT_TRUE(warningsFor(dem, "EPSG:32610").empty());
}

TEST(CrsScale, WorstScaleErrorIsProjsScaleFactor) {
  // UTM's scale factor on its central meridian; Mercator's sqrt(1 - e2 sin2 lat) / cos lat at 60 N.
  EXPECT_NEAR(worstScaleError("EPSG:32632", {{9.0, 0.0}}), 0.0004, 1e-9);
  const double e2 = 0.00669437999014, s2 = 0.75;
  EXPECT_NEAR(worstScaleError("+proj=merc +k=1 +datum=WGS84 +type=crs", {{0.0, 0.0}, {10.0, 60.0}}),
              std::sqrt(1 - e2 * s2) / 0.5 - 1, 1e-9);
  // PROJ cannot tell: no CRS, or a point the projection cannot take (a transverse Mercator
  // 100 degrees from its meridian); a CRS with heights is weighed by its projected part.
  EXPECT_TRUE(std::isnan(worstScaleError("not a crs", {{0.0, 0.0}})));
  EXPECT_TRUE(std::isnan(worstScaleError("+proj=tmerc +lon_0=0 +datum=WGS84", {{0.0, 0.0}, {100.0, 0.0}})));
  EXPECT_NEAR(worstScaleError("EPSG:25832+7837", {{9.0, 0.0}}), 0.0004, 1e-9);
}

TEST(CrsScale, PercentagesSayWhatTheyMean) {
  EXPECT_EQ(percentText(0.27), "27 %");
  EXPECT_EQ(percentText(0.0023), "0.2 %");
  EXPECT_EQ(percentText(0.012), "1.2 %");
  EXPECT_EQ(percentText(0.0104), "1.04 %");  // over 1 %, never "1 %"
  EXPECT_EQ(percentText(0.010004), "1.01 %");
  EXPECT_EQ(percentText(1.3e6), "over 1000 %");
  EXPECT_EQ(percentText(1e-6), "under 0.1 %");  // never "0 %"
}

TEST(CrsScale, AFittedCrsHoldsEveryPoint) {
  // Along the meridian a transverse Mercator would be true to scale, but it cannot project the
  // point 100 degrees east of it: the Mercator, which can, is the one fitted.
  std::vector<LonLat> points{{100.0, 0.0}};
  for (int lat = -60; lat <= 60; lat += 10) points.push_back({0.0, double(lat)});
  const FittedCrs fitted = fittedCrs(points, {0.0, 0.0});
  EXPECT_EQ(fitted.kind, "a Mercator");
  EXPECT_EQ(worstScaleError(fitted.definition, points), fitted.error);
}

TEST(CrsScale, AFittedCrsFarFromTrueScaleIsNotAdvised) {
  // Web Mercator of a DEM 120 degrees wide reaching 85 N: a balanced Mercator would still be
  // 84 % off (and shrink the equator by as much), the others more.
  std::vector<LonLat> points;
  for (int lon = -60; lon <= 60; lon += 60)
    for (int lat = 0; lat <= 85; lat += 5) points.push_back({double(lon), double(lat)});
  const std::string advice = scaleAdvice(points, {0.0, 42.5}, worstScaleError("EPSG:3857", points));
  EXPECT_EQ(advice, "none of the conformal CRSs tinlod fits keeps a DEM this large within 1 % of true scale");
}

TEST(CrsScale, AFittedCrsShrinksAsMuchAsItStretches) {
  // On the equator and at 10 N a Mercator's scales are 1 and 1/cos 10 (nearly): balanced about
  // 1, each is off by their half-difference over their half-sum, whatever the longitudes.
  const std::vector<LonLat> band = {{-2, 0}, {2, 0}, {-2, 10}, {2, 10}, {0, 5}};
  const FittedCrs fitted = fittedCrs(band, {0, 5});
  const double high = std::sqrt(1 - 0.00669437999014 * std::pow(std::sin(10 * M_PI / 180), 2)) / std::cos(10 * M_PI / 180);
  EXPECT_LE(fitted.error, (high - 1) / (high + 1) + 1e-6);  // a Mercator's, or better
  EXPECT_NEAR(worstScaleError(fitted.definition + " +type=crs", band), fitted.error, 1e-12);
}

TEST(Crs, ADemWiderThanAUtmZoneIsWarnedOfWithACrsThatFitsIt) {
  // 60 degrees of longitude at 30-40 N: UTM zone 32N is true to scale at the centre, 12 % off at the sides.
  const Dem dem = degreeDem(-20, 40, 30, 40);
  const std::vector<std::string> warned = warningsFor(dem);
  ASSERT_TRUE(has(warned, "UTM zone 32N (EPSG:32632) stretches distances by up to 12 % over the DEM")) << warned.size();
  EXPECT_TRUE(has(warned, "(a Lambert conformal conic fitted to the DEM, within 0.2 %)")) << warned[0];
  const std::string advised = advisedCrs(warned[0]);
  ASSERT_NE(advised.find("+proj=lcc"), std::string::npos) << warned[0];
  // Within what it says everywhere over the DEM, not only at the points weighed.
  EXPECT_LE(worstScaleError(advised + " +type=crs", denseGrid(-20, 40, 30, 40)), 0.0025);
  EXPECT_TRUE(warningsFor(dem, advised).empty());
  const CrsTransform t = CrsTransform::forDem(dem, "", advised, ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(t.targetName().rfind("'+proj=lcc ", 0), 0u) << t.targetName();  // named by its PROJ string, not "unknown"
}

TEST(Crs, ADemAcrossTheAntimeridianIsFittedAboutItsCentre) {
  // 170 E to 160 W: the centre, 175 W, is in zone 1, whose meridian is 2 degrees west of it.
  const Dem dem = degreeDem(170, 200, 0, 10);
  const std::vector<std::string> warned = warningsFor(dem);
  ASSERT_TRUE(has(warned, "UTM zone 1N (EPSG:32601) stretches distances by up to")) << warned.size();
  EXPECT_NE(advisedCrs(warned[0]).find("+lon_0=-175 "), std::string::npos) << warned[0];
  EXPECT_TRUE(warningsFor(dem, advisedCrs(warned[0])).empty());
}

TEST(Crs, AHemisphereNoUtmZoneCanHoldIsSaidBeforeTheRunWithACrsThatCoversIt) {
  // 180 degrees of longitude, 60 S to 60 N: PROJ cannot project the equator 90 degrees from
  // zone 31's meridian. The run would fail once the DEM is read; it is said now, and the
  // run's error says what to use: a Mercator, 1 at the equator and 2 at 60 degrees,
  // balanced to 33 %.
  const Dem dem = degreeDem(-90, 90, -60, 60);
  const std::vector<std::string> warned = warningsFor(dem);
  ASSERT_TRUE(has(warned, "UTM zone 31N (EPSG:32631) cannot project the whole DEM: PROJ fails at 2 of 81 points"))
      << (warned.empty() ? "" : warned[0]);
  EXPECT_TRUE(has(warned, "(a Mercator fitted to the DEM, which covers it, within 33 % of true scale")) << warned[0];
  EXPECT_TRUE(has(warned, "or cut it into regions (gdal_translate -projwin)")) << warned[0];
  std::vector<double> x, y;
  for (const LonLat& p : denseGrid(-90, 90, -60, 60)) x.push_back(p.lon), y.push_back(p.lat);
  const std::string failed = test::errorOf([&] {
    std::vector<double> tx = x, ty = y;
    CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1)).apply(tx, ty);
  });
  EXPECT_NE(failed.find("PROJ could not transform 17 of 1681 points of the DEM to WGS 84 / UTM zone 31N"), std::string::npos)
      << failed;
  EXPECT_NE(failed.find("use -t_srs '" + advisedCrs(warned[0]) + "'"), std::string::npos) << failed;
  // The CRS advised covers every point, within what it says.
  const CrsTransform advised = CrsTransform::forDem(dem, "", advisedCrs(warned[0]), ProgressRange(Feedback{}, 0, 1));
  EXPECT_NO_THROW(advised.apply(x, y));
  EXPECT_LE(worstScaleError(advisedCrs(warned[0]) + " +type=crs", denseGrid(-90, 90, -60, 60)), 0.335);
}

TEST(Crs, ACrsWhoseGridIsMissingFailsBeforeTheRunWithProjsReason) {
  // GDAL reported the missing grid at each question asked of the CRS, then "Reprojection
  // failed, err = 4098" at each point, and the run failed once the DEM was read.
  const std::string failed = test::errorOf([] {
    CrsTransform::forDem(degreeDem(7, 8, 46, 47), "", "+proj=utm +zone=32 +ellps=GRS80 +nadgrids=missing.gsb +units=m",
                         ProgressRange(Feedback{}, 0, 1));
  });
  EXPECT_NE(failed.find("PROJ cannot transform any point of the DEM to '+proj=utm +zone=32"), std::string::npos) << failed;
  EXPECT_NE(failed.find("(PROJ: hgridshift: could not find required grid(s).)"), std::string::npos) << failed;
}

TEST(Crs, ADemOfMarsGoesToATransverseMercatorOnMarsNotToAnEarthUtmZone) {
  // Mars picked Earth's UTM zone 52N and failed with both CRSs' whole WKT in the message.
  Dem dem = degreeDem(130, 133, 18, 20);
  OGRSpatialReference mars;
  ASSERT_EQ(mars.SetFromUserInput("IAU_2015:49900"), OGRERR_NONE);
  char* wkt = nullptr;
  mars.exportToWkt(&wkt);
  dem.crsWkt = wkt;
  CPLFree(wkt);
  const CrsTransform t = CrsTransform::forDem(dem, "", "", ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(t.targetName(), "Transverse Mercator 131.5 on Mars (2015) - Sphere");
  // A degree of latitude on the central meridian is pi / 180 of Mars's 3396.19 km radius.
  std::vector<double> x{131.5, 131.5}, y{18.0, 19.0};
  t.apply(x, y);
  EXPECT_NEAR(y[1] - y[0], 3396190.0 * M_PI / 180, 1e-3);
  EXPECT_NEAR(x[0], 0, 1e-6);
  const std::string earth = test::errorOf([&] { CrsTransform::forDem(dem, "", "EPSG:32652", ProgressRange(Feedback{}, 0, 1)); });
  EXPECT_NE(earth.find("and WGS 84 / UTM zone 52N (EPSG:32652) is on Earth: give -t_srs a projected CRS of the DEM's own body"),
            std::string::npos)
      << earth;
  EXPECT_EQ(earth.find("GEOGCRS"), std::string::npos) << earth;
}

TEST(Crs, TheWholeWorldIsToldToBeCutIntoRegions) {
  const std::vector<std::string> warned = warningsFor(degreeDem(-180, 180, -90, 90));
  EXPECT_TRUE(has(warned, "cannot project the whole DEM: PROJ fails at")) << (warned.empty() ? "" : warned[0]);
  EXPECT_TRUE(has(warned, ": none of the conformal CRSs tinlod fits covers a DEM this large within 50 % of true scale: "
                          "cut it into regions (gdal_translate -projwin) and run each in a CRS of its own"));
}

TEST(Crs, ADemWithinItsUtmZonesReachIsNotWarnedOf) {
  // 14 degrees of longitude at 58-62 N are within 420 km of zone 33's meridian (0.2 % at most).
  EXPECT_TRUE(warningsFor(degreeDem(5, 19, 58, 62)).empty());
}

TEST(Crs, AContinentNoCrsKeepsTrueToScaleIsSaidToBeSo) {
  // Antarctica in its polar stereographic CRS, 6000 km across: 2.7 % short at the pole, longer
  // at the corners; a fitted stereographic would still be off by over 5 %.
  const std::vector<std::string> warned = warningsFor(projectedDem(3031, -3000000.0, 3000000.0, 1200000.0));
  EXPECT_TRUE(has(warned, "Antarctic Polar Stereographic (EPSG:3031) stretches distances by up to")) << warned.size();
  EXPECT_TRUE(has(warned, "none of the conformal CRSs tinlod fits keeps a DEM this large within 1 % of true scale"));
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
