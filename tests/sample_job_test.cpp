// SPDX-License-Identifier: GPL-3.0-or-later
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/sample_job.h"
#include "tinlod/synthetic_dem.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::string defaultDem() { return test::smallSyntheticDemFile(); }

struct GpkgLayer {
  long long features = -1;
  std::string geometry;
  std::string crs;
};

GpkgLayer layerInfo(const std::string& path, const std::string& layer) {
  GDALAllRegister();
  GpkgLayer info;
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  if (!ds) return info;
  if (OGRLayer* l = ds->GetLayerByName(layer.c_str())) {
    info.features = l->GetFeatureCount();
    info.geometry = OGRGeometryTypeToName(l->GetGeomType());
    if (l->GetSpatialRef()) info.crs = l->GetSpatialRef()->GetName();
  }
  GDALClose(ds);
  return info;
}

void addLayer(const std::string& path, const char* name) {
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  OGRLayer* l = ds->CreateLayer(name, nullptr, wkbPoint, nullptr);
  OGRFeature f(l->GetLayerDefn());
  f.SetGeometryDirectly(new OGRPoint(1, 2));
  ASSERT_EQ(l->CreateFeature(&f), OGRERR_NONE);
  GDALClose(ds);
}

std::size_t filesIn(const std::string& dir) {
  return std::distance(fs::directory_iterator(dir), fs::directory_iterator());
}

TEST(SampleJob, WritesVerticesAndTrianglesLayersWithCrs) {
  const std::string out = test::tempDir() + "/tin.gpkg";
  const SampleSummary s = runSampleJob(defaultDem(), out, {}, false, {});
  EXPECT_GT(s.vertices, 360u * 300u / 9);
  EXPECT_EQ(layerInfo(out, "vertices").features, (long long)s.vertices);
  EXPECT_EQ(layerInfo(out, "triangles").features, (long long)s.triangles);
  EXPECT_EQ(layerInfo(out, "triangles").geometry, "3D Polygon");
  EXPECT_EQ(layerInfo(out, "vertices").geometry, "3D Point");
  EXPECT_EQ(layerInfo(out, "triangles").crs, "WGS 84 / UTM zone 32N");
}

// A hole's diagonal edge is a stair of cells on the valid area's outline, all sampled, many
// of which end inside the TIN: the TIN's outline is its triangles', as a hierarchy's level
// 0 counts it (info showed 2856 for mandakini's sample and 1086 for its build's level 0).
TEST(SampleJob, OutlineVerticesAreTheTinsOutlineAsTheHierarchysLevelZeroCountsThem) {
  Dem dem = test::makeDem(120, 90, 30, [](int r, int c) {
    const bool hole = std::abs(r - c + 10) < 12 && r > 20 && r < 70;
    return hole ? std::nanf("") : float(300 + 2 * r + std::sin(c / 5.0) * 10);
  });
  const std::string dir = test::tempDir(), demPath = dir + "/stairs.tif";
  writeDemGeoTiff(dem, demPath);
  const SampleSummary s = runSampleJob(demPath, dir + "/stairs_tin.gpkg", {}, true, {});
  runBuildJob(demPath, dir + "/stairs_h.gpkg", {}, {}, true, {});
  const HierarchyInfo tin = readHierarchyInfo(dir + "/stairs_tin.gpkg");
  const HierarchyInfo built = readHierarchyInfo(dir + "/stairs_h.gpkg");
  // The brute force: vertices on an edge that one triangle has.
  std::map<std::pair<long long, long long>, int> edges;
  {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir + "/stairs_tin.gpkg").c_str(), GDAL_OF_VECTOR));
    for (auto& f : *ds->GetLayerByName("triangles")) {
      const long long v[3] = {f->GetFieldAsInteger64("v0"), f->GetFieldAsInteger64("v1"), f->GetFieldAsInteger64("v2")};
      for (int k = 0; k < 3; ++k) ++edges[std::minmax(v[k], v[(k + 1) % 3])];
    }
  }
  std::set<long long> on;
  for (const auto& [edge, count] : edges)
    if (count == 1) on.insert(edge.first), on.insert(edge.second);
  EXPECT_EQ(s.outlineVertices, on.size());
  EXPECT_EQ(tin.levels.front().outlineVertices, on.size());
  EXPECT_EQ(built.levels.front().outlineVertices, on.size());
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir + "/stairs_tin.gpkg").c_str(), GDAL_OF_VECTOR));
  OGRLayer* vertices = ds->GetLayerByName("vertices");
  vertices->SetAttributeFilter("outline = 1");
  EXPECT_LT(on.size(), std::size_t(vertices->GetFeatureCount())) << "the stairs' inner cells are flagged, not on the outline";
}

TEST(SampleJob, SameSeedSameTinOtherSeedOtherTin) {
  const Dem dem = test::smallSyntheticDem();
  const ProgressRange quiet(Feedback{}, 0, 1);
  SampleOptions o;
  const Tin a = sampleTin(dem, o, quiet), b = sampleTin(dem, o, quiet);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  EXPECT_EQ(a.triangles, b.triangles);
  for (std::size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i].x, b.vertices[i].x);
  o.seed = 2;
  const Tin c = sampleTin(dem, o, quiet);
  EXPECT_NE(a.triangles, c.triangles);
}

// Which way (-1, 0, +1 along x and y of the map) most of a cell's missing 8-neighbours lie.
std::array<int, 2> towardsNodata(const Dem& dem, int row, int col) {
  int x = 0, y = 0;
  for (int dr = -1; dr <= 1; ++dr)
    for (int dc = -1; dc <= 1; ++dc)
      if ((dr || dc) && !dem.valid(row + dr, col + dc)) x += dc, y -= dr;  // north-up: +row is -y
  return {(x > 0) - (x < 0), (y > 0) - (y < 0)};
}

// Offsets in [0, jitter) towards +x and +y, but for outline cells inside the raster, which
// move towards the nodata beside them (by as much).
TEST(SampleJob, JitterStaysInItsBounds) {
  const Dem dem = test::smallSyntheticDem();
  SampleOptions o;
  o.jitter = 0.5;
  const Tin tin = sampleTin(dem, o, ProgressRange(Feedback{}, 0, 1));
  double maxDx = 0, maxDy = 0, minD = 1;
  int towards = 0, away = 0;
  for (const TinVertex& v : tin.vertices) {
    const double dx = v.x - dem.centreX(v.col), dy = v.y - dem.centreY(v.row);
    ASSERT_LT(std::abs(dx), 0.5);
    ASSERT_LT(std::abs(dy), 0.5);
    const bool inside = v.row > 0 && v.col > 0 && v.row < dem.height - 1 && v.col < dem.width - 1;
    const std::array<int, 2> side = v.outline && inside ? towardsNodata(dem, v.row, v.col) : std::array<int, 2>{0, 0};
    const double d[2] = {dx, dy};
    for (int k = 0; k < 2; ++k) {
      if (side[k] == 0) {
        ASSERT_GE(d[k], 0.0) << v.row << " " << v.col;
      } else {
        ASSERT_GE(side[k] * d[k], 0.0) << v.row << " " << v.col;
        (side[k] > 0 ? towards : away)++;
      }
    }
    maxDx = std::max(maxDx, std::abs(dx)), maxDy = std::max(maxDy, std::abs(dy)), minD = std::min({minD, std::abs(dx), std::abs(dy)});
  }
  EXPECT_GT(maxDx, 0.49);  // the offsets fill the range
  EXPECT_GT(maxDy, 0.49);
  EXPECT_LT(minD, 0.01);
  EXPECT_GT(towards, 100);  // the void's outline has cells on every side
  EXPECT_GT(away, 100);
}

// Whether (px, py) is in the closed triangle: the test's own check, in doubles, with a
// margin far below the jitter.
bool inTriangle(const Tin& tin, const Triangle& t, double px, double py) {
  double s[3];
  for (int k = 0; k < 3; ++k) {
    const TinVertex &a = tin.vertices[t[k]], &b = tin.vertices[t[(k + 1) % 3]];
    s[k] = (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
  }
  const double eps = 1e-9;
  return (s[0] >= -eps && s[1] >= -eps && s[2] >= -eps) || (s[0] <= eps && s[1] <= eps && s[2] <= eps);
}

// The outline's vertices move towards the nodata beside them: every valid cell's centre is
// in a triangle (it was not, for 26 of the DEM's 105,778 cells, when the jitter moved them
// all towards +x and +y whatever side the void was on).
TEST(SampleJob, LevelZeroCoversEveryValidCellsCentre) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, ProgressRange(Feedback{}, 0, 1));
  std::vector<char> covered(static_cast<std::size_t>(dem.width) * dem.height, 0);
  const auto& gt = dem.geotransform;
  for (const Triangle& t : tin.triangles) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 3; ++k)
      x0 = std::min(x0, tin.vertices[t[k]].x), x1 = std::max(x1, tin.vertices[t[k]].x),
      y0 = std::min(y0, tin.vertices[t[k]].y), y1 = std::max(y1, tin.vertices[t[k]].y);
    const int c0 = std::max(0, int(std::floor((x0 - gt[0]) / gt[1] - 0.5))), c1 = std::min(dem.width - 1, int(std::ceil((x1 - gt[0]) / gt[1] - 0.5)));
    const int r0 = std::max(0, int(std::floor((y1 - gt[3]) / gt[5] - 0.5))), r1 = std::min(dem.height - 1, int(std::ceil((y0 - gt[3]) / gt[5] - 0.5)));
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        if (inTriangle(tin, t, dem.centreX(c), dem.centreY(r))) covered[std::size_t(r) * dem.width + c] = 1;
  }
  std::size_t valid = 0, inTin = 0;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c)
      if (dem.valid(r, c)) ++valid, inTin += covered[std::size_t(r) * dem.width + c];
  EXPECT_EQ(valid, 105778u);
  EXPECT_EQ(inTin, valid);
}

TEST(SampleJob, DefaultDemTinIsValid) {
  const Dem dem = test::smallSyntheticDem();
  const Tin tin = sampleTin(dem, {}, ProgressRange(Feedback{}, 0, 1));
  test::expectValidTin(dem, tin, SampleOptions().jitter);
  const test::Topology t = test::analyseTopology(tin);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.boundaryLoops, 2u);  // the outline and the void
}

TEST(SampleJob, ExistingOutputNeedsOverwriteAndKeepsOtherLayers) {
  const std::string out = test::tempDir() + "/tin.gpkg";
  runSampleJob(defaultDem(), out, {}, false, {});
  addLayer(out, "roads");
  const std::string before = test::readFile(out);
  try {
    runSampleJob(defaultDem(), out, {}, false, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-overwrite"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::readFile(out), before);
  SampleOptions o;
  o.block = 5;
  const SampleSummary s = runSampleJob(defaultDem(), out, o, true, {});
  EXPECT_EQ(layerInfo(out, "roads").features, 1);
  EXPECT_EQ(layerInfo(out, "triangles").features, (long long)s.triangles);
}

// QGIS replaces an output without asking: a hierarchy's levels going for a sampled TIN are
// said; a TIN replacing a TIN is not news.
TEST(SampleJob, ReplacingAHierarchySaysItsLevelsGo) {
  const std::string out = test::tempDir() + "/h.gpkg";
  HierarchyOptions h;
  h.maxLevels = 2;
  runBuildJob(defaultDem(), out, {}, h, false, {});
  test::RecordingFeedback first;
  runSampleJob(defaultDem(), out, {}, true, first.feedback());
  EXPECT_TRUE(first.warned("'" + out + "' held a tinlod TIN hierarchy (its levels, groups and level views): this run's TIN "
                           "will replace it, its other layers kept"));
  EXPECT_EQ(readHierarchyInfo(out).kind, "tin");
  test::RecordingFeedback again;
  runSampleJob(defaultDem(), out, {}, true, again.feedback());
  EXPECT_FALSE(again.warned("held a tinlod"));
}

// An output that is not a GeoPackage is neither replaced nor half updated: the error says
// so, and the file and its folder are as they were.
TEST(SampleJob, AnOutputThatIsNotAGeoPackageIsLeftAlone) {
  const std::string dir = test::tempDir();
  const std::string out = dir + "/tin.gpkg";
  {
    std::ofstream(out) << "a note saved under the wrong name";
  }
  try {
    runSampleJob(defaultDem(), out, {}, true, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exists but is not a GeoPackage GDAL can update"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::readFile(out), "a note saved under the wrong name");
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(SampleJob, CancelLeavesNothingBehindInEveryPhase) {
  // Reading, sampling, triangulating, writing vertices, writing triangles, and the
  // last check before GDAL builds the spatial index (at 0.6 + 0.4 * 0.7 = 0.88).
  for (const double stopAt : {0.05, 0.3, 0.55, 0.65, 0.8, 0.879}) {
    const std::string dir = test::tempDir();
    const std::string out = dir + "/tin.gpkg";
    Feedback cancelling;
    cancelling.progress = [stopAt](double f, const std::string&) { return f < stopAt; };
    EXPECT_THROW(runSampleJob(defaultDem(), out, {}, false, cancelling), Cancelled) << stopAt;
    EXPECT_EQ(filesIn(dir), 0u) << "after cancelling at " << stopAt;
  }
}

TEST(SampleJob, CancelDuringTheSpatialIndexIsHonouredBeforeTheRename) {
  const std::string dir = test::tempDir();
  Feedback cancelling;
  cancelling.progress = [](double f, const std::string&) { return f < 0.9; };
  EXPECT_THROW(runSampleJob(defaultDem(), dir + "/tin.gpkg", {}, false, cancelling), Cancelled);
  EXPECT_EQ(filesIn(dir), 0u);
}

TEST(SampleJob, CancelAfterTheFileIsInPlaceIsIgnored) {
  const std::string out = test::tempDir() + "/tin.gpkg";
  bool sawEnd = false;
  Feedback cancelling;
  cancelling.progress = [&sawEnd](double f, const std::string&) {
    sawEnd = sawEnd || f >= 1.0;
    return f < 1.0;
  };
  const SampleSummary s = runSampleJob(defaultDem(), out, {}, false, cancelling);
  EXPECT_TRUE(sawEnd);
  EXPECT_EQ(layerInfo(out, "triangles").features, (long long)s.triangles);
}

TEST(SampleJob, IdsCountFromOneAndEqualTheFid) {
  const std::string out = test::tempDir() + "/tin.gpkg";
  runSampleJob(defaultDem(), out, {}, false, {});
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(out.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  for (const char* name : {"vertices", "triangles"}) {
    OGRLayer* layer = ds->GetLayerByName(name);
    long long expected = 1;
    for (auto& f : *layer) {
      ASSERT_EQ(f->GetFID(), expected);
      ASSERT_EQ(f->GetFieldAsInteger64("id"), expected);
      ++expected;
    }
  }
  // A triangle's corners are the vertices with those fids, at the same place.
  OGRLayer* triangles = ds->GetLayerByName("triangles");
  OGRLayer* vertices = ds->GetLayerByName("vertices");
  triangles->ResetReading();
  OGRFeature* t = triangles->GetNextFeature();
  const OGRLinearRing* ring = t->GetGeometryRef()->toPolygon()->getExteriorRing();
  for (int k = 0; k < 3; ++k) {
    OGRFeature* v = vertices->GetFeature(t->GetFieldAsInteger64(("v" + std::to_string(k)).c_str()));
    ASSERT_NE(v, nullptr);
    EXPECT_DOUBLE_EQ(v->GetGeometryRef()->toPoint()->getX(), ring->getX(k));
    OGRFeature::DestroyFeature(v);
  }
  OGRFeature::DestroyFeature(t);
  GDALClose(ds);
}

// A run killed outright (SIGKILL, power loss) leaves its staging folder; nobody holds its
// lock any more, so the next run for the same output removes it.
TEST(SampleJob, StagingFoldersOfKilledRunsAreRemoved) {
  const std::string dir = test::tempDir();
  const fs::path stale = dir + "/.tin.gpkg.tinlod-00000000deadbeef";
  fs::create_directories(stale);
  std::ofstream(stale / ".lock") << "";
  std::ofstream(stale / "tin.gpkg") << "left by a killed run";
  std::ofstream(stale / "tin.gpkg-journal") << "x";
  runSampleJob(defaultDem(), dir + "/tin.gpkg", {}, false, {});
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(SampleJob, SymlinkedOutputReplacesItsTarget) {
  const std::string dir = test::tempDir();
  fs::create_directories(dir + "/store");
  runSampleJob(defaultDem(), dir + "/store/tin.gpkg", {}, false, {});
  fs::create_symlink(dir + "/store/tin.gpkg", dir + "/link.gpkg");
  SampleOptions o;
  o.block = 6;
  const SampleSummary s = runSampleJob(defaultDem(), dir + "/link.gpkg", o, true, {});
  EXPECT_TRUE(fs::is_symlink(dir + "/link.gpkg"));
  EXPECT_EQ(layerInfo(dir + "/store/tin.gpkg", "triangles").features, (long long)s.triangles);
}

TEST(SampleJob, OutputThatIsAFolderOrNotAGeoPackageIsRefused) {
  const std::string dir = test::tempDir();
  fs::create_directories(dir + "/folder.gpkg");
  EXPECT_THROW(runSampleJob(defaultDem(), dir + "/folder.gpkg", {}, true, {}), Error);
  std::ofstream(dir + "/text.gpkg") << "hello";
  try {
    runSampleJob(defaultDem(), dir + "/text.gpkg", {}, true, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a GeoPackage"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find(".tmp-"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::readFile(dir + "/text.gpkg"), "hello");
  EXPECT_EQ(filesIn(dir), 2u);
}

TEST(SampleJob, JitterOfACellOrMoreIsRefused) {
  SampleOptions o;
  o.jitter = 25;  // the default DEM's cell size
  EXPECT_THROW(sampleTin(test::smallSyntheticDem(), o, ProgressRange(Feedback{}, 0, 1)), Error);
  o.jitter = 24;
  test::RecordingFeedback fb;
  EXPECT_NO_THROW(sampleTin(test::smallSyntheticDem(), o, ProgressRange(fb.feedback(), 0, 1)));
  EXPECT_TRUE(fb.warned("more than half the cell size"));
}

TEST(SampleJob, CancelWhileReplacingLeavesTheOldFileUntouched) {
  const std::string dir = test::tempDir();
  const std::string out = dir + "/tin.gpkg";
  runSampleJob(defaultDem(), out, {}, false, {});
  const std::string before = test::readFile(out);
  Feedback cancelling;
  cancelling.progress = [](double f, const std::string&) { return f < 0.8; };
  EXPECT_THROW(runSampleJob(defaultDem(), out, {}, true, cancelling), Cancelled);
  EXPECT_EQ(test::readFile(out), before);
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(SampleJob, BadOutputPathsFailBeforeAnyWork) {
  int calls = 0;
  Feedback counting;
  counting.progress = [&calls](double, const std::string&) { return ++calls > 0; };
  EXPECT_THROW(runSampleJob(defaultDem(), test::tempDir() + "/tin.shp", {}, false, counting), Error);
  EXPECT_THROW(runSampleJob(defaultDem(), test::tempDir() + "/no/such/dir/tin.gpkg", {}, false, counting), Error);
  SampleOptions bad;
  bad.block = 0;
  EXPECT_THROW(runSampleJob(defaultDem(), test::tempDir() + "/tin.gpkg", bad, false, counting), Error);
  EXPECT_EQ(calls, 0);
}

TEST(SampleJob, ProgressRisesToOne) {
  double last = -1;
  bool monotone = true;
  Feedback watching;
  watching.progress = [&](double f, const std::string&) {
    monotone = monotone && f >= last;
    last = f;
    return true;
  };
  runSampleJob(defaultDem(), test::tempDir() + "/tin.gpkg", {}, false, watching);
  EXPECT_TRUE(monotone);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

}  // namespace
}  // namespace tinlod
