// SPDX-License-Identifier: GPL-3.0-or-later
// Prints the figures of the accuracy evaluation of every level of a hierarchy at the
// DEM's resolution: test points per second for interpolation, for the B-spline fit and
// for curvature, each on all cores, and the whole evaluation per level. Not a timed test:
//   bench_accuracy [DEM] [-control c]
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include "bench_support.h"
#include "parallel_blocks.h"
#include "tinlod/accuracy_evaluator.h"
#include "tinlod/dem_reader.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/sample_job.h"
#include "tinlod/terrain_measures.h"
#include "tinlod/tin_rasterizer.h"

using tinlod::bench::Clock;
using tinlod::bench::seconds;

namespace {

const tinlod::ProgressRange kQuiet(tinlod::Feedback{}, 0, 1);

// Fit and curvature timed apart: evaluating rows, then measures of the evaluated points.
void timeSurface(const tinlod::Grid& heights, const tinlod::TestGrid& grid, int control, double& fit, double& curvature) {
  const tinlod::BsplineSurface surface(heights, control, grid.cellWidth, grid.cellHeight);
  std::vector<std::vector<tinlod::SurfacePoint>> rows(grid.rows);
  const Clock::time_point t0 = Clock::now();
  tinlod::forEachBlock(grid.rows, [&](int b, int e) { for (int r = b; r < e; ++r) surface.evaluateRow(r, rows[r]); }, {});
  const Clock::time_point t1 = Clock::now();
  std::vector<double> sink(grid.rows);
  tinlod::forEachBlock(grid.rows, [&](int b, int e) {
    for (int r = b; r < e; ++r)
      for (const tinlod::SurfacePoint& p : rows[r]) sink[r] += tinlod::terrainMeasures(p).meanCurvature;
  }, {});
  fit = seconds(t0, t1), curvature = seconds(t1, Clock::now());
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = tinlod::bench::defaultDem();
  int control = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-control" && i + 1 < argc) control = std::atoi(argv[++i]);
    else path = a;
  }
  if (!std::filesystem::exists(path)) {
    std::printf("bench_accuracy: %s not found (set TINLOD_TEST_DATA or pass a DEM)\n", path.c_str());
    return 1;
  }
  const tinlod::Dem dem = tinlod::readDem(path, 1, kQuiet);
  const tinlod::Tin tin = tinlod::sampleTin(dem, {}, kQuiet);
  const tinlod::Hierarchy h = tinlod::buildHierarchy(tin, dem, {}, tinlod::HierarchyOptions(), kQuiet);
  const tinlod::CrsTransform toTin = tinlod::CrsTransform::forDem(dem, "", "", kQuiet);
  tinlod::AccuracyOptions options;
  options.controlSpacing = control;
  Clock::time_point t0 = Clock::now();
  const tinlod::AccuracyEvaluator evaluator(dem, tin, toTin, options, kQuiet);
  const tinlod::TestGrid& grid = evaluator.grid();
  const double points = double(grid.cols) * grid.rows;
  std::printf("DEM %s: %d x %d test points (%.1f M), %d levels, control spacing %d, %u threads; set-up %.2f s\n",
              path.c_str(), grid.cols, grid.rows, points / 1e6, h.coarsest() + 1, control,
              std::thread::hardware_concurrency(), seconds(t0, Clock::now()));
  const auto positions = tinlod::gridPositions(grid, dem, tin.vertices, toTin);
  std::vector<double> z;
  for (const tinlod::TinVertex& v : tin.vertices) z.push_back(v.z);
  std::printf("%6s %10s %12s %12s %12s %12s %10s %10s\n", "level", "vertices", "interp M/s", "fit M/s", "curv M/s",
              "whole s", "RMSE m", "r mean H");
  double interpAll = 0, fitAll = 0, curvAll = 0, wholeAll = 0;
  for (int L = 0; L <= h.coarsest(); ++L) {
    std::vector<tinlod::Triangle> triangles;
    for (std::uint32_t t : h.levelTriangles(L)) triangles.push_back(h.triangles[t].v);
    t0 = Clock::now();
    const tinlod::Grid heights = tinlod::rasterizeTin(positions, z, triangles, grid.cols, grid.rows, kQuiet);
    const double interp = seconds(t0, Clock::now());
    double fit = 0, curvature = 0;
    timeSurface(heights, grid, control, fit, curvature);
    tinlod::LevelAccuracy row;
    t0 = Clock::now();
    evaluator.evaluate(triangles, row, nullptr, kQuiet);
    const double whole = seconds(t0, Clock::now());
    std::printf("%6d %10zu %12.1f %12.1f %12.1f %12.2f %10.2f %10.4f\n", L, h.levels[L].vertices, points / interp / 1e6,
                points / fit / 1e6, points / curvature / 1e6, whole, row.rmse, tinlod::correlationOf(row, "mean_curvature"));
    interpAll += interp, fitAll += fit, curvAll += curvature, wholeAll += whole;
  }
  const int n = h.coarsest() + 1;
  std::printf("all levels: interpolation %.1f M points/s, fit %.1f M points/s, curvature %.1f M points/s, "
              "fit with curvature %.1f M points/s; whole evaluation %.2f s per level (%.1f M points/s)\n",
              n * points / interpAll / 1e6, n * points / fitAll / 1e6, n * points / curvAll / 1e6,
              n * points / (fitAll + curvAll) / 1e6, wholeAll / n, n * points / wholeAll / 1e6);
  std::printf("peak memory: %.1f MB\n", tinlod::bench::peakMegabytes());
  return 0;
}
