// SPDX-License-Identifier: GPL-3.0-or-later
// Tiles under an error bound agree their border lines in rounds (-border_keep), as
// tinlod tiles runs them: in the end both tiles of every line keep the same vertices at
// every level, and every cell of the raster stays within the bound, on both sides.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_borders.h"

namespace tinlod {
namespace {

constexpr int kWidth = 150, kHeight = 120, kTile = 60;  // 3 x 2 tiles
constexpr double kMaxError = 1.0;
const ProgressRange kQuiet(Feedback{}, 0, 1);

std::string roughDem() {
  static const std::string path = [] {
    SyntheticDemOptions o;
    o.width = kWidth, o.height = kHeight, o.cellSize = 25;
    const std::string p = test::tempDir() + "/agreement_dem.tif";
    writeDemGeoTiff(makeSyntheticDem(o), p);
    return p;
  }();
  return path;
}

using Cell = std::pair<long long, long long>;  // row, col of the whole raster

std::set<Cell> cellsIn(const char* text) {
  std::set<Cell> out;
  std::istringstream parts(text ? text : "");
  std::string part;
  while (std::getline(parts, part, ';')) {
    std::istringstream fields(part);
    Cell c;
    if (fields >> c.first >> c.second) out.insert(c);
  }
  return out;
}

std::string metadataItem(const std::string& gpkg, const char* key) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR));
  const char* value = ds ? ds->GetMetadataItem(key) : nullptr;
  return value ? value : "";
}

struct Job {
  std::string dem;
  int size;  // cells per tile side
  double maxError;
  Dem whole;
  std::string dir = test::tempDir();
  std::vector<TileSpec> tiles;
  std::set<Cell> kept;

  Job(std::string demPath, int tileSize, double bound)
      : dem(std::move(demPath)), size(tileSize), maxError(bound), whole(readDem(dem, 1, kQuiet)) {
    for (int row = 0; row < TileSpec::count(whole.height, size); ++row)
      for (int col = 0; col < TileSpec::count(whole.width, size); ++col) tiles.push_back({size, col, row});
  }
  std::string file(const TileSpec& t) const { return dir + "/tile_" + std::to_string(t.col) + "_" + std::to_string(t.row) + ".gpkg"; }
  HierarchyOptions options() const {
    HierarchyOptions o;
    o.measure = Measure::Error;
    o.maxError = maxError;
    return o;
  }

  // Builds every tile with the kept cells so far; returns the cells they refused.
  std::set<Cell> round() {
    const std::string keep = dir + "/keep.txt";
    std::ofstream out(keep);
    for (const Cell& c : kept) out << c.first << " " << c.second << "\n";
    out.close();
    HierarchyOptions o = options();
    o.borderKeep = keep;
    std::set<Cell> refused;
    for (const TileSpec& t : tiles) {
      runBuildJob(dem, file(t), {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), t);
      EXPECT_EQ(metadataItem(file(t), "TINLOD_BORDER_AGREED"), "yes");
      for (const Cell& c : cellsIn(metadataItem(file(t), "TINLOD_BORDER_REFUSED").c_str())) refused.insert(c);
    }
    return refused;
  }

  // Rounds until no tile refuses a line vertex (at most 10); returns how many were made.
  int agree() {
    int rounds = 0;
    for (std::set<Cell> refused = {{-1, -1}}; !refused.empty() && rounds < 10; ++rounds) {
      refused = round();
      kept.insert(refused.begin(), refused.end());
      if (rounds == 9) EXPECT_TRUE(refused.empty()) << "still refusing after 10 rounds";
    }
    return rounds;
  }
};

// By shared line (a column or a row of the whole raster, and the tile row or column along
// it) and level: the cells of the line's vertices a tile has at that level. A tile's
// stored rows and columns are its window's (TINLOD_TILE_WINDOW gives where it starts).
using LineKey = std::tuple<char, long long, int>;
std::map<std::pair<LineKey, int>, std::multiset<long long>> lineVertices(const Job& job) {
  std::map<std::pair<LineKey, int>, std::multiset<long long>> out;
  const int across = TileSpec::count(job.whole.width, job.size), down = TileSpec::count(job.whole.height, job.size);
  for (const TileSpec& t : job.tiles) {
    const Hierarchy h = readHierarchy(job.file(t), kQuiet).hierarchy;
    long long col0 = 0, row0 = 0;
    std::sscanf(metadataItem(job.file(t), "TINLOD_TILE_WINDOW").c_str(), "%lld,%lld", &col0, &row0);
    const long long firstCol = t.col * job.size, lastCol = (t.col + 1) * job.size;
    const long long firstRow = t.row * job.size, lastRow = (t.row + 1) * job.size;
    for (VertexId v = 0; v < h.base.vertices.size(); ++v) {
      const long long row = row0 + h.base.vertices[v].row, col = col0 + h.base.vertices[v].col;
      std::vector<std::pair<LineKey, long long>> on;  // the line, and the cell's place along it
      if (t.col > 0 && col == firstCol) on.push_back({{'c', col, t.row}, row});
      if (t.col + 1 < across && col == lastCol) on.push_back({{'c', col, t.row}, row});
      if (t.row > 0 && row == firstRow) on.push_back({{'r', row, t.col}, col});
      if (t.row + 1 < down && row == lastRow) on.push_back({{'r', row, t.col}, col});
      for (const auto& [key, along] : on)
        for (int level = 0; level <= h.vertexLevel[v] && level <= h.coarsest(); ++level) out[{key, level}].insert(along);
    }
  }
  return out;
}

// Places on lines, at some level, that only one of the line's two tiles holds, of those
// both hold at level 0 (beside a void, a line cell may be a vertex of one tile only: the
// other has no triangle there).
int disagreements(const Job& job) {
  const auto all = lineVertices(job);
  int differing = 0;
  for (const auto& [key, places] : all) {
    const auto& zero = all.at({key.first, 0});
    for (long long p : std::set<long long>(places.begin(), places.end())) differing += places.count(p) == 1 && zero.count(p) == 2;
  }
  return differing;
}

// Each valid cell centre's distance to a level, its vertices put back on the whole
// raster's grid from their x and y (the DEM's CRS may not be the TIN's; the stored rows
// and columns, without the jitter, are not read).
std::vector<double> cellDistances(const Dem& whole, const Hierarchy& h, std::int32_t level) {
  std::vector<double> x, y;
  for (const TinVertex& v : h.base.vertices) x.push_back(v.x), y.push_back(v.y);
  CrsTransform::forDem(whole, "", h.base.crsWkt, kQuiet).applyInverse(x, y);
  const auto& g = whole.geotransform;
  return test::cellDistances(whole, h, level, [&](const TinVertex& v) {
    const std::size_t i = static_cast<std::size_t>(&v - h.base.vertices.data());
    return std::array<double, 2>{(x[i] - g[0]) / g[1] - 0.5, (y[i] - g[3]) / g[5] - 0.5};
  });
}

// Cells of any tile's level further than max(-max_error, level 0's distance there).
std::int64_t cellsBeyondTheBound(const Job& job) {
  std::int64_t beyond = 0;
  for (const TileSpec& t : job.tiles) {
    const Hierarchy h = readHierarchy(job.file(t), kQuiet).hierarchy;
    const std::vector<double> zero = cellDistances(job.whole, h, 0);
    for (std::int32_t level = 1; level <= h.coarsest(); ++level) {
      const std::vector<double> d = cellDistances(job.whole, h, level);
      for (std::size_t i = 0; i < d.size(); ++i) {
        const double allowed = std::isnan(zero[i]) ? job.maxError : std::max(job.maxError, zero[i]);
        beyond += !std::isnan(d[i]) && d[i] > allowed + 1e-6;
      }
    }
  }
  return beyond;
}

// Line vertices that go at some level: the agreement deletes them, not only keeps them.
std::size_t lineVerticesGone(const Job& job) {
  std::map<LineKey, std::pair<std::size_t, std::size_t>> counts;  // at level 0, and the fewest at any level
  for (const auto& [key, places] : lineVertices(job)) {
    auto& [first, fewest] = counts.try_emplace(key.first, places.size(), places.size()).first->second;
    if (key.second == 0) first = places.size();
    fewest = std::min(fewest, places.size());
  }
  std::size_t gone = 0;
  for (const auto& [key, c] : counts) gone += c.first - c.second;
  return gone;
}

TEST(BorderAgreement, RoundsEndWithTheSameLinesAndEveryCellWithinTheBound) {
  Job job(roughDem(), kTile, kMaxError);
  ASSERT_EQ(job.tiles.size(), 6u);
  std::set<Cell> refused = job.round();
  // The first round: each tile refused on its own side, so some lines disagree (23
  // refusals, 112 places); every tile alone keeps its cells within the bound.
  ASSERT_FALSE(refused.empty());
  EXPECT_GT(disagreements(job), 0);
  EXPECT_EQ(cellsBeyondTheBound(job), 0);
  job.kept = refused;
  const int rounds = 1 + job.agree();
  EXPECT_LE(rounds, 4);
  EXPECT_EQ(disagreements(job), 0);
  EXPECT_EQ(cellsBeyondTheBound(job), 0);  // 1297 cells when no tile refuses (checked)
  EXPECT_GT(lineVerticesGone(job), 10u);   // 12 (2 rounds)
  // Every tile recorded the kept cells of its own lines: each kept cell by both tiles of
  // its line (none is a tile corner, which never goes).
  std::map<Cell, int> recorded;
  for (const TileSpec& t : job.tiles)
    for (const Cell& c : cellsIn(metadataItem(job.file(t), "TINLOD_BORDER_KEPT").c_str())) ++recorded[c];
  EXPECT_EQ(recorded.size(), job.kept.size());
  for (const Cell& c : job.kept) EXPECT_EQ(recorded[c], 2) << "cell " << c.first << " " << c.second;
}

// A geographic DEM with SRTM voids, the TIN in UTM: the same, with holes reaching the lines.
TEST(BorderAgreement, ARealGeographicDemWithVoids) {
  const std::string dir = test::dataDir();
  if (dir.empty()) GTEST_SKIP() << "../shared/data is absent (set TINLOD_TEST_DATA): real-DEM test skipped";
  Job job(dir + "/swiss_alps_N46E008.tif", 600, 10);
  ASSERT_EQ(job.tiles.size(), 4u);
  const int rounds = job.agree();
  EXPECT_GE(rounds, 2);  // some line vertex was refused
  EXPECT_EQ(disagreements(job), 0);
  EXPECT_EQ(cellsBeyondTheBound(job), 0);  // 3877 cells when no tile refuses (checked)
  EXPECT_GT(lineVerticesGone(job), 100u);
}

// Without -border_keep a bounded tile keeps its lines whole: nothing to agree.
TEST(BorderAgreement, WithoutAKeepFileABoundedTileKeepsItsLines) {
  Job job(roughDem(), kTile, kMaxError);
  for (const TileSpec& t : job.tiles) {
    runBuildJob(roughDem(), job.file(t), {}, job.options(), true, {}, AccuracyOutputs(), HierarchyLayers(), t);
    EXPECT_EQ(metadataItem(job.file(t), "TINLOD_BORDER_AGREED"), "");
  }
  EXPECT_EQ(lineVerticesGone(job), 0u);
  EXPECT_EQ(disagreements(job), 0);
  EXPECT_EQ(cellsBeyondTheBound(job), 0);
}

TEST(BorderAgreement, RefusesABadKeepFileAndOtherMethods) {
  const std::string dir = test::tempDir();
  HierarchyOptions o;
  o.measure = Measure::Error;
  o.maxError = kMaxError;
  o.borderKeep = dir + "/absent.txt";
  const TileSpec tile{kTile, 0, 0};
  const auto build = [&] { runBuildJob(roughDem(), dir + "/t.gpkg", {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), tile); };
  EXPECT_THROW(build(), Error);
  std::ofstream(dir + "/bad.txt") << "12 7\n3 x\n";
  o.borderKeep = dir + "/bad.txt";
  try {
    build();
    ADD_FAILURE() << "a bad line was read";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "line 2")) << e.what();
  }
  std::ofstream(dir + "/good.txt") << "# kept\n12 60\n\n";
  o.borderKeep = dir + "/good.txt";
  EXPECT_NO_THROW(build());
  o.maxError = INFINITY;
  EXPECT_THROW(build(), Error);  // an unbounded error method needs no agreement
  o.measure = Measure::Volume;
  EXPECT_THROW(build(), Error);
  o.measure = Measure::Error, o.maxError = kMaxError;
  EXPECT_THROW(runBuildJob(roughDem(), dir + "/w.gpkg", {}, o, true, {}), Error);  // not a tile
  EXPECT_FALSE(std::filesystem::exists(dir + "/w.gpkg"));
}

}  // namespace
}  // namespace tinlod
