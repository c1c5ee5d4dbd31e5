// SPDX-License-Identifier: GPL-3.0-or-later
// A catalogue's tiles read as one hierarchy: one vertex for each place, every level one
// conforming TIN covering what the tiles cover, and a varying level of detail across the
// tiles without a crack, where extracting each tile on its own leaves cracks.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "catalogue_hierarchy.h"
#include "catalogue_lod.h"
#include "tile_ownership.h"
#include "tin_outline.h"
#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/build_job.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/locate_job.h"
#include "tinlod/lod_job.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_reader.h"

namespace tinlod {
namespace {

const Feedback kQuiet;
const ProgressRange kRange(kQuiet, 0, 1);
constexpr int kTileSize = 120;  // the 360 x 300 small DEM: 3 x 3 tiles, the last row 60 cells high

struct BuiltTiles {
  std::string catalogue;
  std::vector<std::string> files;
};

void addField(OGRLayer& layer, const char* name, OGRFieldType type) {
  OGRFieldDefn field(name, type);
  ASSERT_EQ(layer.CreateField(&field), OGRERR_NONE);
}

// The tile's cells' extent, for the catalogue's geometry (read only by tinlod locate).
OGRPolygon tileBox(const Dem& dem, const CellWindow& cells) {
  const double x0 = dem.geotransform[0] + cells.xoff * dem.geotransform[1];
  const double y0 = dem.geotransform[3] + cells.yoff * dem.geotransform[5];
  const double x1 = x0 + cells.xsize * dem.geotransform[1], y1 = y0 + cells.ysize * dem.geotransform[5];
  OGRLinearRing ring;
  ring.addPoint(x0, y0), ring.addPoint(x1, y0), ring.addPoint(x1, y1), ring.addPoint(x0, y1), ring.addPoint(x0, y0);
  OGRPolygon box;
  box.addRing(&ring);
  return box;
}

// Every tile of a DEM built as tinlod tiles -selection tile builds them, and a catalogue as
// tinlod-tiles writes it: the fields the readers use, file names relative to the catalogue.
BuiltTiles buildCatalogue(const std::string& demFile, int tileSize, const std::string& dir) {
  BuiltTiles b;
  GDALAllRegister();
  const Dem dem = readDem(demFile, 1, kRange);
  b.catalogue = dir + "/catalogue.gpkg";
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(b.catalogue.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  ds->SetMetadataItem("TINLOD_KIND", "catalogue");
  OGRLayer& layer = *ds->CreateLayer("tiles", nullptr, wkbPolygon, nullptr);
  for (const char* name : {"tile_col", "tile_row", "xoff", "yoff", "xsize", "ysize"}) addField(layer, name, OFTInteger);
  for (const char* name : {"file", "status"}) addField(layer, name, OFTString);
  for (int c = 0; c < TileSpec::count(dem.width, tileSize); ++c)
    for (int r = 0; r < TileSpec::count(dem.height, tileSize); ++r) {
      const std::string name = "tile_" + std::to_string(c) + "_" + std::to_string(r) + ".gpkg";
      b.files.push_back(dir + "/" + name);
      runBuildJob(demFile, b.files.back(), SampleOptions{}, HierarchyOptions{}, true, kQuiet, AccuracyOutputs(),
                  HierarchyLayers(), TileSpec{tileSize, c, r});
      const CellWindow cells = tileWindow({dem.width, dem.height}, TileSpec{tileSize, c, r});
      OGRFeature f(layer.GetLayerDefn());
      f.SetField("tile_col", c), f.SetField("tile_row", r);
      f.SetField("xoff", cells.xoff), f.SetField("yoff", cells.yoff);
      f.SetField("xsize", cells.xsize), f.SetField("ysize", cells.ysize);
      f.SetField("file", name.c_str()), f.SetField("status", "done");
      OGRPolygon box = tileBox(dem, cells);
      f.SetGeometry(&box);
      EXPECT_EQ(layer.CreateFeature(&f), OGRERR_NONE);
    }
  GDALClose(ds);
  return b;
}

// The small synthetic DEM (its void and lake included) as 3 x 3 tiles.
const BuiltTiles& builtTiles() {
  static const BuiltTiles built = buildCatalogue(test::smallSyntheticDemFile(), kTileSize, test::tempDir());
  return built;
}

// A copy of the catalogue beside its tiles (which it names relative to its folder), named
// `name` and altered by the SQL statements `sql`, in order.
std::string alteredCatalogue(const std::string& name, const std::vector<std::string>& sql) {
  const std::string catalogue = std::filesystem::path(builtTiles().catalogue).parent_path().string() + "/" + name;
  std::filesystem::copy_file(builtTiles().catalogue, catalogue, std::filesystem::copy_options::overwrite_existing);
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(catalogue.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr));
  EXPECT_NE(ds, nullptr) << catalogue;
  if (!ds) return catalogue;
  for (const std::string& statement : sql) {
    // A statement that failed would leave the catalogue as it was: a test comparing the
    // altered one with the original would then pass on nothing.
    CPLErrorReset();
    ds->ExecuteSQL(statement.c_str(), nullptr, nullptr);
    EXPECT_EQ(CPLGetLastErrorType(), CE_None) << statement << ": " << CPLGetLastErrorMsg();
  }
  GDALClose(ds);
  return catalogue;
}

std::string alteredCatalogue(const std::string& name, const std::string& sql) {
  return alteredCatalogue(name, std::vector<std::string>{sql});
}


const StoredHierarchy& merged() {
  static const StoredHierarchy m = readHierarchyOrCatalogue(builtTiles().catalogue, kRange);
  return m;
}

Tin tinOf(const Hierarchy& h, const std::vector<std::uint32_t>& triangles) {
  Tin tin;
  tin.vertices = h.base.vertices;
  for (std::uint32_t t : triangles) tin.triangles.push_back(h.triangles[t].v);
  dropUnusedVertices(tin);
  return tin;
}

// Expects `tin` to be one conforming surface with the boundary loops of level 0 (the outline
// and the void's): a crack along a tile line is a loop of its own.
void expectOneSurfaceLikeLevelZero(const Tin& tin, const std::string& what, const Hierarchy& like = merged().hierarchy) {
  const test::Topology top = test::analyseTopology(tin);
  EXPECT_EQ(top.problem, "") << what;
  EXPECT_EQ(top.components, 1u) << what;
  EXPECT_EQ(top.boundaryLoops, test::analyseTopology(like.levelTin(0)).boundaryLoops) << what;
  EXPECT_EQ(top.eulerCharacteristic(), top.expectedEuler()) << what;
  EXPECT_EQ(test::verticesInsideTriangles(tin), 0u) << what << ": triangles overlap";
  EXPECT_EQ(test::clockwiseTriangles(tin), 0u) << what;
}

using Place = std::pair<double, double>;

TEST(CatalogueHierarchy, TilesBecomeOneHierarchyWithOneVertexForEachPlace) {
  const Hierarchy& h = merged().hierarchy;
  std::set<Place> places;
  std::size_t tileVertices = 0, tileTriangles = 0, tileGroups = 0;
  double maxError = 0;
  for (const std::string& file : builtTiles().files) {
    const Hierarchy tile = readHierarchy(file, kRange).hierarchy;
    for (const TinVertex& v : tile.base.vertices) places.insert({v.x, v.y});
    tileVertices += tile.base.vertices.size(), tileTriangles += tile.triangles.size(), tileGroups += tile.groups.size();
    maxError = std::max(maxError, tile.levels.back().maxError);
  }
  EXPECT_EQ(h.base.vertices.size(), places.size());
  EXPECT_GT(tileVertices - places.size(), 200u) << "the tiles share the vertices of their lines";
  EXPECT_EQ(h.triangles.size(), tileTriangles);
  EXPECT_EQ(h.groups.size(), tileGroups);
  EXPECT_EQ(h.levels.back().maxError, maxError);
  EXPECT_EQ(merged().info.path, builtTiles().catalogue);
  // Rows and columns are the whole raster's: each vertex has its cell's height.
  const Dem dem = test::smallSyntheticDem();
  for (const TinVertex& v : h.base.vertices) ASSERT_EQ(v.z, dem.at(v.row, v.col)) << "at " << v.x << ", " << v.y;
  // The groups of one vertex (one per tile on a line) delete it at the level it has.
  std::map<VertexId, int> groupsOf;
  for (const Group& g : h.groups) {
    ASSERT_EQ(g.level, h.vertexLevel[g.vertex] + 1);
    ++groupsOf[g.vertex];
  }
  std::size_t shared = 0;
  for (const auto& [v, n] : groupsOf) shared += n > 1;
  EXPECT_GT(shared, 20u) << "border vertices deleted in both tiles";
}

TEST(CatalogueHierarchy, EveryLevelIsOneConformingTin) {
  const Hierarchy& h = merged().hierarchy;
  ASSERT_EQ(h.coarsest(), 14);
  for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
    const Tin tin = h.levelTin(L);
    expectOneSurfaceLikeLevelZero(tin, "level " + std::to_string(L));
    EXPECT_EQ(h.levels[L].vertices, tin.vertices.size()) << "level " << L;
    EXPECT_EQ(h.levels[L].triangles, tin.triangles.size()) << "level " << L;
  }
  EXPECT_LT(h.levels.back().vertices, h.levels[0].vertices / 10);
}

TEST(CatalogueHierarchy, VaryingDetailAcrossTilesHasNoCrackWhereEachTileOnItsOwnHas) {
  const Dem dem = test::smallSyntheticDem();
  LodOptions o;
  // The corner four tiles share, and an error test whose two sides of a line differ.
  o.centres = {{dem.centreX(kTileSize), dem.centreY(kTileSize)}};
  o.dropoff = 60;
  o.maxError = 4, o.errorGrowth = 0.002;
  const Hierarchy& h = merged().hierarchy;
  const std::vector<std::uint32_t> lod = extractLod(h, o, kRange);
  expectOneSurfaceLikeLevelZero(tinOf(h, lod), "varying detail over the catalogue");
  std::set<std::int32_t> levels;
  for (std::uint32_t t : lod) levels.insert(h.triangles[t].firstLevel);
  EXPECT_TRUE(levels.count(0) && *levels.rbegin() >= 10) << "fine at the centre, coarse far away";

  // Each tile extracted on its own, put together: the sides of a line disagree.
  Tin apart;
  std::map<Place, VertexId> ids;
  for (const std::string& file : builtTiles().files) {
    const Hierarchy tile = readHierarchy(file, kRange).hierarchy;
    for (std::uint32_t t : extractLod(tile, o, kRange)) {
      Triangle out;
      for (int k = 0; k < 3; ++k) {
        const TinVertex& v = tile.base.vertices[tile.triangles[t].v[k]];
        const auto [it, added] = ids.try_emplace({v.x, v.y}, VertexId(apart.vertices.size()));
        if (added) apart.vertices.push_back(v);
        out[k] = it->second;
      }
      apart.triangles.push_back(out);
    }
  }
  EXPECT_GT(test::analyseTopology(apart).boundaryLoops, test::analyseTopology(h.levelTin(0)).boundaryLoops)
      << "tiles extracted apart should leave cracks, or this test shows nothing";
}

// A TIN's triangles by their corners' places (each triangle's corners in a canonical turn),
// to compare TINs whose vertices are numbered apart.
std::multiset<std::array<Place, 3>> trianglesByPlace(const Tin& tin) {
  std::multiset<std::array<Place, 3>> out;
  for (const Triangle& t : tin.triangles) {
    std::array<Place, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = {tin.vertices[t[k]].x, tin.vertices[t[k]].y};
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    out.insert(corners);
  }
  return out;
}

// Tile by tile against the tiles read as one hierarchy: the same triangles, the same
// vertices (rows, columns and heights) in the same order.
// A vertex on a line two tiles share is flagged `outline` when an edge of it has a
// triangle on one side only (the union's outline), not because it is on each tile's.
void expectSharedLineOutlineIsTheUnions(const Tin& tin, const std::string& what) {
  std::set<std::pair<VertexId, VertexId>> edges;
  for (const Triangle& t : tin.triangles)
    for (int k = 0; k < 3; ++k) edges.insert({t[k], t[(k + 1) % 3]});
  std::vector<bool> boundary(tin.vertices.size(), false);
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a})) boundary[a] = boundary[b] = true;
  std::size_t shared = 0, wrong = 0;
  for (std::size_t v = 0; v < tin.vertices.size(); ++v) {
    const TinVertex& p = tin.vertices[v];
    if ((p.row % kTileSize != 0 || p.row == 0) && (p.col % kTileSize != 0 || p.col == 0)) continue;
    ++shared;
    wrong += p.outline != boundary[v];
  }
  EXPECT_GT(shared, 0u) << what;
  EXPECT_EQ(wrong, 0u) << what << ": of " << shared << " vertices on shared lines";
}

void expectTheLodOfTheTilesReadAsOne(const std::string& catalogue, const Hierarchy& asOne, const LodOptions& o,
                                     const std::string& what, int* passes = nullptr) {
  const ExtractedLod tiles = extractCatalogueLod(catalogue, [&](const std::string&) { return o; }, kRange);
  const Tin whole = tinOf(asOne, extractLod(asOne, o, kRange));
  EXPECT_EQ(trianglesByPlace(tiles.tin), trianglesByPlace(whole)) << what;
  ASSERT_EQ(tiles.tin.vertices.size(), whole.vertices.size()) << what;
  for (std::size_t v = 0; v < whole.vertices.size(); ++v) {
    const TinVertex &a = tiles.tin.vertices[v], &b = whole.vertices[v];
    EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.row == b.row && a.col == b.col) << what << " vertex " << v;
  }
  EXPECT_EQ(tiles.firstLevel.size(), whole.triangles.size()) << what;
  expectOneSurfaceLikeLevelZero(tiles.tin, what, asOne);
  expectSharedLineOutlineIsTheUnions(tiles.tin, what);
  if (passes) *passes = tiles.passes;
}

TEST(CatalogueHierarchy, LodTileByTileIsThatOfTheTilesReadAsOne) {
  const Dem dem = test::smallSyntheticDem();
  const std::array<double, 2> corner{dem.centreX(kTileSize), dem.centreY(kTileSize)};  // four tiles meet there
  LodOptions byDistance, byError, byGrowingError;
  byDistance.centres = {corner}, byDistance.dropoff = 40;
  byError.maxError = 6;
  byGrowingError.centres = {corner}, byGrowingError.maxError = 4, byGrowingError.errorGrowth = 0.002;
  int passes = 0, most = 0;
  for (const auto& [o, what] : {std::pair{byDistance, "distance"}, std::pair{byError, "error"},
                                std::pair{byGrowingError, "growing error"}}) {
    expectTheLodOfTheTilesReadAsOne(builtTiles().catalogue, merged().hierarchy, o, what, &passes);
    most = std::max(most, passes);
  }
  // A vertex a tile brings back for its own needs makes the tile beside it bring it back too.
  EXPECT_GE(most, 2) << "no line vertex had to be exchanged: the test shows nothing";
}

// The rows of a lod output's layer in fid order: each feature's fields, then its geometry's
// points (x, y, z), as numbers.
std::vector<std::vector<double>> rowsOf(const std::string& path, const char* layerName) {
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  std::vector<std::vector<double>> rows;
  if (!ds) return rows;
  OGRLayer* layer = ds->GetLayerByName(layerName);
  for (auto& f : *layer) {
    std::vector<double> row{double(f->GetFID())};
    for (int i = 0; i < f->GetFieldCount(); ++i) row.push_back(f->GetFieldAsDouble(i));
    OGRGeometry* g = f->GetGeometryRef();
    const OGRSimpleCurve* ring = g && wkbFlatten(g->getGeometryType()) == wkbPolygon ? g->toPolygon()->getExteriorRing() : nullptr;
    if (g && wkbFlatten(g->getGeometryType()) == wkbPoint) row.insert(row.end(), {g->toPoint()->getX(), g->toPoint()->getY(), g->toPoint()->getZ()});
    for (int k = 0; ring && k < ring->getNumPoints(); ++k) row.insert(row.end(), {ring->getX(k), ring->getY(k), ring->getZ(k)});
    rows.push_back(row);
  }
  GDALClose(ds);
  return rows;
}

// The job's file against the extraction held whole: every row, ids, outline and levels.
// Returns the extraction's passes.
int expectTheJobWritesWhatTheExtractionHolds(const std::string& catalogue, const LodJobOptions& o) {
  const ExtractedLod whole = extractCatalogueLod(catalogue, [&](const std::string&) { return o.lod; }, kRange);
  const std::string dir = test::tempDir();
  const LodSummary s = runLodJob(catalogue, dir + "/lod.gpkg", o, false, kQuiet, true);
  EXPECT_EQ(s.vertices, whole.tin.vertices.size());
  EXPECT_EQ(s.triangles, whole.tin.triangles.size());
  std::size_t byLevel = 0;
  for (std::size_t n : s.trianglesPerLevel) byLevel += n;
  EXPECT_EQ(byLevel, whole.tin.triangles.size());
  EXPECT_EQ(s.trianglesPerLevel.size(), static_cast<std::size_t>(whole.coarsest) + 1);
  // Every row as the whole TIN would write it: ids, outline, levels, geometry.
  const auto vertices = rowsOf(dir + "/lod.gpkg", "vertices");
  const auto triangles = rowsOf(dir + "/lod.gpkg", "triangles");
  EXPECT_EQ(vertices.size(), whole.tin.vertices.size());
  EXPECT_EQ(triangles.size(), whole.tin.triangles.size());
  if (vertices.size() != whole.tin.vertices.size() || triangles.size() != whole.tin.triangles.size()) return whole.passes;
  std::size_t outline = 0;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const TinVertex& p = whole.tin.vertices[v];
    const std::vector<double> expected{double(v + 1), double(v + 1), double(p.row), double(p.col), double(p.outline),
                                       whole.vertexLevel[v], p.x, p.y, p.z};
    EXPECT_EQ(vertices[v], expected) << "vertex " << v;
    outline += p.outline;
  }
  EXPECT_GT(outline, 0u);
  // info shows the union's own outline, as it does for a single TIN's file (the flags above
  // are the sampler's, off the shared lines).
  const HierarchyInfo info = readHierarchyInfo(dir + "/lod.gpkg");
  EXPECT_EQ(info.levels.at(0).outlineVertices, countOutlineVertices(whole.tin));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& c = whole.tin.triangles[t];
    std::vector<double> expected{double(t + 1), double(t + 1), double(c[0] + 1), double(c[1] + 1), double(c[2] + 1),
                                 whole.firstLevel[t], whole.lastLevel[t]};
    for (int k = 0; k < 4; ++k) {
      const TinVertex& p = whole.tin.vertices[c[k % 3]];
      expected.insert(expected.end(), {p.x, p.y, p.z});
    }
    EXPECT_EQ(triangles[t], expected) << "triangle " << t;
  }
  // The tiles' parts waited beside the output, and nothing of them is left.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string(), "lod.gpkg");
  return whole.passes;
}

TEST(CatalogueHierarchy, LodJobWritesTheTilesAsTheyComeWhatTheExtractionHoldsWhole) {
  LodJobOptions o;
  o.lod.centres = {{test::smallSyntheticDem().centreX(kTileSize), test::smallSyntheticDem().centreY(kTileSize)}};
  o.lod.maxError = 4, o.lod.errorGrowth = 0.002;
  EXPECT_GE(expectTheJobWritesWhatTheExtractionHolds(builtTiles().catalogue, o), 2)
      << "no line vertex was exchanged: the shared vertices are not tested";
  // A tile failed beside the last one: the last tile's line vertices there are new, and on
  // the union's outline (their rows were still in the batch when the outline was set).
  expectTheJobWritesWhatTheExtractionHolds(
      alteredCatalogue("lod_failed.gpkg", "UPDATE tiles SET status = 'failed' WHERE tile_col = 2 AND tile_row = 1"), o);
}

TEST(CatalogueHierarchy, AccuracyOfACatalogueIsMeasuredOverAllItsTiles) {
  AccuracyOutputs outputs;
  outputs.options.reference = Reference::Dem;
  const AccuracyReport report = runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", kQuiet);
  const Hierarchy& h = merged().hierarchy;
  ASSERT_EQ(report.rows.size(), h.levels.size());
  const Dem dem = test::smallSyntheticDem();
  std::size_t valid = 0;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c) valid += dem.valid(r, c);
  for (const LevelAccuracy& row : report.rows) {
    EXPECT_EQ(row.vertices, h.levels[row.level].vertices);
    // Every valid cell centre level 0 covers, once: the tiles' lines are not counted twice.
    if (row.level == 0) EXPECT_GT(row.testPoints, valid * 98 / 100);
    EXPECT_LE(row.testPoints, valid);
    // The build measured every valid cell centre too: the same largest error.
    EXPECT_NEAR(row.maxAbsError, row.certifiedError, 1e-6) << "level " << row.level;
  }
  EXPECT_GT(report.rows.back().rmse, report.rows[1].rmse);
}

// Heights outside -valid_range are nodata, as in a whole run, and counted once at each
// test point in one warning, however the tiles' windows overlap.
TEST(CatalogueHierarchy, AccuracyTileByTileWarnsOnceOfHeightsOutsideTheValidRange) {
  const Dem dem = test::smallSyntheticDem();
  std::vector<float> heights;
  for (int r = 0; r < dem.height; ++r)
    for (int c = 0; c < dem.width; ++c)
      if (dem.valid(r, c)) heights.push_back(dem.at(r, c));
  std::sort(heights.begin(), heights.end());
  const HeightRange range{-100, double(heights[heights.size() * 95 / 100])};  // the highest 5 % out
  for (int step : {1, 2}) {
    std::size_t outside = 0;
    for (int r = 0; r < dem.height; r += step)
      for (int c = 0; c < dem.width; c += step) outside += dem.valid(r, c) && !range.contains(dem.at(r, c));
    ASSERT_GT(outside, 10u);
    AccuracyOutputs outputs;
    outputs.options.reference = Reference::Dem;
    outputs.options.step = step;
    test::RecordingFeedback fb;
    const AccuracyReport report =
        runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", fb.feedback(), range);
    std::size_t warnings = 0;
    for (const std::string& w : fb.warnings) warnings += test::contains(w, "with heights outside");
    EXPECT_EQ(warnings, 1u) << "step " << step;
    EXPECT_TRUE(fb.warned("ignored " + std::to_string(outside) + " test points of")) << "step " << step << ": "
                                                                                     << (fb.warnings.empty() ? "" : fb.warnings.back());
    // Those points are not measured: fewer than without the range.
    const AccuracyReport all = runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", kQuiet);
    EXPECT_LT(report.rows.front().testPoints, all.rows.front().testPoints);
  }
}

// A catalogue's tiles read as one hierarchy (`h`) and measured at once, as a whole run is.
AccuracyReport measuredAsOne(const std::string& demFile, const Hierarchy& h, const AccuracyOutputs& outputs) {
  const Dem dem = readDem(demFile, 1, kRange);
  const CrsTransform toTin = CrsTransform::forDem(dem, "", h.base.crsWkt, kRange);
  OutputFiles files(outputs.overwrite, {demFile});
  const AccuracyFiles staged = stageAccuracyFiles(outputs, files);
  AccuracyReport report = measureAndWrite(dem, h, toTin, outputs, staged, kRange);
  files.commit();
  return report;
}

// Equal but for the order of summing: `scale` is what the value's rounding is relative to.
void expectSum(double tiles, double whole, double scale, const std::string& what) {
  if (std::isnan(whole)) {
    EXPECT_TRUE(std::isnan(tiles)) << what;
    return;
  }
  EXPECT_NEAR(tiles, whole, 1e-9 * (std::fabs(whole) + std::fabs(scale)) + 1e-300) << what;
}

void expectSameRow(const LevelAccuracy& tiles, const LevelAccuracy& whole, const std::string& what) {
  EXPECT_EQ(tiles.vertices, whole.vertices) << what;
  EXPECT_EQ(tiles.triangles, whole.triangles) << what;
  EXPECT_EQ(tiles.testPoints, whole.testPoints) << what;
  EXPECT_EQ(tiles.certifiedError, whole.certifiedError) << what;
  EXPECT_EQ(tiles.maxAbsError, whole.maxAbsError) << what;
  EXPECT_EQ(tiles.maxErrorX, whole.maxErrorX) << what;
  EXPECT_EQ(tiles.maxErrorY, whole.maxErrorY) << what;
  expectSum(tiles.rmse, whole.rmse, 0, what + " rmse");
  expectSum(tiles.meanError, whole.meanError, whole.rmse, what + " mean error");
  expectSum(tiles.moransI, whole.moransI, 1, what + " Moran's I");
  ASSERT_EQ(tiles.variables.size(), whole.variables.size()) << what;
  for (std::size_t k = 0; k < whole.variables.size(); ++k) {
    const VariableComparison &a = tiles.variables[k], &b = whole.variables[k];
    const std::string name = what + " " + b.name;
    EXPECT_EQ(a.name, b.name) << name;
    EXPECT_EQ(a.count, b.count) << name;
    expectSum(a.correlation, b.correlation, 1, name + " r");
    expectSum(a.meanReference, b.meanReference, b.stdReference, name + " mean");
    expectSum(a.meanSimplified, b.meanSimplified, b.stdSimplified, name + " mean");
    expectSum(a.stdReference, b.stdReference, 0, name + " std");
    expectSum(a.stdSimplified, b.stdSimplified, 0, name + " std");
  }
}

TEST(CatalogueHierarchy, AccuracyTileByTileIsThatOfTheTilesReadAsOne) {
  struct Case {
    Reference reference;
    int step, control;
  };
  // Steps that do and do not divide the tile size; the B-spline reaching 2 to 10 points
  // beyond a tile.
  for (const Case& c : {Case{Reference::Dem, 1, 3}, Case{Reference::Tin, 1, 5}, Case{Reference::Dem, 7, 2},
                        Case{Reference::Tin, 2, 1}}) {
    AccuracyOutputs outputs;
    outputs.options.reference = c.reference, outputs.options.step = c.step, outputs.options.controlSpacing = c.control;
    const AccuracyReport tiles = runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", kQuiet);
    const AccuracyReport whole = measuredAsOne(test::smallSyntheticDemFile(), merged().hierarchy, outputs);
    ASSERT_EQ(tiles.rows.size(), whole.rows.size());
    for (std::size_t L = 0; L < whole.rows.size(); ++L)
      expectSameRow(tiles.rows[L], whole.rows[L],
                    referenceName(c.reference) + " step " + std::to_string(c.step) + " control " +
                        std::to_string(c.control) + " level " + std::to_string(L));
    EXPECT_GT(whole.rows.back().testPoints, 0u);
    EXPECT_GT(whole.rows.back().variables[3].count, 0u) << "curvature is compared";
  }
}

TEST(CatalogueHierarchy, AccuracyTileByTileReportsTheLargestErrorWhereTheWholeRasterDoesOnTies) {
  // A DEM flat at 0 m with two pits 10 m deep at cells no block samples (sampling depends
  // on the seed and the block alone): every level is flat at 0 m and misses both by exactly
  // 10 m (planes through heights other than 0 would round). Pit A (row 10, in tile 1,0)
  // comes first in the raster's rows; pit B (row 122, in tile 0,1) comes first in the
  // catalogue's tiles, which are measured down each column of tiles first, and in its own
  // tile's rows (row 2 or 3 of it), so neither the tiles' order nor a tile's own rows can
  // stand for the raster's.
  const std::string dir = test::tempDir();
  const std::string dem = dir + "/pits.tif";
  const auto flat = [](const std::vector<std::array<int, 2>>& pits) {
    return test::makeDem(360, 300, 25, [pits](int r, int c) {
      for (const auto& p : pits)
        if (p[0] == r && p[1] == c) return -10.0f;
      return 0.0f;
    });
  };
  writeDemGeoTiff(flat({}), dem);
  std::set<std::array<int, 2>> sampled;
  for (const TinVertex& v : readHierarchyOrCatalogue(buildCatalogue(dem, kTileSize, dir).catalogue, kRange).hierarchy.base.vertices)
    sampled.insert({v.row, v.col});
  const auto unsampledFrom = [&](int row, int col) {
    while (sampled.count({row, col})) ++col;
    return std::array<int, 2>{row, col};
  };
  const std::array<int, 2> a = unsampledFrom(10, 150), b = unsampledFrom(122, 30);
  writeDemGeoTiff(flat({a, b}), dem);
  const std::string tilesDir = test::tempDir();
  const BuiltTiles built = buildCatalogue(dem, kTileSize, tilesDir);
  AccuracyOutputs outputs;
  outputs.options.reference = Reference::Dem;
  const AccuracyReport tiles = runAccuracyJob(dem, built.catalogue, outputs, 0, "", kQuiet);
  const AccuracyReport whole = measuredAsOne(dem, readHierarchyOrCatalogue(built.catalogue, kRange).hierarchy, outputs);
  ASSERT_EQ(tiles.rows.size(), whole.rows.size());
  const Dem header = readDem(dem, 1, kRange);
  for (std::size_t L = 0; L < whole.rows.size(); ++L) {
    const std::string what = "level " + std::to_string(L);
    EXPECT_EQ(tiles.rows[L].maxAbsError, 10) << what;
    EXPECT_EQ(tiles.rows[L].maxErrorX, header.geotransform[0] + (a[1] + 0.5) * 25) << what;
    EXPECT_EQ(tiles.rows[L].maxErrorY, header.geotransform[3] - (a[0] + 0.5) * 25) << what;
    EXPECT_EQ(tiles.rows[L].testPoints, whole.rows[L].testPoints) << what;
    EXPECT_EQ(tiles.rows[L].maxAbsError, whole.rows[L].maxAbsError) << what;
    EXPECT_EQ(tiles.rows[L].maxErrorX, whole.rows[L].maxErrorX) << what;
    EXPECT_EQ(tiles.rows[L].maxErrorY, whole.rows[L].maxErrorY) << what;
  }
}

TEST(CatalogueHierarchy, AccuracyTileByTileOnRealDemsIsThatOfTheTilesReadAsOne) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  // A geographic DEM (its TIN in UTM, where a window's edges bend) and one stored bottom-up;
  // both with a last column or row of tiles narrower than the reach of the B-spline. And
  // one with sea (nodata) along tile lines, where a line vertex may be in one tile only.
  for (const std::string name : {"fort_worth_3s.tif", "bavaria_dgm5_bottomup.tif", "vancouver_N49W123.tif"}) {
    const std::string file = data + "/" + name;
    const BuiltTiles built = buildCatalogue(file, kTileSize, test::tempDir());
    AccuracyOutputs outputs;
    outputs.options.reference = Reference::Dem;
    const AccuracyReport tiles = runAccuracyJob(file, built.catalogue, outputs, 0, "", kQuiet);
    const AccuracyReport whole = measuredAsOne(file, readHierarchyOrCatalogue(built.catalogue, kRange).hierarchy, outputs);
    ASSERT_EQ(tiles.rows.size(), whole.rows.size()) << name;
    for (std::size_t L = 0; L < whole.rows.size(); ++L)
      expectSameRow(tiles.rows[L], whole.rows[L], name + " level " + std::to_string(L));
    EXPECT_GT(whole.rows.back().testPoints, 10000u) << name;
  }
}

TEST(CatalogueHierarchy, LodTileByTileOnARealDemIsThatOfTheTilesReadAsOne) {
  const std::string data = test::dataDir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  const std::string file = data + "/fort_worth_3s.tif";
  const BuiltTiles built = buildCatalogue(file, kTileSize, test::tempDir());
  const Hierarchy asOne = readHierarchyOrCatalogue(built.catalogue, kRange).hierarchy;
  const Tin level0 = asOne.levelTin(0);
  double x = 0, y = 0;  // a centre in the middle of the data
  for (const TinVertex& v : level0.vertices) x += v.x / level0.vertices.size(), y += v.y / level0.vertices.size();
  LodOptions o;
  o.centres = {{x, y}}, o.dropoff = 500, o.maxError = 3, o.errorGrowth = 0.001;
  expectTheLodOfTheTilesReadAsOne(built.catalogue, asOne, o, "fort_worth_3s");
}

// The band's values, nodata as NaN.
std::vector<float> bandValues(const std::string& path, int band) {
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  EXPECT_NE(ds, nullptr) << path;
  if (!ds) return {};
  GDALRasterBand* b = ds->GetRasterBand(band);
  std::vector<float> values(static_cast<std::size_t>(ds->GetRasterXSize()) * ds->GetRasterYSize());
  EXPECT_EQ(b->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(), ds->GetRasterYSize(), values.data(), ds->GetRasterXSize(),
                        ds->GetRasterYSize(), GDT_Float32, 0, 0),
            CE_None);
  int hasNodata = 0;
  const double nodata = b->GetNoDataValue(&hasNodata);
  EXPECT_TRUE(hasNodata) << path;
  for (float& v : values)
    if (v == float(nodata)) v = std::nanf("");
  GDALClose(ds);
  return values;
}

// A band's STATISTICS_* item as a number (NaN when absent).
double statistic(const std::string& path, int band, const char* name) {
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!ds) return std::nan("");
  const char* value = ds->GetRasterBand(band)->GetMetadataItem(name);
  const double v = value ? std::atof(value) : std::nan("");
  GDALClose(ds);
  return v;
}

// Every pixel of the four bands the same, and their statistics GDAL's own of the whole band.
void expectSameRaster(const std::string& tilesFile, const std::string& wholeFile, const std::string& what) {
  for (int band = 1; band <= 4; ++band) {
    const std::vector<float> tiles = bandValues(tilesFile, band), whole = bandValues(wholeFile, band);
    ASSERT_EQ(tiles.size(), whole.size());
    std::size_t valid = 0, differing = 0;
    for (std::size_t i = 0; i < whole.size(); ++i) {
      valid += !std::isnan(whole[i]);
      differing += std::isnan(whole[i]) != std::isnan(tiles[i]) || (!std::isnan(whole[i]) && tiles[i] != whole[i]);
    }
    EXPECT_EQ(differing, 0u) << what << " band " << band;
    EXPECT_GT(valid, whole.size() / 2) << what << " band " << band;
    // The statistics summed as the windows were written are GDAL's own of the whole band.
    for (const char* name : {"STATISTICS_MINIMUM", "STATISTICS_MAXIMUM", "STATISTICS_VALID_PERCENT"})
      EXPECT_EQ(statistic(tilesFile, band, name), statistic(wholeFile, band, name)) << what << " band " << band << " " << name;
    for (const char* name : {"STATISTICS_MEAN", "STATISTICS_STDDEV"}) {
      const double w = statistic(wholeFile, band, name);
      EXPECT_NEAR(statistic(tilesFile, band, name), w, 1e-9 * std::fabs(w)) << what << " band " << band << " " << name;
    }
  }
}

TEST(CatalogueHierarchy, AccuracyRasterTileByTileIsThatOfTheTilesReadAsOne) {
  const std::string dir = test::tempDir();
  AccuracyOutputs outputs;
  outputs.options.reference = Reference::Dem;
  outputs.rasterLevel = 5;
  outputs.overwrite = true;
  outputs.rasterPath = dir + "/whole.tif";
  measuredAsOne(test::smallSyntheticDemFile(), merged().hierarchy, outputs);
  // Copied a band of rows at a time (GTiff, striped or in tiles of 64 rows compressed) and
  // by GDAL's CreateCopy (COG, which GDAL cannot write in pieces).
  struct Format {
    const char* name;
    std::vector<std::string> options;
  };
  for (const Format& format : {Format{"GTiff", {}}, Format{"GTiff", {"TILED=YES", "BLOCKYSIZE=64", "COMPRESS=DEFLATE"}},
                               Format{"COG", {}}}) {
    outputs.raster.format = format.name, outputs.raster.creationOptions = format.options;
    outputs.rasterPath = dir + "/tiles.tif";
    runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", kQuiet);
    expectSameRaster(dir + "/tiles.tif", dir + "/whole.tif",
                     std::string(format.name) + (format.options.empty() ? "" : " " + format.options.back()));
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/tiles.tif.canvas.tif"));
}

TEST(CatalogueHierarchy, AccuracyRasterTileByTileIsThatOfTheTilesReadAsOneOverManyStripsOfRows) {
  // Tiles 300 cells high, measured in strips of rows that end on the raster's block rows
  // (256): the void (rows 295 to 344) begins in the second strip of the first tile, where
  // the strip before had values in those rows of the bands.
  const std::string dir = test::tempDir();
  SyntheticDemOptions o;
  o.width = 360, o.height = 800, o.cellSize = 25;
  const std::string dem = dir + "/tall.tif";
  writeDemGeoTiff(makeSyntheticDem(o), dem);
  const BuiltTiles built = buildCatalogue(dem, 300, dir);
  AccuracyOutputs outputs;
  outputs.options.reference = Reference::Dem;
  outputs.rasterLevel = 5;
  outputs.overwrite = true;
  outputs.rasterPath = dir + "/whole.tif";
  const AccuracyReport whole = measuredAsOne(dem, readHierarchyOrCatalogue(built.catalogue, kRange).hierarchy, outputs);
  outputs.rasterPath = dir + "/tiles.tif";
  const AccuracyReport tiles = runAccuracyJob(dem, built.catalogue, outputs, 0, "", kQuiet);
  expectSameRaster(dir + "/tiles.tif", dir + "/whole.tif", "tiles of 300");
  ASSERT_EQ(tiles.rows.size(), whole.rows.size());
  for (std::size_t L = 0; L < whole.rows.size(); ++L) expectSameRow(tiles.rows[L], whole.rows[L], "level " + std::to_string(L));
}

TEST(CatalogueHierarchy, AccuracyTileByTileStopsOnCancelAndLeavesNothing) {
  // Cancelled at 30 %, 60 % and 99 %: in a tile's levels, between tiles, writing the raster.
  for (const double stop : {0.3, 0.6, 0.99}) {
    const std::string dir = test::tempDir() + "/cancel_" + std::to_string(int(stop * 100));
    std::filesystem::create_directories(dir);
    AccuracyOutputs outputs;
    outputs.rasterPath = dir + "/acc.tif";
    outputs.reportPath = dir + "/acc.json";
    Feedback cancelling;
    double reached = 0;
    cancelling.progress = [&](double f, const std::string&) {
      reached = std::max(reached, f);
      return f < stop;
    };
    EXPECT_THROW(runAccuracyJob(test::smallSyntheticDemFile(), builtTiles().catalogue, outputs, 0, "", cancelling),
                 Cancelled);
    EXPECT_LT(reached, stop + 0.05) << "stopped promptly";
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "nothing left at " << stop;
  }
}

TEST(CatalogueHierarchy, AccuracyOfACatalogueThatDoesNotRecordItsTilesCellsIsRefused) {
  const std::string catalogue = alteredCatalogue("no_sizes.gpkg", "UPDATE tiles SET xsize = NULL, ysize = NULL");
  try {
    runAccuracyJob(test::smallSyntheticDemFile(), catalogue, AccuracyOutputs{}, 0, "", kQuiet);
    FAIL() << "measured without knowing the tiles' cells";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "xsize and ysize")) << e.what();
    EXPECT_TRUE(test::contains(e.what(), "tinlod tiles")) << e.what();
  }
}

TEST(CatalogueHierarchy, WithATileUnfinishedTileByTileIsStillTheRestReadAsOne) {
  // The middle tile failed: the others meet a hole in the tiles, not a neighbour. Where it
  // lies, the raster has the reference's curvature (band 3) where its surface reaches, and
  // nodata in the other bands, as the tiles read as one give.
  const std::string catalogue =
      alteredCatalogue("middle_failed.gpkg", "UPDATE tiles SET status = 'failed' WHERE tile_col = 1 AND tile_row = 1");
  const Hierarchy asOne = readHierarchyOrCatalogue(catalogue, kRange).hierarchy;
  struct Case {
    Reference reference;
    int step;
  };
  for (const Case& c : {Case{Reference::Dem, 1}, Case{Reference::Tin, 1}, Case{Reference::Dem, 2}}) {
    const std::string what = std::string(c.reference == Reference::Dem ? "dem" : "tin") + " step " + std::to_string(c.step);
    const std::string dir = test::tempDir();
    AccuracyOutputs outputs;
    outputs.options.reference = c.reference;
    outputs.options.step = c.step;
    outputs.rasterLevel = 2;
    outputs.overwrite = true;
    outputs.rasterPath = dir + "/tiles.tif";
    const AccuracyReport tiles = runAccuracyJob(test::smallSyntheticDemFile(), catalogue, outputs, 0, "", kQuiet);
    outputs.rasterPath = dir + "/whole.tif";
    const AccuracyReport whole = measuredAsOne(test::smallSyntheticDemFile(), asOne, outputs);
    ASSERT_EQ(tiles.rows.size(), whole.rows.size()) << what;
    for (std::size_t L = 0; L < whole.rows.size(); ++L)
      expectSameRow(tiles.rows[L], whole.rows[L], what + " level " + std::to_string(L));
    expectSameRaster(dir + "/tiles.tif", dir + "/whole.tif", "middle tile failed, " + what);
  }
  const std::vector<std::uint32_t> all = extractLod(asOne, LodOptions{{}, std::nan(""), 6}, kRange);
  const Tin whole0 = tinOf(asOne, all);
  const ExtractedLod apart =
      extractCatalogueLod(catalogue, [](const std::string&) { return LodOptions{{}, std::nan(""), 6}; }, kRange);
  EXPECT_EQ(trianglesByPlace(apart.tin), trianglesByPlace(whole0));
  EXPECT_EQ(apart.tin.vertices.size(), whole0.vertices.size());
}

TEST(CatalogueHierarchy, InfoCountsTheTilesByStatusAndAddsUpTheFinishedTilesLevels) {
  // The middle tile failed, with a message in the error field tinlod-tiles writes.
  const std::string catalogue = alteredCatalogue(
      "info_failed.gpkg", std::vector<std::string>{"ALTER TABLE tiles ADD COLUMN error TEXT",
                                                   "UPDATE tiles SET status = 'failed', error = 'tinlod was killed by "
                                                   "signal 9' WHERE tile_col = 1 AND tile_row = 1"});
  const HierarchyInfo info = readHierarchyInfo(catalogue);
  EXPECT_EQ(info.kind, "catalogue");
  EXPECT_EQ(info.tileStatuses, (std::map<std::string, std::size_t>{{"done", 8}, {"failed", 1}}));
  EXPECT_EQ(info.failedTiles, std::vector<std::string>{"1,1: tinlod was killed by signal 9"});
  std::vector<LevelStats> expected;
  std::uintmax_t bytes = 0;
  for (const std::string& file : builtTiles().files) {
    if (file.find("tile_1_1.gpkg") != std::string::npos) continue;
    const HierarchyInfo tile = readHierarchyInfo(file);
    bytes += tile.bytes;
    if (expected.empty()) expected.resize(tile.levels.size());
    ASSERT_EQ(tile.levels.size(), expected.size()) << file;
    for (std::size_t L = 0; L < expected.size(); ++L) {
      expected[L].vertices += tile.levels[L].vertices, expected[L].triangles += tile.levels[L].triangles;
      expected[L].deleted += tile.levels[L].deleted, expected[L].cells += tile.levels[L].cells;
      expected[L].maxError = std::max(expected[L].maxError, tile.levels[L].maxError);
    }
  }
  EXPECT_EQ(info.tileBytes, bytes);
  ASSERT_EQ(info.levels.size(), expected.size());
  for (std::size_t L = 0; L < expected.size(); ++L) {
    EXPECT_EQ(info.levels[L].vertices, expected[L].vertices) << L;
    EXPECT_EQ(info.levels[L].triangles, expected[L].triangles) << L;
    EXPECT_EQ(info.levels[L].deleted, expected[L].deleted) << L;
    EXPECT_EQ(info.levels[L].cells, expected[L].cells) << L;
    EXPECT_EQ(info.levels[L].maxError, expected[L].maxError) << L;
    EXPECT_EQ(info.levels[L].outlineVertices, 0u) << L;
  }
  const std::string text = toText(info);
  EXPECT_NE(text.find(": tinlod catalogue, "), std::string::npos) << text;
  EXPECT_NE(text.find("; 9 tiles (8 done, 1 failed), "), std::string::npos) << text;
  EXPECT_NE(text.find("\n  failed tile 1,1: tinlod was killed by signal 9\n"), std::string::npos) << text;
  const std::string json = toJson(info);
  EXPECT_NE(json.find("\"tiles\": {\"done\": 8, \"failed\": 1}"), std::string::npos) << json;
  EXPECT_NE(json.find("\"failed_tiles\": [\"1,1: tinlod was killed by signal 9\"]"), std::string::npos) << json;
}

TEST(CatalogueHierarchy, InfoOfACatalogueHasTheTrianglesAndLargestErrorsOfItsTilesReadAsOne) {
  const HierarchyInfo info = readHierarchyInfo(builtTiles().catalogue);
  const std::vector<LevelStats>& asOne = merged().hierarchy.levels;
  ASSERT_EQ(info.levels.size(), asOne.size());
  for (std::size_t L = 0; L < asOne.size(); ++L) {
    EXPECT_EQ(info.levels[L].triangles, asOne[L].triangles) << L;
    EXPECT_EQ(info.levels[L].maxError, asOne[L].maxError) << L;
    EXPECT_NEAR(info.levels[L].rmse, asOne[L].rmse, 1e-9 * asOne[L].rmse) << L;
    // The vertices of the tiles' shared lines are counted in each tile that holds them.
    EXPECT_GT(info.levels[L].vertices, asOne[L].vertices) << L;
  }
}

TEST(CatalogueHierarchy, InfoNamesAFinishedTileItCannotRead) {
  const std::string catalogue =
      alteredCatalogue("info_missing.gpkg", "UPDATE tiles SET file = 'gone.gpkg' WHERE tile_col = 0 AND tile_row = 1");
  // The other 8 tiles are described; the lost one is named with the fix.
  const HierarchyInfo info = readHierarchyInfo(catalogue);
  ASSERT_EQ(info.unreadableTiles.size(), 1u);
  const std::string& message = info.unreadableTiles.front();
  EXPECT_EQ(message.rfind("tile 0,1's file '", 0), 0u) << message;
  EXPECT_NE(message.find("gone.gpkg' does not exist: the catalogue names its tiles' files relative to itself"),
            std::string::npos)
      << message;
  const HierarchyInfo whole = readHierarchyInfo(builtTiles().catalogue);
  EXPECT_TRUE(whole.unreadableTiles.empty());
  ASSERT_EQ(info.levels.size(), whole.levels.size());
  EXPECT_EQ(info.tileStatuses, whole.tileStatuses);
  EXPECT_LT(info.levels[0].triangles, whole.levels[0].triangles);
  EXPECT_GT(info.levels[0].triangles, whole.levels[0].triangles * 7 / 9);
  EXPECT_NE(toText(info).find("  unreadable: tile 0,1's file"), std::string::npos) << toText(info);
  EXPECT_NE(toJson(info).find("\"unreadable_tiles\": [\"tile 0,1's file"), std::string::npos) << toJson(info);
  // A reader of one hierarchy given the catalogue says what it is.
  const std::string asFile = test::errorOf([&] { readHierarchy(builtTiles().catalogue, kRange); });
  EXPECT_NE(asFile.find("is a tinlod-tiles catalogue, not the hierarchy of one tile"), std::string::npos) << asFile;
}

// A points file (in the tiles' CRS) of the 9 tiles' centres, round and round three times;
// `tiles` gets each point's tile name.
std::string tileCentresRoundAndRound(const std::string& dir, std::vector<std::string>& tiles) {
  GDALDataset* catalogue = static_cast<GDALDataset*>(
      GDALOpenEx(builtTiles().catalogue.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  std::vector<std::pair<OGRPoint, std::string>> centres;
  for (auto& f : *catalogue->GetLayerByName("tiles")) {
    OGRPoint centre;
    f->GetGeometryRef()->Centroid(&centre);
    centres.emplace_back(centre, std::to_string(f->GetFieldAsInteger("tile_col")) + "," +
                                     std::to_string(f->GetFieldAsInteger("tile_row")));
  }
  GDALClose(catalogue);
  EXPECT_EQ(centres.size(), 9u);
  const std::string points = dir + "/round.gpkg";
  OGRSpatialReference crs;  // the tiles' (a GeoPackage layer without one is taken as geographic)
  crs.importFromWkt(merged().hierarchy.base.crsWkt.c_str());
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(points.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRLayer* layer = ds->CreateLayer("points", &crs, wkbPoint, nullptr);
  addField(*layer, "n", OFTInteger);
  for (int n = 0; n < 27; ++n) {
    OGRFeature f(layer->GetLayerDefn());
    f.SetField("n", n);
    f.SetGeometry(&centres[n % 9].first);
    EXPECT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
    tiles.push_back(centres[n % 9].second);
  }
  GDALClose(ds);
  return points;
}

TEST(CatalogueHierarchy, JobsOnACatalogueWithUnfinishedTilesSayHowMany) {
  const std::string catalogue = alteredCatalogue(
      "two_unfinished.gpkg",
      std::vector<std::string>{"UPDATE tiles SET status = 'failed' WHERE tile_col = 1 AND tile_row = 1",
                               "UPDATE tiles SET status = 'pending' WHERE tile_col = 2 AND tile_row = 0",
                               "UPDATE tiles SET status = 'empty' WHERE tile_col = 0 AND tile_row = 2"});
  const std::string expected =
      "2 of the catalogue's 9 tiles are not finished (1 failed, 1 pending): only the finished tiles are read; "
      "run tinlod tiles again to finish them";
  EXPECT_EQ(unfinishedTilesWarning(catalogue), expected);
  EXPECT_EQ(unfinishedTilesWarning(builtTiles().catalogue), "");
  const std::string dir = test::tempDir();
  test::RecordingFeedback lod, accuracy;
  LodJobOptions o;
  o.lod.maxError = 6;
  runLodJob(catalogue, dir + "/lod.gpkg", o, false, lod.feedback());
  AccuracyOutputs report;
  report.reportPath = dir + "/report.json";
  runAccuracyJob(test::smallSyntheticDemFile(), catalogue, report, 0, "", accuracy.feedback());
  std::vector<std::string> tiles;
  test::RecordingFeedback locate;
  runLocateJob(catalogue, tileCentresRoundAndRound(dir, tiles), dir + "/located.gpkg", 0, false, locate.feedback());
  EXPECT_TRUE(lod.warned(expected));
  EXPECT_TRUE(accuracy.warned(expected));
  EXPECT_TRUE(locate.warned(expected));
  // What they write says so too, wherever it is read later.
  const std::string note = "2 of the catalogue's 9 tiles are not finished (1 failed, 1 pending): the finished tiles alone";
  for (const char* out : {"/lod.gpkg", "/located.gpkg"}) {
    GDALDataset* ds = static_cast<GDALDataset*>(
        GDALOpenEx((dir + out).c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr) << out;
    const char* item = ds->GetMetadataItem("TINLOD_UNFINISHED_TILES");
    EXPECT_EQ(std::string(item ? item : ""), note) << out;
    GDALClose(ds);
  }
  std::ifstream json(dir + "/report.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(test::contains(text, "(" + note + ")")) << text.substr(0, 300);
}

TEST(CatalogueHierarchy, LocateReadsEachTileOnceWhateverTheOrderOfThePoints) {
  // With a few tiles kept, points in this order would read a tile for every point (27), not 9.
  const std::string dir = test::tempDir();
  std::vector<std::string> tiles;
  const std::string points = tileCentresRoundAndRound(dir, tiles);
  const LocateSummary s = runLocateJob(builtTiles().catalogue, points, dir + "/located.gpkg", 1, false, kQuiet);
  EXPECT_EQ(s.tilesRead, 9u);
  EXPECT_EQ(s.located, 27u);
  // Written in the points' own order, each with its tile and that tile's height there.
  GDALDataset* out = static_cast<GDALDataset*>(
      GDALOpenEx((dir + "/located.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  ASSERT_NE(out, nullptr);
  int n = 0;
  std::map<std::string, double> heights;
  for (auto& f : *out->GetLayerByName("points")) {
    EXPECT_EQ(f->GetFieldAsInteger("n"), n);
    EXPECT_EQ(f->GetFieldAsString("tile"), tiles[n]) << n;
    const auto [it, first] = heights.emplace(tiles[n], f->GetFieldAsDouble("elevation"));
    if (!first) EXPECT_EQ(f->GetFieldAsDouble("elevation"), it->second) << n;
    ++n;
  }
  GDALClose(out);
  EXPECT_EQ(n, 27);
}

TEST(CatalogueHierarchy, LocateOnACatalogueStopsOnCancelBeforeReadingTheNextTile) {
  const std::string dir = test::tempDir();
  std::vector<std::string> tiles;
  const std::string points = tileCentresRoundAndRound(dir, tiles);
  std::filesystem::create_directories(dir + "/out");
  Feedback cancelling;
  int asked = 0;  // the tiles read before the stop: the first (to open the catalogue) only
  cancelling.progress = [&](double f, const std::string&) { return f < 0.4 || ++asked < 2; };
  EXPECT_THROW(runLocateJob(builtTiles().catalogue, points, dir + "/out/located.gpkg", 0, false, cancelling), Cancelled);
  EXPECT_EQ(asked, 2);
  EXPECT_TRUE(std::filesystem::is_empty(dir + "/out"));
}

TEST(CatalogueHierarchy, LodOfACatalogueStopsOnCancelAndLeavesNothing) {
  const std::string dir = test::tempDir() + "/lod_cancel";
  std::filesystem::create_directories(dir);
  LodJobOptions o;
  o.lod.maxError = 6;
  Feedback cancelling;
  cancelling.progress = [](double f, const std::string&) { return f < 0.5; };
  EXPECT_THROW(runLodJob(builtTiles().catalogue, dir + "/lod.gpkg", o, false, cancelling), Cancelled);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(TileOwnership, EveryCellHasOneOwnerAmongThePresentTilesOrElseAmongTheMissingOnes) {
  // 4 x 3 tiles, the last column and row narrower; then the last only 2 cells across and down.
  for (const auto& [width, height] : {std::pair{100, 70}, std::pair{92, 62}}) {
    const int size = 30;
    std::vector<CatalogueTile> all;
    for (int c = 0; c < TileSpec::count(width, size); ++c)
      for (int r = 0; r < TileSpec::count(height, size); ++r) {
        const CellWindow w = tileWindow({width, height}, TileSpec{size, c, r});
        CatalogueTile t;
        t.name = std::to_string(c) + "," + std::to_string(r);
        t.xoff = w.xoff, t.yoff = w.yoff, t.xsize = w.xsize, t.ysize = w.ysize;
        all.push_back(t);
      }
    std::mt19937 rng(5);
    for (int trial = 0; trial < 60; ++trial) {
      std::vector<CatalogueTile> present, missing;
      for (const CatalogueTile& t : all) (trial == 0 || rng() % 3 != 0 ? present : missing).push_back(t);
      if (present.empty()) continue;
      std::vector<int> owners(width * height, 0), holders(width * height, 0);
      // Counts the cells of `rects`, each of which must lie in tile t.
      const auto count = [&](const CatalogueTile& t, const std::vector<CellRect>& rects, std::vector<int>& counts) {
        const CellRect held{t.xoff, t.yoff, t.xoff + t.xsize, t.yoff + t.ysize};
        for (const CellRect& rect : rects)
          for (int r = rect.row0; r < rect.row1; ++r)
            for (int c = rect.col0; c < rect.col1; ++c) {
              ASSERT_TRUE(held.contains(c, r)) << "tile " << t.name << " is given a cell it does not hold";
              ++counts[r * width + c];
            }
      };
      // The missing tiles' cells (measured for the reference's surface alone): every cell of
      // the raster is then either a present tile's or a missing tile's, once.
      std::vector<int> left(width * height, 0);
      for (std::size_t m = 0; m < missing.size(); ++m) count(missing[m], cellsLeftBy(present, missing, m), left);
      for (std::size_t i = 0; i < present.size(); ++i) {
        const CatalogueTile& t = present[i];
        count(t, {{t.xoff, t.yoff, t.xoff + t.xsize, t.yoff + t.ysize}}, holders);
        count(t, ownedCells(present, i), owners);
      }
      ASSERT_FALSE(HasFatalFailure()) << "trial " << trial;  // a cell outside its tile, above
      for (int cell = 0; cell < width * height; ++cell) {
        ASSERT_EQ(owners[cell], holders[cell] > 0 ? 1 : 0)
            << "trial " << trial << ", cell " << cell % width << "," << cell / width;
        ASSERT_EQ(left[cell], holders[cell] > 0 ? 0 : 1)
            << "trial " << trial << ", cell " << cell % width << "," << cell / width;
      }
    }
  }
}

// The small DEM's first `width` x `height` cells raised by `raise` metres, as a
// GeoTIFF.
std::string alteredDem(const std::string& path, int width, int height, double raise) {
  GDALDataset* from = static_cast<GDALDataset*>(GDALOpen(test::smallSyntheticDemFile().c_str(), GA_ReadOnly));
  GDALDataset* to =
      GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), width, height, 1, GDT_Float32, nullptr);
  double gt[6];
  from->GetGeoTransform(gt);
  to->SetGeoTransform(gt);
  to->SetProjection(from->GetProjectionRef());
  int hasNodata = 0;
  const double nodata = from->GetRasterBand(1)->GetNoDataValue(&hasNodata);
  if (hasNodata) to->GetRasterBand(1)->SetNoDataValue(nodata);
  std::vector<float> z(static_cast<std::size_t>(width) * height);
  EXPECT_EQ(from->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, width, height, z.data(), width, height, GDT_Float32, 0, 0), CE_None);
  for (float& v : z)
    if (!(hasNodata && v == float(nodata)) && !std::isnan(v)) v += float(raise);
  EXPECT_EQ(to->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, z.data(), width, height, GDT_Float32, 0, 0), CE_None);
  GDALClose(to);
  GDALClose(from);
  return path;
}

TEST(CatalogueHierarchy, TileByTileADemOtherThanTheTilesIsRefused) {
  const std::string smaller = alteredDem(test::tempDir() + "/smaller.tif", 300, 300, 0);
  try {
    runAccuracyJob(smaller, builtTiles().catalogue, AccuracyOutputs{}, 0, "", kQuiet);
    FAIL() << "measured tiles beyond the DEM";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "300 x 300 cells, but tile 2,0")) << e.what();
    EXPECT_TRUE(test::contains(e.what(), "give the DEM the tiles were cut from")) << e.what();
  }
}

TEST(CatalogueHierarchy, TileByTileATileOfAnotherDemIsRefused) {
  // The middle tile built from the DEM raised by 1 m: its line vertices lie where its
  // neighbours' do, at other heights.
  const std::string dir = std::filesystem::path(builtTiles().catalogue).parent_path().string();
  const std::string raised = alteredDem(dir + "/raised.tif", 360, 300, 1);
  runBuildJob(raised, dir + "/raised_tile.gpkg", SampleOptions{}, HierarchyOptions{}, true, kQuiet, AccuracyOutputs(),
              HierarchyLayers(), TileSpec{kTileSize, 1, 1});
  const std::string catalogue =
      alteredCatalogue("raised_middle.gpkg", "UPDATE tiles SET file = 'raised_tile.gpkg' WHERE tile_col = 1 AND tile_row = 1");
  for (const std::string& what :
       {test::errorOf([&] {
          runAccuracyJob(test::smallSyntheticDemFile(), catalogue, AccuracyOutputs{}, 0, "", kQuiet);
        }),
        test::errorOf([&] {
          extractCatalogueLod(catalogue, [](const std::string&) { return LodOptions{{}, std::nan(""), 0}; }, kRange);
        }),
        test::errorOf([&] { readHierarchyOrCatalogue(catalogue, kRange); })}) {
    EXPECT_TRUE(test::contains(what, "not built by one job")) << what;
    EXPECT_TRUE(test::contains(what, "another height")) << what;
  }
}

// What the catalogue's readers (merge, accuracy, lod, locate) say of it.
std::vector<std::string> readersErrors(const std::string& catalogue) {
  const std::string dir = test::tempDir();
  std::vector<std::string> tiles;
  const std::string points = tileCentresRoundAndRound(dir, tiles);
  return {test::errorOf([&] { readHierarchyOrCatalogue(catalogue, kRange); }),
          test::errorOf([&] { runAccuracyJob(test::smallSyntheticDemFile(), catalogue, AccuracyOutputs{}, 0, "", kQuiet); }),
          test::errorOf([&] {
            extractCatalogueLod(catalogue, [](const std::string&) { return LodOptions{{}, std::nan(""), 6}; }, kRange);
          }),
          test::errorOf([&] { runLocateJob(catalogue, points, dir + "/located.gpkg", 0, false, kQuiet); })};
}

TEST(CatalogueHierarchy, ATileFileThatHoldsAnotherTileIsRefused) {
  // Tile 1,1's file copied from tile 0,0's: its triangles would land on tile 0,0's.
  const std::string catalogue =
      alteredCatalogue("swapped.gpkg", "UPDATE tiles SET file = 'tile_0_0.gpkg' WHERE tile_col = 1 AND tile_row = 1");
  for (const std::string& message : readersErrors(catalogue))
    EXPECT_NE(message.find("tile 1,1 ('"), std::string::npos) << message;
  const std::string message = test::errorOf([&] { readHierarchyOrCatalogue(catalogue, kRange); });
  EXPECT_NE(message.find("tile_0_0.gpkg') holds tile 0,0: remove the file and run tinlod tiles again"), std::string::npos)
      << message;
  // info names it too, and does not add tile 0,0's rows twice.
  const HierarchyInfo info = readHierarchyInfo(catalogue);
  ASSERT_EQ(info.unreadableTiles.size(), 1u);
  EXPECT_EQ(info.unreadableTiles.front().rfind("tile 1,1 ('", 0), 0u) << info.unreadableTiles.front();
  EXPECT_NE(info.unreadableTiles.front().find("holds tile 0,0"), std::string::npos) << info.unreadableTiles.front();
  EXPECT_LT(info.levels[0].triangles, readHierarchyInfo(builtTiles().catalogue).levels[0].triangles);
}

// A finished tile's file cut short: every reader names the tile and the fix.
TEST(CatalogueHierarchy, ADamagedTileIsNamedWithTheFix) {
  const std::string cut = std::filesystem::path(builtTiles().files[1]).parent_path().string() + "/cut_tile.gpkg";
  {
    std::ifstream in(builtTiles().files[1], std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, 50000);
  }
  const std::string catalogue = alteredCatalogue(
      "cut_short.gpkg", "UPDATE tiles SET file = '" + cut + "' WHERE tile_col = 1 AND tile_row = 0");
  for (const std::string& message : readersErrors(catalogue)) {
    EXPECT_TRUE(test::contains(message, "tile 1,0 ('" + cut + "') cannot be read: ")) << message;
    EXPECT_TRUE(test::contains(message, "remove the file and run tinlod tiles on the catalogue again")) << message;
  }
}

// A catalogue named as a tile (its own, here) is refused, not read without end.
TEST(CatalogueHierarchy, ACatalogueAsItsOwnTileIsRefused) {
  const std::string catalogue =
      alteredCatalogue("own_tile.gpkg", "UPDATE tiles SET file = 'own_tile.gpkg' WHERE tile_col = 1 AND tile_row = 0");
  const HierarchyInfo info = readHierarchyInfo(catalogue);
  ASSERT_EQ(info.unreadableTiles.size(), 1u);
  EXPECT_TRUE(test::contains(info.unreadableTiles.front(), "it is a tinlod-tiles catalogue, not a tile"))
      << info.unreadableTiles.front();
  const std::string message = test::errorOf([&] { readHierarchyOrCatalogue(catalogue, kRange); });
  EXPECT_TRUE(test::contains(message, "tile 1,0 ('")) << message;
}

TEST(CatalogueHierarchy, TilesOfTwoJobsAreRefused) {
  // Beside the tiles: the catalogue names them relative to its folder.
  const std::string dir = std::filesystem::path(builtTiles().catalogue).parent_path().string();
  const std::string other = dir + "/other.gpkg";
  HierarchyOptions fewer;
  fewer.deletePct = 30;
  runBuildJob(test::smallSyntheticDemFile(), other, SampleOptions{}, fewer, true, kQuiet, AccuracyOutputs(),
              HierarchyLayers(), TileSpec{kTileSize, 1, 1});
  const std::string catalogue =
      alteredCatalogue("two_jobs.gpkg", "UPDATE tiles SET file = '" + other + "' WHERE tile_col = 1 AND tile_row = 1");
  try {
    readHierarchyOrCatalogue(catalogue, kRange);
    FAIL() << "tiles of another job were merged";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "tile 1,1")) << e.what();
    EXPECT_TRUE(test::contains(e.what(), "not built by one job")) << e.what();
  }
}

TEST(CatalogueHierarchy, NoOutputReplacesATileOfTheCatalogue) {
  const std::string tile = builtTiles().files[4];
  const auto before = std::filesystem::last_write_time(tile);
  LodJobOptions o;
  o.lod.dropoff = 0, o.lod.centres = {{0, 0}};
  try {
    runLodJob(builtTiles().catalogue, tile, o, true, kQuiet);
    FAIL() << "lod wrote over a tile of its catalogue";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "an input of this run")) << e.what();
  }
  EXPECT_EQ(std::filesystem::last_write_time(tile), before);
}

}  // namespace
}  // namespace tinlod
