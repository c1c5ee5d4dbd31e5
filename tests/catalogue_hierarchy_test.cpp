// SPDX-License-Identifier: GPL-3.0-or-later
// A catalogue's tiles read as one hierarchy: one vertex for each place, every level one
// conforming TIN covering what the tiles cover, and a varying level of detail across the
// tiles without a crack, where extracting each tile on its own leaves cracks.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "catalogue_hierarchy.h"
#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/error.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/lod_job.h"

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
OGRPolygon tileBox(const Dem& dem, int col, int row) {
  const double x0 = dem.geotransform[0] + col * kTileSize * dem.geotransform[1];
  const double y0 = dem.geotransform[3] + row * kTileSize * dem.geotransform[5];
  const double x1 = x0 + (kTileSize + 1) * dem.geotransform[1], y1 = y0 + (kTileSize + 1) * dem.geotransform[5];
  OGRLinearRing ring;
  ring.addPoint(x0, y0), ring.addPoint(x1, y0), ring.addPoint(x1, y1), ring.addPoint(x0, y1), ring.addPoint(x0, y0);
  OGRPolygon box;
  box.addRing(&ring);
  return box;
}

// Every tile of the small synthetic DEM (its void and lake included) built as tinlod tiles
// -selection tile builds them, and a catalogue as tinlod-tiles writes it: the fields the
// readers use, file names relative to the catalogue.
const BuiltTiles& builtTiles() {
  static const BuiltTiles built = [] {
    BuiltTiles b;
    GDALAllRegister();
    const std::string dir = test::tempDir();
    const Dem dem = test::smallSyntheticDem();
    b.catalogue = dir + "/catalogue.gpkg";
    GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GPKG")->Create(b.catalogue.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    ds->SetMetadataItem("TINLOD_KIND", "catalogue");
    OGRLayer& layer = *ds->CreateLayer("tiles", nullptr, wkbPolygon, nullptr);
    for (const char* name : {"tile_col", "tile_row", "xoff", "yoff"}) addField(layer, name, OFTInteger);
    for (const char* name : {"file", "status"}) addField(layer, name, OFTString);
    for (int c = 0; c < TileSpec::count(dem.width, kTileSize); ++c)
      for (int r = 0; r < TileSpec::count(dem.height, kTileSize); ++r) {
        const std::string name = "tile_" + std::to_string(c) + "_" + std::to_string(r) + ".gpkg";
        b.files.push_back(dir + "/" + name);
        runBuildJob(test::smallSyntheticDemFile(), b.files.back(), SampleOptions{}, HierarchyOptions{}, true, kQuiet,
                    AccuracyOutputs(), HierarchyLayers(), TileSpec{kTileSize, c, r});
        OGRFeature f(layer.GetLayerDefn());
        f.SetField("tile_col", c), f.SetField("tile_row", r);
        f.SetField("xoff", c * kTileSize), f.SetField("yoff", r * kTileSize);
        f.SetField("file", name.c_str()), f.SetField("status", "done");
        OGRPolygon box = tileBox(dem, c, r);
        f.SetGeometry(&box);
        EXPECT_EQ(layer.CreateFeature(&f), OGRERR_NONE);
      }
    GDALClose(ds);
    return b;
  }();
  return built;
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
void expectOneSurfaceLikeLevelZero(const Tin& tin, const std::string& what) {
  const test::Topology top = test::analyseTopology(tin);
  EXPECT_EQ(top.problem, "") << what;
  EXPECT_EQ(top.components, 1u) << what;
  EXPECT_EQ(top.boundaryLoops, test::analyseTopology(merged().hierarchy.levelTin(0)).boundaryLoops) << what;
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

TEST(CatalogueHierarchy, TilesOfTwoJobsAreRefused) {
  // Beside the tiles: the catalogue names them relative to its folder.
  const std::string dir = std::filesystem::path(builtTiles().catalogue).parent_path().string();
  const std::string other = dir + "/other.gpkg";
  HierarchyOptions fewer;
  fewer.deletePct = 30;
  runBuildJob(test::smallSyntheticDemFile(), other, SampleOptions{}, fewer, true, kQuiet, AccuracyOutputs(),
              HierarchyLayers(), TileSpec{kTileSize, 1, 1});
  const std::string catalogue = dir + "/two_jobs.gpkg";
  ASSERT_TRUE(std::filesystem::copy_file(builtTiles().catalogue, catalogue));
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(catalogue.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr));
  ds->ExecuteSQL(("UPDATE tiles SET file = '" + other + "' WHERE tile_col = 1 AND tile_row = 1").c_str(), nullptr, nullptr);
  GDALClose(ds);
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
