// SPDX-License-Identifier: GPL-3.0-or-later
// Tiles under an error bound agree their border lines in rounds (-border_keep), as
// tinlod tiles runs them: in the end both tiles of every line keep the same vertices at
// every level, and every cell of the raster stays within the bound, on both sides.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "mesh_checks.h"
#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/dem_reader.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/synthetic_dem.h"
#include "tinlod/tile_borders.h"

namespace tinlod {
namespace {

constexpr int kWidth = 150, kHeight = 120, kTile = 60;
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
  std::string dir = test::tempDir();
  std::vector<TileSpec> tiles;
  std::set<Cell> kept;

  Job() {
    for (int row = 0; row < TileSpec::count(kHeight, kTile); ++row)
      for (int col = 0; col < TileSpec::count(kWidth, kTile); ++col) tiles.push_back({kTile, col, row});
  }
  std::string file(const TileSpec& t) const { return dir + "/tile_" + std::to_string(t.col) + "_" + std::to_string(t.row) + ".gpkg"; }

  // Builds every tile with the kept cells so far; returns the cells they refused.
  std::set<Cell> round() {
    const std::string keep = dir + "/keep.txt";
    std::ofstream out(keep);
    for (const Cell& c : kept) out << c.first << " " << c.second << "\n";
    out.close();
    HierarchyOptions o;
    o.measure = Measure::Error;
    o.maxError = kMaxError;
    o.borderKeep = keep;
    std::set<Cell> refused;
    for (const TileSpec& t : tiles) {
      runBuildJob(roughDem(), file(t), {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), t);
      EXPECT_EQ(metadataItem(file(t), "TINLOD_BORDER_AGREED"), "yes");
      for (const Cell& c : cellsIn(metadataItem(file(t), "TINLOD_BORDER_REFUSED").c_str())) refused.insert(c);
    }
    return refused;
  }
};

// By shared line (a column or a row of the whole raster, and the tile row or column along
// it) and level: the places of the line's vertices a tile has at that level.
using LineKey = std::tuple<char, int, int>;
std::map<std::pair<LineKey, int>, std::multiset<double>> lineVertices(const Job& job, const Dem& whole) {
  std::map<std::pair<LineKey, int>, std::multiset<double>> out;
  const int across = TileSpec::count(kWidth, kTile), down = TileSpec::count(kHeight, kTile);
  for (const TileSpec& t : job.tiles) {
    const Hierarchy h = readHierarchy(job.file(t), kQuiet).hierarchy;
    std::vector<std::pair<LineKey, double>> lines;  // the line, and its x (a column) or y (a row)
    const auto columnX = [&](int col) { return whole.geotransform[0] + (col + 0.5) * whole.geotransform[1]; };
    const auto rowY = [&](int row) { return whole.geotransform[3] + (row + 0.5) * whole.geotransform[5]; };
    if (t.col > 0) lines.push_back({{'c', t.col * kTile, t.row}, columnX(t.col * kTile)});
    if (t.col + 1 < across) lines.push_back({{'c', (t.col + 1) * kTile, t.row}, columnX((t.col + 1) * kTile)});
    if (t.row > 0) lines.push_back({{'r', t.row * kTile, t.col}, rowY(t.row * kTile)});
    if (t.row + 1 < down) lines.push_back({{'r', (t.row + 1) * kTile, t.col}, rowY((t.row + 1) * kTile)});
    for (VertexId v = 0; v < h.base.vertices.size(); ++v)
      for (const auto& [key, at] : lines) {
        const bool column = std::get<0>(key) == 'c';
        const TinVertex& p = h.base.vertices[v];
        if (std::fabs((column ? p.x : p.y) - at) > 1e-6) continue;
        for (int level = 0; level <= h.vertexLevel[v] && level <= h.coarsest(); ++level)
          out[{key, level}].insert(column ? p.y : p.x);
      }
  }
  return out;
}

// Levels of lines whose two tiles hold different vertices.
int disagreements(const Job& job, const Dem& whole) {
  const auto all = lineVertices(job, whole);
  // Each tile's vertices of a line were pooled: both hold them alike when every place is
  // there an even number of times (twice: once a tile).
  int differing = 0;
  for (const auto& [key, places] : all)
    for (double p : std::set<double>(places.begin(), places.end())) differing += places.count(p) != 2;
  return differing;
}

// Each valid cell centre's distance to a level, its vertices placed in the whole raster's
// grid by their x and y (the stored rows and columns are not read).
std::vector<double> cellDistances(const Dem& whole, const Hierarchy& h, std::int32_t level) {
  const auto& g = whole.geotransform;
  return test::cellDistances(whole, h, level, [&](const TinVertex& v) {
    return std::array<double, 2>{(v.x - g[0]) / g[1] - 0.5, (v.y - g[3]) / g[5] - 0.5};
  });
}

// Cells of any tile's level further than max(-max_error, level 0's distance there).
std::int64_t cellsBeyondTheBound(const Job& job, const Dem& whole) {
  std::int64_t beyond = 0;
  for (const TileSpec& t : job.tiles) {
    const Hierarchy h = readHierarchy(job.file(t), kQuiet).hierarchy;
    const std::vector<double> zero = cellDistances(whole, h, 0);
    for (std::int32_t level = 1; level <= h.coarsest(); ++level) {
      const std::vector<double> d = cellDistances(whole, h, level);
      for (std::size_t i = 0; i < d.size(); ++i) {
        const double allowed = std::isnan(zero[i]) ? kMaxError : std::max(kMaxError, zero[i]);
        beyond += !std::isnan(d[i]) && d[i] > allowed + 1e-6;
      }
    }
  }
  return beyond;
}

// Line vertices that go at some level: the agreement deletes them, not only keeps them.
std::size_t lineVerticesGone(const Job& job, const Dem& whole) {
  std::map<LineKey, std::pair<std::size_t, std::size_t>> counts;  // at level 0, and the fewest at any level
  for (const auto& [key, places] : lineVertices(job, whole)) {
    auto& [first, fewest] = counts.try_emplace(key.first, places.size(), places.size()).first->second;
    if (key.second == 0) first = places.size();
    fewest = std::min(fewest, places.size());
  }
  std::size_t gone = 0;
  for (const auto& [key, c] : counts) gone += c.first - c.second;
  return gone;
}

TEST(BorderAgreement, RoundsEndWithTheSameLinesAndEveryCellWithinTheBound) {
  const Dem whole = readDem(roughDem(), 1, kQuiet);
  Job job;
  ASSERT_EQ(job.tiles.size(), 6u);
  std::set<Cell> refused = job.round();
  // The first round: each tile refused on its own side, so some lines disagree (23
  // refusals, 112 places); every tile alone keeps its cells within the bound.
  ASSERT_FALSE(refused.empty());
  EXPECT_GT(disagreements(job, whole), 0);
  EXPECT_EQ(cellsBeyondTheBound(job, whole), 0);
  int rounds = 1;
  while (!refused.empty() && rounds < 10) {
    job.kept.insert(refused.begin(), refused.end());
    refused = job.round();
    ++rounds;
  }
  EXPECT_TRUE(refused.empty()) << "still refusing after " << rounds << " rounds";
  EXPECT_LE(rounds, 4);
  EXPECT_EQ(disagreements(job, whole), 0);
  EXPECT_EQ(cellsBeyondTheBound(job, whole), 0);  // 1297 cells when no tile refuses (checked)
  EXPECT_GT(lineVerticesGone(job, whole), 10u);     // 12 (2 rounds)
  // Every tile recorded the kept cells of its own lines: each kept cell by both tiles of
  // its line (none is a tile corner, which never goes).
  std::map<Cell, int> recorded;
  for (const TileSpec& t : job.tiles)
    for (const Cell& c : cellsIn(metadataItem(job.file(t), "TINLOD_BORDER_KEPT").c_str())) ++recorded[c];
  EXPECT_EQ(recorded.size(), job.kept.size());
  for (const Cell& c : job.kept) EXPECT_EQ(recorded[c], 2) << "cell " << c.first << " " << c.second;
}

// Without -border_keep a bounded tile keeps its lines whole: nothing to agree.
TEST(BorderAgreement, WithoutAKeepFileABoundedTileKeepsItsLines) {
  const Dem whole = readDem(roughDem(), 1, kQuiet);
  Job job;
  HierarchyOptions o;
  o.measure = Measure::Error;
  o.maxError = kMaxError;
  for (const TileSpec& t : job.tiles) {
    runBuildJob(roughDem(), job.file(t), {}, o, true, {}, AccuracyOutputs(), HierarchyLayers(), t);
    EXPECT_EQ(metadataItem(job.file(t), "TINLOD_BORDER_AGREED"), "");
  }
  EXPECT_EQ(lineVerticesGone(job, whole), 0u);
  EXPECT_EQ(disagreements(job, whole), 0);
  EXPECT_EQ(cellsBeyondTheBound(job, whole), 0);
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
