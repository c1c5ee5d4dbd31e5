// SPDX-License-Identifier: GPL-3.0-or-later
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "parallel_blocks.h"
#include "test_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/height_range.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);

struct RasterSpec {
  int width = 6, height = 5, bands = 1;
  GDALDataType type = GDT_Float32;
  double gt[6] = {500000, 10, 0, 5000000, 0, -10};
  bool setNodata = false;
  double nodata = 0;
  std::function<double(int, int)> value = [](int r, int c) { return 100 + r + c; };
};

std::string writeRaster(const RasterSpec& s, const std::string& name = "dem.tif") {
  GDALAllRegister();
  const std::string path = test::tempDir() + "/" + name;
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), s.width, s.height,
                                                                            s.bands, s.type, nullptr);
  ds->SetGeoTransform(const_cast<double*>(s.gt));
  ds->SetProjection("EPSG:32632");
  std::vector<double> v(std::size_t(s.width) * s.height);
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c) v[std::size_t(r) * s.width + c] = s.value(r, c);
  for (int b = 1; b <= s.bands; ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b);
    if (s.setNodata) band->SetNoDataValue(s.nodata);
    EXPECT_EQ(band->RasterIO(GF_Write, 0, 0, s.width, s.height, v.data(), s.width, s.height, GDT_Float64, 0, 0), CE_None);
  }
  GDALClose(ds);
  return path;
}

void expectError(const std::string& path, int band, const std::string& fragment) {
  try {
    readDem(path, band, kRange);
    FAIL() << "expected an error containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(DemReader, ReadsHeightsGeoreferencingAndCrs) {
  RasterSpec s;
  s.type = GDT_Int16;
  const Dem dem = readDem(writeRaster(s), 1, kRange);
  EXPECT_EQ(dem.width, 6);
  EXPECT_EQ(dem.height, 5);
  EXPECT_FLOAT_EQ(dem.at(2, 3), 105.0f);
  EXPECT_DOUBLE_EQ(dem.centreX(0), 500005.0);
  EXPECT_DOUBLE_EQ(dem.centreY(0), 4999995.0);
  EXPECT_NE(dem.crsWkt.find("32632"), std::string::npos);
  EXPECT_EQ(dem.validCount(), 30u);
}

// The heights are decoded on a handle of their own beside the CRS lookup, unless one
// thread is all there is: both ways read the same DEM, and a cancel while the heights are
// read stops the reading either way.
TEST(DemReader, ReadingBesideTheCrsLookupReadsWhatReadingInTurnReads) {
  GDALAllRegister();
  const std::string path = test::tempDir() + "/tiled.tif";
  const char* const options[] = {"TILED=YES", "BLOCKXSIZE=64", "BLOCKYSIZE=64", "COMPRESS=DEFLATE", nullptr};
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 300, 200, 1, GDT_Float32,
                                                                            const_cast<char**>(options));
  const double gt[6] = {7.0, 0.001, 0, 47.0, 0, -0.001};
  ds->SetGeoTransform(const_cast<double*>(gt));
  ds->SetProjection("EPSG:4326");
  std::vector<float> v(300 * 200);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = i % 97 == 0 ? -9999.f : float(i % 1013) * 0.5f;
  ds->GetRasterBand(1)->SetNoDataValue(-9999);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 300, 200, v.data(), 300, 200, GDT_Float32, 0, 0), CE_None);
  GDALClose(ds);

  const Dem beside = readDem(path, 1, kRange);
  Dem inTurn;
  {
    ThisThreadAlone alone;
    inTurn = readDem(path, 1, kRange);
  }
  EXPECT_NE(beside.crsWkt.find("4326"), std::string::npos);
  EXPECT_EQ(beside.crsWkt, inTurn.crsWkt);
  ASSERT_EQ(beside.z.size(), v.size());
  ASSERT_EQ(inTurn.z.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(std::isnan(beside.z[i]), v[i] == -9999.f) << i;
    if (v[i] != -9999.f) EXPECT_EQ(beside.z[i], v[i]) << i;
    EXPECT_EQ(std::isnan(inTurn.z[i]), std::isnan(beside.z[i])) << i;
    if (!std::isnan(beside.z[i])) EXPECT_EQ(inTurn.z[i], beside.z[i]) << i;
  }

  Feedback cancelling;
  cancelling.progress = [](double, const std::string&) { return false; };
  EXPECT_THROW(readDem(path, 1, ProgressRange(cancelling, 0, 1)), Cancelled);
  ThisThreadAlone alone;
  EXPECT_THROW(readDem(path, 1, ProgressRange(cancelling, 0, 1)), Cancelled);
}

TEST(DemReader, DeclaredNodataBecomesMissing) {
  RasterSpec s;
  s.type = GDT_Int16;
  s.setNodata = true;
  s.nodata = -32767;
  s.value = [](int r, int c) { return r == 1 && c == 1 ? -32767 : 10; };
  const Dem dem = readDem(writeRaster(s), 1, kRange);
  EXPECT_FALSE(dem.valid(1, 1));
  EXPECT_EQ(dem.validCount(), 29u);
}

TEST(DemReader, FloatNodataGivenAsDoubleStillMatches) {
  RasterSpec s;
  s.setNodata = true;
  s.nodata = -3.4028234663852886e+38;
  s.value = [](int r, int) { return r == 0 ? -3.4028234663852886e+38 : 1.0; };
  EXPECT_EQ(readDem(writeRaster(s), 1, kRange).validCount(), 24u);
}

TEST(DemReader, NanIsMissingWithoutDeclaredNodata) {
  RasterSpec s;
  s.value = [](int r, int c) { return r == 2 && c < 3 ? NAN : 1.0; };
  EXPECT_EQ(readDem(writeRaster(s), 1, kRange).validCount(), 27u);
}

TEST(DemReader, ChosenBandIsRead) {
  RasterSpec s;
  s.bands = 3;
  const std::string path = writeRaster(s);
  {
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_Update));
    float v = 777;
    ASSERT_EQ(ds->GetRasterBand(2)->RasterIO(GF_Write, 0, 0, 1, 1, &v, 1, 1, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
  }
  EXPECT_FLOAT_EQ(readDem(path, 2, kRange).at(0, 0), 777.0f);
  expectError(path, 4, "invalid band number 4");
  expectError(path, 0, "bands 1 to 3");
}

TEST(DemReader, BottomUpGeotransformIsKept) {
  RasterSpec s;
  s.gt[3] = 4999950;
  s.gt[5] = 10;  // rows go north
  const Dem dem = readDem(writeRaster(s), 1, kRange);
  EXPECT_DOUBLE_EQ(dem.centreY(0), 4999955.0);
  EXPECT_DOUBLE_EQ(dem.centreY(4), 4999995.0);
}

TEST(DemReader, RotatedGeotransformIsAnError) {
  RasterSpec s;
  s.gt[2] = 0.5;
  expectError(writeRaster(s), 1, "rotated geotransform");
}

TEST(DemReader, GroundControlPointsInsteadOfAGeotransformAreAnError) {
  // Read as 1 x 1 metre cells in no CRS, the TIN was nowhere, with only a warning.
  GDALAllRegister();  // run alone (ctest), no other test has
  const std::string path = test::tempDir() + "/gcps.tif";
  {
    GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 6, 5, 1, GDT_Float32, nullptr));
    std::vector<float> z(30, 100.0f);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 6, 5, z.data(), 6, 5, GDT_Float32, 0, 0), CE_None);
    GDAL_GCP gcps[3];
    GDALInitGCPs(3, gcps);
    const double pixel[3] = {0, 6, 0}, line[3] = {0, 0, 5}, x[3] = {8, 8.1, 8}, y[3] = {46, 46, 45.9};
    for (int i = 0; i < 3; ++i) gcps[i].dfGCPPixel = pixel[i], gcps[i].dfGCPLine = line[i], gcps[i].dfGCPX = x[i], gcps[i].dfGCPY = y[i];
    OGRSpatialReference wgs84;
    wgs84.importFromEPSG(4326);
    ASSERT_EQ(ds->SetGCPs(3, gcps, &wgs84), CE_None);
    GDALDeinitGCPs(3, gcps);
  }
  expectError(path, 1, "is georeferenced by 3 ground control points, not a geotransform: warp it to a grid first, e.g. gdalwarp");
  // A satellite DEM's rational polynomial coefficients, likewise.
  const std::string rpc = test::tempDir() + "/rpc.tif";
  {
    GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GTiff")->Create(rpc.c_str(), 6, 5, 1, GDT_Float32, nullptr));
    std::vector<float> z(30, 100.0f);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 6, 5, z.data(), 6, 5, GDT_Float32, 0, 0), CE_None);
    const char* const coefficients[] = {"LINE_OFF=2", "SAMP_OFF=3", "LAT_OFF=46", "LONG_OFF=8", "HEIGHT_OFF=0", "LINE_SCALE=2",
                                        "SAMP_SCALE=3", "LAT_SCALE=0.01", "LONG_SCALE=0.01", "HEIGHT_SCALE=100",
                                        "LINE_NUM_COEFF=0 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0",
                                        "LINE_DEN_COEFF=1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0",
                                        "SAMP_NUM_COEFF=0 0 1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0",
                                        "SAMP_DEN_COEFF=1 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0", nullptr};
    ASSERT_EQ(ds->SetMetadata(const_cast<char**>(coefficients), "RPC"), CE_None);
  }
  expectError(rpc, 1, "is georeferenced by rational polynomial coefficients (RPC), not a geotransform: warp it to a grid "
                      "first, e.g. gdalwarp -rpc");
}

TEST(DemReader, AFileOfSeveralRastersNamesThemToChooseFrom) {
  // A GeoPackage (as a netCDF of several variables) of two rasters: "has no raster band".
  const std::string dem = writeRaster(RasterSpec{}), path = test::tempDir() + "/two.gpkg";
  ASSERT_EQ(std::system(("gdal_translate -q -of GPKG -co RASTER_TABLE=heights " + dem + " " + path + " && gdal_translate -q "
                         "-of GPKG -co RASTER_TABLE=slopes -co APPEND_SUBDATASET=YES " + dem + " " + path)
                            .c_str()),
            0);
  expectError(path, 1, "' holds 2 rasters (subdatasets), not one: give one of them as the DEM, e.g. GPKG:" + path +
                           ":heights, GPKG:" + path + ":slopes");
}

TEST(DemReader, FewerThanThreeValidCellsIsAnError) {
  RasterSpec s;
  s.setNodata = true;
  s.nodata = -9999;
  s.value = [](int r, int c) { return r == 0 && c < 2 ? 1 : -9999; };
  expectError(writeRaster(s), 1, "has 2 valid cell(s)");
}

TEST(DemReader, HeightsInKilometresAreConvertedAndAFeetCrsWithoutAHeightUnitIsWarnedOf) {
  RasterSpec s;
  s.value = [](int r, int c) { return r + c; };
  const std::string path = writeRaster(s);
  {
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    ds->GetRasterBand(1)->SetUnitType("km");
  }
  EXPECT_FLOAT_EQ(readDem(path, 1, kRange, HeightRange{-1e6, 1e6}).at(2, 3), 5000.0f);
  // California zone 3 in US survey feet, the heights' unit unnamed: taken as metres, said so.
  {
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    ds->GetRasterBand(1)->SetUnitType("");
    ds->SetProjection(test::wktOf(2227).c_str());
  }
  test::RecordingFeedback fb;
  EXPECT_FLOAT_EQ(readDem(path, 1, ProgressRange(fb.feedback(), 0, 1)).at(2, 3), 5.0f);
  ASSERT_EQ(fb.warnings.size(), 1u);
  EXPECT_NE(fb.warnings[0].find("whose x and y are in feet, and names no unit for its heights: they are taken as metres; if "
                                "they are feet, say so (gdal_edit -units ft, or US-ft)"),
            std::string::npos)
      << fb.warnings[0];
  {
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
    ds->GetRasterBand(1)->SetUnitType("US-ft");
  }
  test::RecordingFeedback named;
  EXPECT_NEAR(readDem(path, 1, ProgressRange(named.feedback(), 0, 1)).at(2, 3), 5 * 1200.0 / 3937.0, 1e-5);
  EXPECT_TRUE(named.warnings.empty()) << named.warnings[0];
}

TEST(DemReader, ScaleAndOffsetAreApplied) {
  RasterSpec s;
  s.type = GDT_Int16;
  s.setNodata = true;
  s.nodata = -1;
  s.value = [](int r, int c) { return r == 0 && c == 0 ? -1 : r * 10 + c; };
  const std::string path = writeRaster(s);
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_Update));
  ds->GetRasterBand(1)->SetScale(0.1);
  ds->GetRasterBand(1)->SetOffset(100);
  GDALClose(ds);
  const Dem dem = readDem(path, 1, kRange);
  EXPECT_FALSE(dem.valid(0, 0));  // nodata applies to the stored value
  EXPECT_FLOAT_EQ(dem.at(2, 3), 102.3f);
}

TEST(DemReader, HeightsInFeetBecomeMetres) {
  RasterSpec s;
  const std::string path = writeRaster(s);
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_Update));
  ds->GetRasterBand(1)->SetUnitType("ft");
  GDALClose(ds);
  test::RecordingFeedback fb;
  const Dem dem = readDem(path, 1, ProgressRange(fb.feedback(), 0, 1));
  EXPECT_FLOAT_EQ(dem.at(1, 1), float(102 * 0.3048));
  ASSERT_FALSE(fb.infos.empty());
  EXPECT_NE(fb.infos[0].find("converted to metres"), std::string::npos);

  ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_Update));
  ds->GetRasterBand(1)->SetUnitType("furlong");
  GDALClose(ds);
  test::RecordingFeedback unknown;
  EXPECT_FLOAT_EQ(readDem(path, 1, ProgressRange(unknown.feedback(), 0, 1)).at(1, 1), 102.0f);
  EXPECT_TRUE(unknown.warned("'furlong', a unit tinlod does not know"));
}

TEST(DemReader, FileThatIsNoRasterIsAnError) {
  const std::string path = test::tempDir() + "/notes.txt";
  std::ofstream(path) << "this is not a DEM\n";
  expectError(path, 1, "is not a raster GDAL can read");
  expectError(test::tempDir() + "/missing.tif", 1, "missing.tif' does not exist");
}

TEST(DemReader, AsciiGridIsRead) {
  const std::string dir = test::tempDir();
  std::ofstream(dir + "/g.asc") << "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -1\n"
                                   "1 2 3\n4 -1 6\n";
  const Dem dem = readDem(dir + "/g.asc", 1, kRange);
  EXPECT_EQ(dem.validCount(), 5u);
  EXPECT_FLOAT_EQ(dem.at(1, 2), 6.0f);
}

// Undeclared fill: 1e30 (a float's "no value" in some exports), infinity and -32768 (SRTM's
// void, here without its nodata declaration) would become vertices miles up or down.
TEST(DemReader, HeightsOutsideTheValidRangeAreNodataWithOneWarning) {
  RasterSpec s;
  s.value = [](int r, int c) {
    if (r == 0) return c < 3 ? 1e30 : -32768.0;
    if (r == 1 && c < 2) return c == 0 ? double(INFINITY) : -double(INFINITY);
    return r == 2 && c == 0 ? double(NAN) : 100.0 + c;
  };
  const std::string path = writeRaster(s);
  test::RecordingFeedback fb;
  const Dem dem = readDem(path, 1, ProgressRange(fb.feedback(), 0, 1));
  EXPECT_EQ(dem.validCount(), 30u - 8u - 1u);
  EXPECT_FALSE(dem.valid(0, 0));
  EXPECT_FALSE(dem.valid(1, 1));
  ASSERT_EQ(fb.warnings.size(), 1u);
  EXPECT_EQ(fb.warnings[0], "ignored 8 cells of '" + path +
                                "' with heights outside -12000..9000 m (treated as nodata); widen with -valid_range");
}

TEST(DemReader, TheValidRangeCanBeWidenedAndNarrowed) {
  RasterSpec s;
  s.value = [](int r, int c) { return r == 0 && c == 0 ? 9500.0 : 100.0 + r + c; };
  const std::string path = writeRaster(s);
  test::RecordingFeedback wide;
  EXPECT_EQ(readDem(path, 1, ProgressRange(wide.feedback(), 0, 1), HeightRange{-500, 10000}).validCount(), 30u);
  EXPECT_TRUE(wide.warnings.empty());
  test::RecordingFeedback narrow;
  EXPECT_EQ(readDem(path, 1, ProgressRange(narrow.feedback(), 0, 1), HeightRange{101, 104}).validCount(), 14u);
  EXPECT_TRUE(narrow.warned("ignored 16 cells of '" + path + "' with heights outside 101..104 m")) << narrow.warnings[0];
  try {
    readDem(path, 1, kRange, HeightRange{5, 5});
    FAIL() << "an empty range was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "-valid_range must be two finite heights in metres, the lower first (got 5 5); the default is -12000 9000");
  }
}

TEST(DemReader, TheRangeAppliesInMetres) {
  RasterSpec s;
  s.value = [](int, int c) { return c == 0 ? 29000.0 : 28000.0; };  // feet: 8839 and 8534 m
  const std::string path = writeRaster(s);
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_Update));
  ds->GetRasterBand(1)->SetUnitType("ft");
  GDALClose(ds);
  EXPECT_EQ(readDem(path, 1, kRange).validCount(), 30u);
}

TEST(DemReader, ADemWithNoPlausibleHeightIsAnError) {
  RasterSpec s;
  s.value = [](int r, int) { return r == 0 ? double(NAN) : 1e30; };
  expectError(writeRaster(s), 1,
              "band 1 has no valid cell: all its 30 cells are nodata (declared nodata, NaN, masked, or heights outside "
              "-12000..9000 m; -valid_range widens that)");
}

TEST(DemReader, ComplexBandsAreRefused) {
  for (GDALDataType type : {GDT_CInt16, GDT_CInt32, GDT_CFloat32, GDT_CFloat64}) {
    RasterSpec s;
    s.type = type;
    s.bands = 2;
    const std::string path = writeRaster(s, "complex.tif");
    expectError(path, 2,
                "complex.tif' band 2 holds complex numbers (" + std::string(GDALGetDataTypeName(type)) +
                    "), not heights: choose a band of heights with -b");
  }
}

TEST(HeightRange, RecordedRangeReadsBackAndDefaultsForOldFiles) {
  const HeightRange r = recordedRange({{"valid_range", HeightRange{-500.25, 1e4}.text()}});
  EXPECT_EQ(r.min, -500.25);
  EXPECT_EQ(r.max, 1e4);
  EXPECT_EQ(HeightRange{}.text(), "-12000..9000 m");
  EXPECT_EQ(recordedRange({}).min, -12000);
  EXPECT_EQ(parseHeightRange("3..7.5 m").max, 7.5);
  for (const char* bad : {"", "3..7", "7..3 m", "a..b m", "3...7 m", "-inf..0 m"})
    EXPECT_THROW(parseHeightRange(bad), Error) << bad;
}

}  // namespace
}  // namespace tinlod
