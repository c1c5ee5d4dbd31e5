// SPDX-License-Identifier: GPL-3.0-or-later
// Prints issue 15's targets: the delete simplification's levels against greedy insertion
// run to exactly the same number of vertices, both measured against the DEM at every valid
// cell centre they cover. Not a timed test:
//   bench_levels_vs_insert [DEM ...]   (default: four DEMs of $TINLOD_TEST_DATA or ../shared/data)
// Per DEM (default sampling) and run (volume and error with their defaults, and error with
// max_error 10 m), one row:
// - build s: buildHierarchy alone; L0 RMSE and L0 max: level 0's own distance to the DEM
//   (the sampling's, one cell in k x k), the floor under every level and insertion;
// - at the level whose vertex count is nearest 10 % of level 0's, and at the coarsest level:
//   the level's RMSE and maximum vertical distance to the DEM, greedy insertion's over the
//   same samples with exactly as many vertices, and level / insertion for both;
// - outline %: the coarsest level's vertices on the outline of the data (TinVertex::outline);
// - over bound (the max_error 10 run only): valid cells where some level is further from
//   the DEM than max(10 m, level 0's own distance there) by more than 1e-6 m, and their
//   share of the valid cells level 0 covers;
// - peak MB: the process's peak resident memory so far.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_support.h"
#include "tinlod/crs_transform.h"
#include "tinlod/dem_reader.h"
#include "tinlod/greedy_inserter.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/insert_job.h"
#include "tinlod/nodata_filter.h"
#include "tinlod/sample_job.h"
#include "tinlod/test_grid.h"
#include "tinlod/tin_rasterizer.h"

using namespace tinlod;

namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

// A DEM, its sampled TIN (default sampling) and where the TIN's vertices fall on the DEM's grid.
struct Surface {
  explicit Surface(const std::string& path)
      : dem(readDem(path, 1, kQuiet)),
        tin(sampleTin(dem, SampleOptions{}, kQuiet)),
        toTin(CrsTransform::forDem(dem, "", "", kQuiet)) {
    const TestGrid grid = makeTestGrid(dem, 1, toTin);
    positions = gridPositions(grid, dem, tin.vertices, toTin);
    for (const TinVertex& v : tin.vertices) z.push_back(v.z);
    demZ = demHeights(dem, grid);
  }
  Dem dem;
  Tin tin;
  CrsTransform toTin;
  std::vector<std::array<double, 2>> positions;  // per vertex, in DEM cell units (step 1)
  std::vector<double> z;
  Grid demZ;  // the DEM at its cell centres, NaN where missing
};

// Distance to the DEM of a TIN over `triangles` (indexing the sampled TIN's vertices).
struct Distance {
  double rmse = NAN, max = NAN;
  std::size_t cells = 0;
};

Grid rasterize(const Surface& s, const std::vector<Triangle>& triangles) {
  return rasterizeTin(s.positions, s.z, triangles, s.demZ.cols, s.demZ.rows, kQuiet);
}

Distance distanceToDem(const Surface& s, const Grid& heights) {
  Distance d;
  double sum = 0, max = 0;
  for (std::size_t i = 0; i < heights.values.size(); ++i) {
    const double h = heights.values[i], z = s.demZ.values[i];
    if (std::isnan(h) || std::isnan(z)) continue;  // not covered, or nodata
    sum += (h - z) * (h - z), max = std::max(max, std::fabs(h - z));
    ++d.cells;
  }
  if (d.cells) d.rmse = std::sqrt(sum / d.cells), d.max = max;
  return d;
}

std::vector<Triangle> levelTriangles(const Hierarchy& h, int level) {
  std::vector<Triangle> out;
  for (std::uint32_t t : h.levelTriangles(level)) out.push_back(h.triangles[t].v);
  return out;
}

// Greedy insertion over the samples, continued to `count` vertices: its triangles as
// `tinlod sample` keeps them, indexing the sampled TIN's vertices.
std::vector<Triangle> insertTo(GreedyInserter& inserter, const Surface& s, std::size_t count) {
  inserter.run({0, count, 0}, kQuiet);
  if (inserter.vertexCount() != count)
    std::fprintf(stderr, "warning: greedy insertion stopped at %zu vertices, not %zu\n", inserter.vertexCount(), count);
  Triangulation t = inserter.triangulation();
  for (Triangle& tri : t.triangles)
    for (VertexId& v : tri) v = inserter.inserted()[v].candidate;
  return trianglesOnValidData(s.dem, t, s.tin);
}

struct Comparison {
  int level = 0;
  std::size_t vertices = 0;
  Distance levelDistance, insertDistance;
};

struct Row {
  std::string run;
  double buildSeconds = 0;
  std::size_t originalVertices = 0;
  Comparison tenPct, coarsest;
  Distance original;  // level 0's
  double outlineShare = NAN;
  long long overBound = -1;  // -1: not counted for this run
};

// Valid cells where some level above 0 is further from the DEM than max(bound, level 0's
// own distance there).
long long cellsOverBound(const Surface& s, const Hierarchy& h, const Grid& level0, double bound) {
  std::vector<char> over(level0.values.size(), 0);
  for (int L = 1; L <= h.coarsest(); ++L) {
    const Grid heights = rasterize(s, levelTriangles(h, L));
    for (std::size_t i = 0; i < heights.values.size(); ++i) {
      const double z = s.demZ.values[i];
      if (std::isnan(z) || std::isnan(heights.values[i]) || std::isnan(level0.values[i])) continue;
      const double allowed = std::max(bound, std::fabs(level0.values[i] - z));
      if (std::fabs(heights.values[i] - z) > allowed + 1e-6) over[i] = 1;
    }
  }
  return std::count(over.begin(), over.end(), 1);
}

// `level0`: level 0 rasterized; `overBound`: count the cells where a level passes the bound.
Row measureRun(const Surface& s, const std::string& name, const HierarchyOptions& options, const Grid& level0,
               bool overBound) {
  Row row;
  row.run = name;
  row.original = distanceToDem(s, level0);
  Tin taken = s.tin;  // the copy is not the build's time
  const bench::Clock::time_point t0 = bench::Clock::now();
  const Hierarchy h = buildHierarchy(std::move(taken), s.dem, {}, options, kQuiet);
  row.buildSeconds = bench::seconds(t0, bench::Clock::now());
  row.originalVertices = h.levels.front().vertices;

  // The level nearest 10 % of level 0's vertices (the coarsest when none is that small).
  const double target = 0.1 * h.levels.front().vertices;
  int near = std::min(1, h.coarsest());
  for (int L = 1; L <= h.coarsest(); ++L)
    if (std::fabs(h.levels[L].vertices - target) < std::fabs(h.levels[near].vertices - target)) near = L;
  row.tenPct.level = near, row.coarsest.level = h.coarsest();

  // One insertion run serves both sizes: the smaller first.
  GreedyInserter inserter(makeInsertGrid(s.dem, s.toTin, &s.tin), kQuiet);
  for (Comparison* c : {&row.coarsest, &row.tenPct}) {
    c->vertices = h.levels[c->level].vertices;
    c->levelDistance = distanceToDem(s, rasterize(s, levelTriangles(h, c->level)));
    c->insertDistance = distanceToDem(s, rasterize(s, insertTo(inserter, s, c->vertices)));
  }

  std::size_t inCoarsest = 0, outline = 0;
  for (std::size_t v = 0; v < h.vertexLevel.size(); ++v)
    if (h.vertexLevel[v] == h.coarsest()) ++inCoarsest, outline += h.base.vertices[v].outline;
  if (inCoarsest != h.levels.back().vertices)
    std::fprintf(stderr, "warning: %zu vertices have the coarsest level, which has %zu\n", inCoarsest, h.levels.back().vertices);
  row.outlineShare = inCoarsest ? double(outline) / inCoarsest : NAN;
  if (overBound) row.overBound = cellsOverBound(s, h, level0, options.maxError);
  return row;
}

void printHeader() {
  std::printf("%-22s %-13s %7s %8s %7s %6s |%4s %7s %8s %8s %8s %8s %6s %6s |%4s %7s %8s %8s %8s %8s %6s %6s |%8s %18s %7s\n",
              "DEM", "run", "build s", "L0 vert", "L0 RMSE", "L0 max", "lvl", "verts", "RMSE", "max", "ins RMSE", "ins max", "RMSE x",
              "max x", "lvl", "verts", "RMSE", "max", "ins RMSE", "ins max", "RMSE x", "max x", "outline%",
              "over bound (%)", "peak MB");
}

void printComparison(const Comparison& c) {
  std::printf("|%4d %7zu %8.2f %8.1f %8.2f %8.1f %6.2f %6.2f ", c.level, c.vertices, c.levelDistance.rmse,
              c.levelDistance.max, c.insertDistance.rmse, c.insertDistance.max,
              c.levelDistance.rmse / c.insertDistance.rmse, c.levelDistance.max / c.insertDistance.max);
}

void printRow(const std::string& dem, const Row& r) {
  std::printf("%-22s %-13s %7.3f %8zu %7.2f %6.1f ", dem.c_str(), r.run.c_str(), r.buildSeconds, r.originalVertices,
              r.original.rmse, r.original.max);
  printComparison(r.tenPct);
  printComparison(r.coarsest);
  std::printf("|%8.1f ", 100 * r.outlineShare);
  if (r.overBound < 0)
    std::printf("%18s ", "-");
  else
    std::printf("%9lld (%5.2f %%) ", r.overBound, 100.0 * r.overBound / r.original.cells);
  std::printf("%7.0f\n", bench::peakMegabytes());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths(argv + 1, argv + argc);
  if (paths.empty()) {
    const char* env = std::getenv("TINLOD_TEST_DATA");
    const std::string dir = env ? env : "../shared/data";
    for (const char* name : {"big_tujunga_30m.tif", "dead_sea_N31E035.tif", "fort_worth_3s.tif", "meghalaya_50m.tif"})
      paths.push_back(dir + "/" + name);
  }
  std::printf("Levels against greedy insertion with as many vertices, both against the DEM at every valid cell\n"
              "they cover; 'x' columns are level / insertion. First block: the level nearest 10 %% of level 0's\n"
              "vertices; second: the coarsest level. Over bound (error, max 10 m): cells where some level is\n"
              "further from the DEM than max(10 m, level 0's distance there).\n");
  printHeader();
  for (const std::string& path : paths) {
    const std::string name = std::filesystem::path(path).filename().string();
    if (!std::filesystem::exists(path)) {
      std::printf("%-22s skipped: %s is absent (set TINLOD_TEST_DATA or pass DEMs)\n", name.c_str(), path.c_str());
      continue;
    }
    const Surface s(path);
    HierarchyOptions volume, error, bounded;
    error.measure = bounded.measure = Measure::Error;
    bounded.maxError = 10;
    const Grid level0 = rasterize(s, s.tin.triangles);
    printRow(name, measureRun(s, "volume", volume, level0, false));
    printRow(name, measureRun(s, "error", error, level0, false));
    printRow(name, measureRun(s, "error max 10", bounded, level0, true));
  }
  return 0;
}
