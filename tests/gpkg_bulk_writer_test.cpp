// SPDX-License-Identifier: GPL-3.0-or-later
// The GeoPackages written in bulk (rows through prepared statements, R-trees packed and
// loaded at once) read back through OGR as written, and their spatial indexes answer as
// SQLite's own row-by-row index does.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <set>

#include "gdal_metadata_xml.h"
#include "packed_rtree.h"
#include "test_support.h"
#include "tin_gpkg_file.h"
#include "tinlod/error.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/hierarchy_writer.h"
#include "tinlod/sample_job.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

struct Built {
  Dem dem;
  Hierarchy h;
};

const Built& built() {
  static const Built b = [] {
    Built out{test::smallSyntheticDem(), {}};
    SampleOptions sample;
    Tin tin = sampleTin(out.dem, sample, ProgressRange(Feedback{}, 0, 1));
    out.h = buildHierarchy(std::move(tin), out.dem, {}, HierarchyOptions(), ProgressRange(Feedback{}, 0, 1));
    return out;
  }();
  return b;
}

std::string writeHierarchy(const std::string& name, const HierarchyLayers& layers = {}) {
  const std::string path = test::tempDir() + "/" + name;
  fs::remove(path);
  writeHierarchyGpkg(built().h, path, GpkgWriteOptions{false, {{"TINLOD_KIND", "hierarchy"}}}, ProgressRange(Feedback{}, 0, 1),
                     layers);
  return path;
}

struct Dataset {
  explicit Dataset(const std::string& path)
      : ds(static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr))) {}
  ~Dataset() { GDALClose(ds); }
  GDALDataset* ds;
};

struct Sqlite {
  explicit Sqlite(const std::string& path) {
    sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  }
  ~Sqlite() { sqlite3_close(db); }
  std::vector<long long> column(const std::string& sql) const {
    std::vector<long long> out;
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) ADD_FAILURE() << sqlite3_errmsg(db) << ": " << sql;
    while (s && sqlite3_step(s) == SQLITE_ROW) out.push_back(sqlite3_column_int64(s, 0));
    sqlite3_finalize(s);
    return out;
  }
  std::string text(const std::string& sql) const {
    std::string out;
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr);
    if (s && sqlite3_step(s) == SQLITE_ROW && sqlite3_column_text(s, 0))
      out = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
    sqlite3_finalize(s);
    return out;
  }
  sqlite3* db = nullptr;
};

// Every vertex and triangle of `tin` through OGR: points and rings exactly as stored, ids.
void expectTinLayers(GDALDataset& ds, const Tin& tin, const std::vector<Triangle>& triangles) {
  OGRLayer* vertices = ds.GetLayerByName("vertices");
  ASSERT_NE(vertices, nullptr);
  ASSERT_EQ(vertices->GetFeatureCount(), static_cast<GIntBig>(tin.vertices.size()));
  for (auto& f : *vertices) {
    const std::size_t i = static_cast<std::size_t>(f->GetFID()) - 1;
    const auto* p = f->GetGeometryRef()->toPoint();
    const TinVertex& v = tin.vertices[i];
    ASSERT_TRUE(p->getX() == v.x && p->getY() == v.y && p->getZ() == v.z) << "vertex " << i + 1;
    ASSERT_EQ(f->GetFieldAsInteger64("id"), f->GetFID());
    ASSERT_EQ(f->GetFieldAsInteger("row"), v.row);
    ASSERT_EQ(f->GetFieldAsInteger("col"), v.col);
    ASSERT_EQ(f->GetFieldAsInteger("outline"), v.outline ? 1 : 0);
  }
  OGRLayer* layer = ds.GetLayerByName("triangles");
  ASSERT_NE(layer, nullptr);
  ASSERT_EQ(layer->GetFeatureCount(), static_cast<GIntBig>(triangles.size()));
  ASSERT_EQ(layer->GetGeomType(), wkbPolygon25D);
  for (auto& f : *layer) {
    const std::size_t i = static_cast<std::size_t>(f->GetFID()) - 1;
    const OGRLinearRing* ring = f->GetGeometryRef()->toPolygon()->getExteriorRing();
    ASSERT_EQ(ring->getNumPoints(), 4);
    for (int k = 0; k < 4; ++k) {
      const TinVertex& v = tin.vertices[triangles[i][k % 3]];
      ASSERT_TRUE(ring->getX(k) == v.x && ring->getY(k) == v.y && ring->getZ(k) == v.z) << "triangle " << i + 1;
    }
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(f->GetFieldAsInteger64(("v" + std::to_string(k)).c_str()), triangles[i][k] + 1);
  }
}

std::vector<Triangle> cornersOf(const Hierarchy& h) {
  std::vector<Triangle> out;
  for (const HierarchyTriangle& t : h.triangles) out.push_back(t.v);
  return out;
}

TEST(PackedRtree, EveryEntryInOneLeafAndEveryBoxInsideItsParent) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> at(-1000, 1000), size(0, 5);
  for (std::size_t n : {0u, 1u, 51u, 52u, 2601u, 2602u, 20000u}) {
    std::vector<RtreeBox> boxes;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = at(random), y = at(random);
      boxes.push_back(outwardBox({x, x + size(random), y, y + size(random)}));
    }
    const PackedRtree tree(boxes, 51);
    // Full nodes: the fewest a tree of 51-cell nodes can have.
    std::size_t expected = 0;
    for (std::size_t level = std::max<std::size_t>(n, 1); ; level = (level + 50) / 51) {
      expected += (level + 50) / 51;
      if ((level + 50) / 51 <= 1) break;
    }
    EXPECT_EQ(tree.nodes(), n ? expected : 0u) << n;
    if (n == 0) continue;
    const std::vector<std::uint32_t> leaf = tree.leaves();
    std::vector<int> seen(tree.nodes() + 1, 0);
    for (std::uint32_t l : leaf) ++seen[l];
    for (std::size_t node = 1; node <= tree.nodes(); ++node) EXPECT_LE(seen[node], 51);
    EXPECT_EQ(tree.parents().size(), tree.nodes() + 1);
    EXPECT_EQ(tree.depth() == 0, n <= 51) << n;
  }
}

// The writer frees the entries' boxes once the nodes are written, before the rowid table:
// what it then reads of the tree must not change.
// `n` unit squares at random in 2000 x 2000.
std::vector<RtreeBox> unitBoxes(unsigned seed, int n) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> at(-1000, 1000);
  std::vector<RtreeBox> boxes;
  for (int i = 0; i < n; ++i) {
    const double x = at(random), y = at(random);
    boxes.push_back(outwardBox({x, x + 1, y, y + 1}));
  }
  return boxes;
}

TEST(PackedRtree, LeavesAndParentsOutliveTheEntriesBoxes) {
  PackedRtree tree(unitBoxes(11, 5000), 51);
  const std::vector<std::uint32_t> leaves = tree.leaves(), parents = tree.parents();
  const std::size_t nodes = tree.nodes();
  tree.dropEntryBoxes();
  EXPECT_EQ(tree.entries(), 5000u);
  EXPECT_EQ(tree.nodes(), nodes);
  EXPECT_EQ(tree.leaves(), leaves);
  EXPECT_EQ(tree.parents(), parents);
}

// A cancelled write no longer waits for the packing beside it (up to 2 s on alps_2x2's
// 3.4 million triangles): once abandoned, the packing stops; never abandoned, it packs the same tree.
TEST(PackedRtree, AnAbandonedPackingStopsAndAWatchedOneIsTheSameTree) {
  const std::vector<RtreeBox> boxes = unitBoxes(5, 100000);
  std::atomic<bool> abandon{false};
  const PackedRtree plain(boxes, 51), watched(boxes, 51, &abandon);
  EXPECT_EQ(watched.leaves(), plain.leaves());
  EXPECT_EQ(watched.parents(), plain.parents());
  abandon = true;
  EXPECT_THROW(PackedRtree(boxes, 51, &abandon), PackingAbandoned);
}

// The packing sorts each box as one integer (centre, then index): its leaves must be those
// of sort-tile-recursive done as written, centres compared as floats and ties broken by
// index, where centres tie often (a grid of boxes) and cross zero (-0 among them).
TEST(PackedRtree, LeavesAreSortTileRecursiveWithTiesBrokenByIndex) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> cell(-20, 20);
  std::vector<RtreeBox> boxes;
  for (int i = 0; i < 30000; ++i) {
    const float x = static_cast<float>(cell(random)), y = static_cast<float>(cell(random));
    switch (i % 7) {
      case 0: boxes.push_back({-0.0f, -0.0f, y, y + 1}); break;  // centre -0 in x
      case 1: boxes.push_back({0.0f, 0.0f, -0.0f, -0.0f}); break;  // +0 in x, -0 in y
      default: boxes.push_back({x, x + 1, y, y + 1});
    }
  }
  const PackedRtree tree(boxes, 51);
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto by = [&](float RtreeBox::*lo, float RtreeBox::*hi) {
    return [&, lo, hi](std::uint32_t a, std::uint32_t b) {
      const float ca = boxes[a].*lo + boxes[a].*hi, cb = boxes[b].*lo + boxes[b].*hi;
      return ca < cb || (ca == cb && a < b);
    };
  };
  std::sort(order.begin(), order.end(), by(&RtreeBox::minX, &RtreeBox::maxX));
  const std::size_t leaves = (boxes.size() + 50) / 51;
  const std::size_t slice = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(leaves)))) * 51;
  for (std::size_t begin = 0; begin < order.size(); begin += slice)
    std::sort(order.begin() + begin, order.begin() + std::min(order.size(), begin + slice),
              by(&RtreeBox::minY, &RtreeBox::maxY));
  std::vector<std::uint32_t> expected(boxes.size());
  const std::size_t firstLeaf = tree.nodes() - leaves + 1;
  for (std::size_t k = 0; k < order.size(); ++k) expected[order[k]] = static_cast<std::uint32_t>(firstLeaf + k / 51);
  EXPECT_EQ(tree.leaves(), expected);
}

TEST(PackedRtree, RoundsOutwardAsSqlite) {
  // 0.1 is no float: the box must still hold it, on both sides of zero.
  const RtreeBox b = outwardBox({0.1, 0.1, -0.1, -0.1});
  EXPECT_LT(b.minX, 0.1);
  EXPECT_GT(b.maxX, 0.1);
  EXPECT_LT(b.minY, -0.1);
  EXPECT_GT(b.maxY, -0.1);
  const RtreeBox exact = outwardBox({1.5, 2.5, -3.5, 4});
  EXPECT_TRUE(exact.minX == 1.5f && exact.maxX == 2.5f && exact.minY == -3.5f && exact.maxY == 4.0f);
}

TEST(GpkgBulkWriter, HierarchyReadsBackAsWritten) {
  const std::string path = writeHierarchy("round_trip.gpkg", {{}, true, true});
  const Hierarchy& h = built().h;
  {
    Dataset d(path);
    ASSERT_NE(d.ds, nullptr);
    expectTinLayers(*d.ds, h.base, cornersOf(h));
    OGRLayer* triangles = d.ds->GetLayerByName("triangles");
    for (auto& f : *triangles) {
      const HierarchyTriangle& t = h.triangles[f->GetFID() - 1];
      ASSERT_EQ(f->GetFieldAsInteger("first_level"), t.firstLevel);
      ASSERT_EQ(f->GetFieldAsInteger("last_level"), t.lastLevel);
      ASSERT_EQ(f->IsFieldNull(f->GetFieldIndex("group_id")), t.group < 0);
      ASSERT_EQ(f->IsFieldNull(f->GetFieldIndex("replaced_by")), t.replacedBy < 0);
      ASSERT_EQ(f->GetFieldAsDouble("error"), t.error);
    }
    OGRLayer* groups = d.ds->GetLayerByName("groups");
    ASSERT_EQ(groups->GetGeomType(), wkbPolygon);
    for (auto& f : *groups) {
      const Group& g = h.groups[f->GetFID() - 1];
      const OGRLinearRing* ring = f->GetGeometryRef()->toPolygon()->getExteriorRing();
      ASSERT_EQ(ring->getNumPoints(), static_cast<int>(g.ringEnd - g.ringBegin) + 1);
      const TinVertex& first = h.base.vertices[h.rings[g.ringBegin]];
      ASSERT_TRUE(ring->getX(0) == first.x && ring->getY(0) == first.y);
      ASSERT_EQ(f->GetFieldAsDouble("importance"), g.importance);
    }
    // Each level's view is exactly the triangles whose levels span it.
    for (std::int32_t L = 0; L <= h.coarsest(); ++L) {
      OGRLayer* view = d.ds->GetLayerByName(("level_" + std::to_string(L)).c_str());
      ASSERT_NE(view, nullptr) << L;
      std::set<GIntBig> fids, expected;
      for (auto& f : *view) fids.insert(f->GetFID());
      for (std::size_t i = 0; i < h.triangles.size(); ++i)
        if (h.triangles[i].firstLevel <= L && h.triangles[i].lastLevel >= L) expected.insert(GIntBig(i) + 1);
      EXPECT_EQ(fids, expected) << "level_" << L;
      EXPECT_EQ(fids.size(), h.levels[L].triangles);
    }
    EXPECT_STREQ(d.ds->GetMetadataItem("TINLOD_KIND"), "hierarchy");
  }
  const StoredHierarchy read = readHierarchy(path, ProgressRange(Feedback{}, 0, 1));
  ASSERT_EQ(read.hierarchy.triangles.size(), h.triangles.size());
  ASSERT_EQ(read.hierarchy.groups.size(), h.groups.size());
  ASSERT_EQ(read.hierarchy.levels.size(), h.levels.size());
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    ASSERT_EQ(read.hierarchy.groups[g].vertex, h.groups[g].vertex);
    ASSERT_EQ(read.hierarchy.groups[g].level, h.groups[g].level);
  }
}

TEST(GpkgBulkWriter, TinWithExtraFieldsReadsBackAsWritten) {
  const Tin& tin = built().h.base;
  std::vector<ExtraField> vx{{"insertion", {}, true}}, tx{{"error", {}, false}};
  for (std::size_t i = 0; i < tin.vertices.size(); ++i) vx[0].values.push_back(i % 3 ? double(i) : NAN);
  for (std::size_t i = 0; i < tin.triangles.size(); ++i) tx[0].values.push_back(i % 5 ? i * 0.25 : INFINITY);
  const std::string path = test::tempDir() + "/tin.gpkg";
  fs::remove(path);
  writeTinGpkg(tin, path, GpkgWriteOptions{false, {}}, ProgressRange(Feedback{}, 0, 1), vx, tx);
  Dataset d(path);
  expectTinLayers(*d.ds, tin, tin.triangles);
  for (auto& f : *d.ds->GetLayerByName("vertices")) {
    const std::size_t i = f->GetFID() - 1;
    if (i % 3) ASSERT_EQ(f->GetFieldAsInteger("insertion"), int(i));
    else ASSERT_TRUE(f->IsFieldNull(f->GetFieldIndex("insertion")));
  }
  for (auto& f : *d.ds->GetLayerByName("triangles")) {
    const std::size_t i = f->GetFID() - 1;
    if (i % 5) ASSERT_EQ(f->GetFieldAsDouble("error"), i * 0.25);
    else ASSERT_TRUE(f->IsFieldNull(f->GetFieldIndex("error")));
  }
  OGREnvelope extent;
  ASSERT_EQ(d.ds->GetLayerByName("triangles")->GetExtent(&extent, false), OGRERR_NONE);
  double minX = INFINITY, maxX = -INFINITY;
  for (const TinVertex& v : tin.vertices) minX = std::min(minX, v.x), maxX = std::max(maxX, v.x);
  EXPECT_EQ(extent.MinX, minX);
  EXPECT_EQ(extent.MaxX, maxX);
}

// A TIN's file written in steps, whose first vertex rows turned out wrong (a writer that
// wrote rows ahead of time for vertices the TIN then dropped): cleared and written again,
// the file holds only the second rows, counted and bounded as the TIN's; the extra
// fields' names outlive the caller's list.
TEST(GpkgBulkWriter, VertexRowsClearedAndWrittenAgainAreTheOnlyOnes) {
  const Tin& tin = built().h.base;
  const std::string dir = test::tempDir();
  OutputFiles files(false);
  const StagedFile& staged = files.add(dir + "/steps.gpkg", "output", true);
  {
    TinGpkgFile file(staged, GpkgWriteOptions{}, tin.crsWkt, std::vector<ExtraField>{{"insertion", {}, true}}, {});
    Tin wrong = tin;
    for (TinVertex& v : wrong.vertices) v.x += 1000, v.row += 7;
    wrong.vertices.push_back(wrong.vertices.front());  // one vertex too many
    std::vector<ExtraField> none{{"insertion", std::vector<double>(wrong.vertices.size(), 5), true}};
    writeVertices(wrong, file.vertexRows(), file.srsId(), extraSetter(none, int(vertexFields().size())),
                  ProgressRange(Feedback{}, 0, 1));
    file.clearVertexRows();
    std::vector<ExtraField> order{{"insertion", {}, true}};
    for (std::size_t i = 0; i < tin.vertices.size(); ++i) order[0].values.push_back(double(i + 1));
    writeVertices(tin, file.vertexRows(), file.srsId(), extraSetter(order, int(vertexFields().size())),
                  ProgressRange(Feedback{}, 0, 1));
    file.indexLater(tin);
    file.finish(tin, {}, ProgressRange(Feedback{}, 0, 0.8), ProgressRange(Feedback{}, 0.8, 1));
  }
  files.commit();
  Dataset d(dir + "/steps.gpkg");
  expectTinLayers(*d.ds, tin, tin.triangles);
  for (auto& f : *d.ds->GetLayerByName("vertices")) ASSERT_EQ(f->GetFieldAsInteger64("insertion"), f->GetFID());
  OGREnvelope extent;
  ASSERT_EQ(d.ds->GetLayerByName("vertices")->GetExtent(&extent, false), OGRERR_NONE);
  double maxX = -INFINITY;
  for (const TinVertex& v : tin.vertices) maxX = std::max(maxX, v.x);
  EXPECT_EQ(extent.MaxX, maxX);
  Sqlite db(dir + "/steps.gpkg");
  EXPECT_EQ(db.column("SELECT feature_count FROM gpkg_ogr_contents WHERE table_name = 'vertices'"),
            std::vector<long long>{(long long)tin.vertices.size()});
  // GDAL's count triggers are back: a row added later is counted.
  EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE name LIKE 'trigger_%_feature_count_vertices'"),
            std::vector<long long>{2});
}

// The packed index against SQLite's own, filled row by row from OGR's envelopes.
void expectIndexAsRowByRow(const std::string& path, const std::string& table) {
  Sqlite db(path);
  EXPECT_EQ(db.text("SELECT rtreecheck('rtree_" + table + "_geom')"), "ok") << table;
  EXPECT_EQ(db.text("SELECT scope FROM gpkg_extensions WHERE table_name = '" + table + "' AND extension_name = 'gpkg_rtree_index'"),
            "write-only");
  EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE type = 'trigger' AND name LIKE 'rtree_" + table + "_geom_%'")[0], 6);
  const std::string reference = test::tempDir() + "/reference.db";
  fs::remove(reference);
  Sqlite ref(reference);
  sqlite3_exec(ref.db, "CREATE VIRTUAL TABLE r USING rtree(id, minx, maxx, miny, maxy); BEGIN", nullptr, nullptr, nullptr);
  Dataset d(path);
  OGREnvelope all;
  OGRLayer* layer = d.ds->GetLayerByName(table.c_str());
  ASSERT_EQ(layer->GetExtent(&all, true), OGRERR_NONE);
  for (auto& f : *layer) {
    OGREnvelope e;
    f->GetGeometryRef()->getEnvelope(&e);
    char sql[256];
    std::snprintf(sql, sizeof sql, "INSERT INTO r VALUES (%lld, %.17g, %.17g, %.17g, %.17g)", static_cast<long long>(f->GetFID()),
                  e.MinX, e.MaxX, e.MinY, e.MaxY);
    sqlite3_exec(ref.db, sql, nullptr, nullptr, nullptr);
  }
  sqlite3_exec(ref.db, "COMMIT", nullptr, nullptr, nullptr);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> x(all.MinX, all.MaxX), y(all.MinY, all.MaxY), size(0, (all.MaxX - all.MinX) / 10);
  for (int q = 0; q < 200; ++q) {
    const double x0 = x(random), y0 = y(random), w = q % 10 ? size(random) : 0;  // some are points
    char where[200];
    std::snprintf(where, sizeof where, " WHERE minx <= %.17g AND maxx >= %.17g AND miny <= %.17g AND maxy >= %.17g ORDER BY id",
                  x0 + w, x0, y0 + w, y0);
    ASSERT_EQ(db.column("SELECT id FROM rtree_" + table + "_geom" + where), ref.column(std::string("SELECT id FROM r") + where))
        << table << where;
  }
}

TEST(GpkgBulkWriter, PackedIndexesAnswerAsRowByRowOnes) {
  const std::string path = writeHierarchy("indexed.gpkg", {{}, true, true});
  for (const char* table : {"triangles", "vertices", "groups"}) expectIndexAsRowByRow(path, table);
  // OGR's spatial filter goes through the index.
  Dataset d(path);
  OGRLayer* triangles = d.ds->GetLayerByName("triangles");
  OGREnvelope e;
  ASSERT_EQ(triangles->GetExtent(&e), OGRERR_NONE);
  triangles->SetSpatialFilterRect(e.MinX, e.MinY, (e.MinX + e.MaxX) / 2, (e.MinY + e.MaxY) / 2);
  const GIntBig some = triangles->GetFeatureCount();
  EXPECT_GT(some, 0);
  EXPECT_LT(some, static_cast<GIntBig>(built().h.triangles.size()));
}

// A single TIN's vertices are indexed only when asked (sample, insert and lod's
// -vertex_index); its triangles always are.
TEST(GpkgBulkWriter, TinVerticesIndexedOnlyWhenAsked) {
  const Tin& tin = built().h.base;
  for (bool vertexIndex : {false, true}) {
    const std::string path = test::tempDir() + "/tin_index.gpkg";
    fs::remove(path);
    GpkgWriteOptions options{false, {}};
    options.vertexIndex = vertexIndex;
    writeTinGpkg(tin, path, options, ProgressRange(Feedback{}, 0, 1));
    {
      Sqlite db(path);
      EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE name = 'rtree_vertices_geom'")[0], vertexIndex ? 1 : 0);
      EXPECT_EQ(db.column("SELECT count(*) FROM gpkg_extensions WHERE table_name = 'vertices'")[0], vertexIndex ? 1 : 0);
    }
    expectIndexAsRowByRow(path, "triangles");
    if (vertexIndex) expectIndexAsRowByRow(path, "vertices");
  }
}

TEST(GpkgBulkWriter, ValidatesAsAGeoPackage) {
  const char* validator = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
  if (!fs::exists(validator)) GTEST_SKIP() << "GDAL's validate_gpkg.py is not installed (python3-gdal)";
  for (const HierarchyLayers& layers : {HierarchyLayers{{}, true, true}, HierarchyLayers{{0, HierarchyLayers::kCoarsest}, false, false}}) {
    const std::string path = writeHierarchy("valid.gpkg", layers);
    const test::CommandRun run = test::runCommand(std::string("/usr/bin/python3 ") + validator + " " + path);
    EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
  }
}

TEST(GpkgBulkWriter, ChosenLayers) {
  const Hierarchy& h = built().h;
  std::vector<std::string> warnings;
  Feedback feedback;
  feedback.warning = [&](const std::string& m) { warnings.push_back(m); };
  const std::string path = test::tempDir() + "/chosen.gpkg";
  fs::remove(path);
  HierarchyLayers layers{{2, HierarchyLayers::kCoarsest, 0, 99}, false, false};
  writeHierarchyGpkg(h, path, GpkgWriteOptions{false, {{"TINLOD_KIND", "hierarchy"}}}, ProgressRange(feedback, 0, 1), layers);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(test::contains(warnings[0], "no view for level 99")) << warnings[0];
  Sqlite db(path);
  const std::string coarsest = std::to_string(h.coarsest());
  EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE type = 'view'")[0], 3);
  EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE name IN ('level_0', 'level_2', 'level_" + coarsest + "')")[0], 3);
  EXPECT_EQ(db.column("SELECT count(*) FROM sqlite_master WHERE name LIKE 'rtree_%' AND type = 'table'")[0], 4);  // triangles'
  EXPECT_EQ(db.text("SELECT data_type FROM gpkg_contents WHERE table_name = 'groups'"), "attributes");
  EXPECT_EQ(db.column("SELECT count(*) FROM groups")[0], static_cast<long long>(h.groups.size()));
  // Still a whole hierarchy for every reader.
  const StoredHierarchy read = readHierarchy(path, ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(read.hierarchy.groups.size(), h.groups.size());
  EXPECT_THROW(parseLevelList("0,x", "-levels"), Error);
  EXPECT_THROW(parseLevelList("0,,1", "-levels"), Error);
  EXPECT_THROW(parseLevelList("-1", "-levels"), Error);
  EXPECT_EQ(parseLevelList("all", "-levels").size(), 0u);
  EXPECT_EQ(parseLevelList("3,last", "-levels"), (std::vector<std::int32_t>{3, HierarchyLayers::kCoarsest}));
  EXPECT_EQ(parseLevelList("0, 2 ,last", "-levels"), (std::vector<std::int32_t>{0, 2, HierarchyLayers::kCoarsest}));
}

TEST(GpkgBulkWriter, CancelWhileIndexingLeavesNoFile) {
  const std::string path = test::tempDir() + "/cancelled.gpkg";
  fs::remove(path);
  bool indexing = false;
  Feedback feedback;
  feedback.progress = [&](double, const std::string& phase) {
    indexing = indexing || phase == "Writing the spatial index";
    return !indexing;
  };
  EXPECT_THROW(writeHierarchyGpkg(built().h, path, GpkgWriteOptions{false, {}}, ProgressRange(feedback, 0, 1)), Cancelled);
  EXPECT_TRUE(indexing);
  EXPECT_FALSE(fs::exists(path));
  for (const auto& entry : fs::directory_iterator(test::tempDir()))
    EXPECT_EQ(entry.path().filename().string().find(".cancelled.gpkg.tinlod-"), std::string::npos) << entry.path();
}

// docs/geopackage.md's table of layers names every layer and field a hierarchy file has.
TEST(GpkgBulkWriter, TheDocumentedLayersAreTheWrittenOnes) {
  const std::string doc = test::readFile(test::sourceDir() + "/docs/geopackage.md");
  ASSERT_FALSE(doc.empty());
  const std::string path = writeHierarchy("documented.gpkg", {{}, true, true});
  Dataset d(path);
  for (int i = 0; i < d.ds->GetLayerCount(); ++i) {
    OGRLayer* layer = d.ds->GetLayer(i);
    const std::string name = layer->GetName();
    const bool view = name.rfind("level_", 0) == 0;
    const std::size_t row = doc.find("| `" + (view ? std::string("level_0") : name) + "`");
    ASSERT_NE(row, std::string::npos) << name << " is not in docs/geopackage.md";
    if (view) continue;
    const std::string line = doc.substr(row, doc.find('\n', row) - row);
    OGRFeatureDefn* defn = layer->GetLayerDefn();
    for (int f = 0; f < defn->GetFieldCount(); ++f) {
      const std::string field = defn->GetFieldDefn(f)->GetNameRef();
      // v0, v1 and v2 are written as a range there
      if (field == "v1") continue;
      EXPECT_NE(line.find("`" + field + "`"), std::string::npos) << name << "." << field << " is not in its row: " << line;
    }
  }
}

// Replacing tinlod's layers keeps everything else, registered or not: QGIS keeps projects
// in a plain table, and another tool may leave out GDAL's feature counts.
TEST(GpkgBulkWriter, OverwriteKeepsTheUsersOtherContent) {
  const Tin& tin = built().h.base;
  const std::string path = test::tempDir() + "/shared.gpkg";
  fs::remove(path);
  {
    GDALAllRegister();
    const char* const noCounts[] = {"ADD_GPKG_OGR_CONTENTS=NO", nullptr};
    GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(
        path.c_str(), 0, 0, 0, GDT_Unknown, const_cast<char**>(noCounts)));
    ASSERT_TRUE(ds);
    OGRLayer* mine = ds->CreateLayer("my_points", nullptr, wkbPoint, nullptr);
    OGRFeature f(mine->GetLayerDefn());
    f.SetGeometryDirectly(new OGRPoint(1, 2));
    ASSERT_EQ(mine->CreateFeature(&f), OGRERR_NONE);
  }
  writeTinGpkg(tin, path, GpkgWriteOptions(true, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  const auto size = fs::file_size(path);
  writeTinGpkg(tin, path, GpkgWriteOptions(true, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  {
    Dataset d(path);
    ASSERT_NE(d.ds->GetLayerByName("my_points"), nullptr);
    EXPECT_EQ(d.ds->GetLayerByName("my_points")->GetFeatureCount(), 1);
    EXPECT_EQ(d.ds->GetLayerByName("triangles")->GetFeatureCount(), static_cast<GIntBig>(tin.triangles.size()));
  }
  // The same output again reuses the old layers' pages (no compaction needed); a much
  // smaller one leaves them free, and the file is compacted.
  auto freeShare = [&] {
    Sqlite db(path);
    return double(db.column("PRAGMA freelist_count")[0]) / double(db.column("PRAGMA page_count")[0]);
  };
  EXPECT_LE(freeShare(), 1.0 / 8);
  EXPECT_LE(fs::file_size(path), size + size / 8);
  Tin small = tin;
  small.triangles.resize(tin.triangles.size() / 20);
  writeTinGpkg(small, path, GpkgWriteOptions(true, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  EXPECT_LE(freeShare(), 1.0 / 8);
  EXPECT_LT(fs::file_size(path), size / 2);
  EXPECT_EQ(Dataset(path).ds->GetLayerByName("my_points")->GetFeatureCount(), 1);
  // A project saved in a file of tinlod's layers: a table GeoPackage does not register.
  const std::string project = test::tempDir() + "/project.gpkg";
  fs::remove(project);
  writeTinGpkg(tin, project, GpkgWriteOptions(false, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  {
    Sqlite db(project);
    ASSERT_EQ(sqlite3_exec(db.db, "CREATE TABLE qgis_projects (name TEXT PRIMARY KEY, metadata BLOB, content BLOB); "
                                  "INSERT INTO qgis_projects VALUES ('survey', NULL, x'01')", nullptr, nullptr, nullptr), SQLITE_OK);
  }
  writeTinGpkg(tin, project, GpkgWriteOptions(true, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(Sqlite(project).column("SELECT count(*) FROM qgis_projects WHERE name = 'survey'"), std::vector<long long>{1});
  // A file of tinlod's alone is made anew rather than emptied and compacted.
  const std::string alone = test::tempDir() + "/alone.gpkg";
  fs::remove(alone);
  writeTinGpkg(tin, alone, GpkgWriteOptions(false, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(Sqlite(alone).column("PRAGMA page_size"), std::vector<long long>{16384});  // set as GDAL makes the file
  writeTinGpkg(tin, alone, GpkgWriteOptions(true, {{"TINLOD_KIND", "tin"}}), ProgressRange(Feedback{}, 0, 1));
  EXPECT_EQ(Sqlite(alone).column("PRAGMA page_size"), std::vector<long long>{16384});
}

TEST(GdalMetadataXml, ItemsAreAddedAndReplacedInTheDefaultDomain) {
  std::string xml =
      "<GDALMultiDomainMetadata>\n  <Metadata>\n    <MDI key=\"A\">1</MDI>\n    <MDI key=\"B\">2</MDI>\n  </Metadata>\n"
      "  <Metadata domain=\"other\">\n    <MDI key=\"C\">3</MDI>\n  </Metadata>\n</GDALMultiDomainMetadata>\n";
  ASSERT_TRUE(withGdalMetadataItems(xml, {{"B", "<&>"}, {"D", "4"}}));
  EXPECT_EQ(xml,
            "<GDALMultiDomainMetadata>\n  <Metadata>\n    <MDI key=\"A\">1</MDI>\n    <MDI key=\"B\">&lt;&amp;&gt;</MDI>\n"
            "    <MDI key=\"D\">4</MDI>\n  </Metadata>\n  <Metadata domain=\"other\">\n    <MDI key=\"C\">3</MDI>\n"
            "  </Metadata>\n</GDALMultiDomainMetadata>\n");
  std::string none = "<GDALMultiDomainMetadata>\n</GDALMultiDomainMetadata>\n";
  EXPECT_FALSE(withGdalMetadataItems(none, {{"A", "1"}}));
}

TEST(GpkgBulkWriter, LateMetadataReadsBackThroughGdal) {
  const Tin& tin = built().h.base;
  const std::string path = test::tempDir() + "/late.gpkg";
  fs::remove(path);
  GpkgWriteOptions options(false, {{"TINLOD_KIND", "tin"}, {"TINLOD_RMSE", "pending"}});
  options.lateMetadata = [] { return std::map<std::string, std::string>{{"TINLOD_RMSE", "1.5"}, {"TINLOD_X", "a&b"}}; };
  writeTinGpkg(tin, path, options, ProgressRange(Feedback{}, 0, 1));
  Dataset d(path);
  EXPECT_STREQ(d.ds->GetMetadataItem("TINLOD_KIND"), "tin");
  EXPECT_STREQ(d.ds->GetMetadataItem("TINLOD_RMSE"), "1.5");
  EXPECT_STREQ(d.ds->GetMetadataItem("TINLOD_X"), "a&b");
}

}  // namespace
}  // namespace tinlod
