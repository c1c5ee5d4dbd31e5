// SPDX-License-Identifier: GPL-3.0-or-later
// Prints the figures of the delete simplification: time per level split into select and
// delete, vertices removed per second, peak memory; and CGAL's bare remove() rate on the
// same TIN for comparison. Not a timed test:
//   bench_build [DEM] [-method m] [-delete_pct p] [-stop_pct s] [-out OUT.gpkg]
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bench_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/sample_job.h"

using tinlod::bench::Clock;
using tinlod::bench::cpuSeconds;
using tinlod::bench::peakMegabytes;
using tinlod::bench::seconds;

double bareRemoveRate(const tinlod::Tin& tin, std::size_t count);  // bench_bare_remove.cpp

int main(int argc, char** argv) {
  std::string path = tinlod::bench::defaultDem();
  tinlod::HierarchyOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-method" && i + 1 < argc) options.measure = tinlod::parseMeasure(argv[++i]);
    else if (a == "-delete_pct" && i + 1 < argc) options.deletePct = std::atof(argv[++i]);
    else if (a == "-stop_pct" && i + 1 < argc) options.stopPct = std::atof(argv[++i]);
    else if (a == "-max_error" && i + 1 < argc) options.maxError = std::atof(argv[++i]);
    else if (a == "-keep_outline") options.keepOutline = true;
    else path = a;
  }
  if (!std::filesystem::exists(path)) {
    std::printf("bench_build: %s not found (set TINLOD_TEST_DATA or pass a DEM)\n", path.c_str());
    return 1;
  }
  const tinlod::ProgressRange quiet(tinlod::Feedback{}, 0, 1);
  const tinlod::Dem dem = tinlod::readDem(path, 1, quiet);
  const tinlod::Tin tin = tinlod::sampleTin(dem, {}, quiet);
  tinlod::Tin taken = tin;  // the build takes its TIN over, as the command line's does
  const double cpu0 = cpuSeconds();
  const Clock::time_point t0 = Clock::now();
  const tinlod::Hierarchy h = tinlod::buildHierarchy(std::move(taken), dem, {}, options, quiet);
  const Clock::time_point t1 = Clock::now();
  const double cpu = cpuSeconds() - cpu0;
  std::size_t removed = h.levels.front().vertices - h.levels.back().vertices;
  std::printf("DEM %s: %zu vertices at level 0, method %s, delete %g %%, stop %g %%\n", path.c_str(),
              h.levels[0].vertices, tinlod::measureName(options.measure).c_str(), options.deletePct, options.stopPct);
  std::printf("%6s %10s %10s %9s %10s %10s %10s %9s %9s %10s\n", "level", "vertices", "triangles", "deleted", "select s",
              "delete s", "max err m", "RMSE m", "outline", "net lost");
  double select = 0, remove = 0;
  for (const tinlod::LevelStats& l : h.levels) {
    std::printf("%6d %10zu %10zu %9zu %10.3f %10.3f %10.2f %9.2f %8.1f%% %10lld\n", l.level, l.vertices, l.triangles,
                l.deleted, l.selectSeconds, l.deleteSeconds, l.maxError, l.rmse, 100.0 * l.outlineVertices / l.vertices,
                static_cast<long long>(h.levels.front().cells - l.cells));
    select += l.selectSeconds, remove += l.deleteSeconds;
  }
  const double total = seconds(t0, t1);
  std::printf("build: %.3f s in all (%.3f select, %.3f delete, %.3f set-up); %.3f M vertices removed/s; %.3f CPU s\n",
              total, select, remove, total - select - remove, removed / total / 1e6, cpu);
  std::printf("select %s delete (the study found select slower)\n", select > remove ? "slower than" : "faster than");
  // CGAL's removals take inner vertices only: as many as there are, less a tenth (the last
  // ones left beside a raster edge's straight line of vertices have stars of thousands).
  std::size_t inner = 0;
  for (const tinlod::TinVertex& v : tin.vertices) inner += !v.outline;
  std::fflush(stdout);  // the figures above stand even if the comparison fails
  const double bare = bareRemoveRate(tin, std::min(removed, inner - inner / 10));
  std::printf("CGAL bare remove() on the same TIN: %.3f M vertices/s; the build takes %.2fx its time (aim: 2x)\n", bare,
              bare / (removed / total / 1e6));
  std::printf("peak memory: %.1f MB\n", peakMegabytes());
  return 0;
}
