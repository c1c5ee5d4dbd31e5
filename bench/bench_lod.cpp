// SPDX-License-Identifier: GPL-3.0-or-later
// Prints the extraction time and size of varying level-of-detail TINs, and point location
// throughput, on a hierarchy built in memory. Not a timed test:
//   bench_lod [DEM]   (default: ../shared/data/alps_2x2_N46E007_N47E008.tif)
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "bench_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/hierarchy_builder.h"
#include "tinlod/hierarchy_locator.h"
#include "tinlod/lod_extraction.h"
#include "tinlod/sample_job.h"

namespace {

using namespace tinlod;

void extract(const Hierarchy& h, const char* label, const LodOptions& o) {
  const auto start = bench::Clock::now();
  const std::size_t triangles = extractLod(h, o, ProgressRange(Feedback{}, 0, 1)).size();
  std::printf("  %-34s %9zu triangles (%5.1f %% of level 0) in %.3f s\n", label, triangles,
              100.0 * triangles / h.levels[0].triangles, bench::seconds(start, bench::Clock::now()));
}

void locate(const Hierarchy& h, const HierarchyLocator& locator, int level, double x0, double x1, double y0, double y1) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> x(x0, x1), y(y0, y1);
  const int n = 1000000;
  std::size_t found = 0;
  const auto start = bench::Clock::now();
  for (int i = 0; i < n; ++i) found += locator.locate(x(rng), y(rng), level).found();
  const double s = bench::seconds(start, bench::Clock::now());
  std::printf("  level %2d: %.2f M random points/s (%zu of %d on the TIN)\n", level, n / s / 1e6, found, n);
  (void)h;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : bench::defaultDem();
  if (!std::filesystem::exists(path)) {
    std::printf("skipped: %s is absent\n", path.c_str());
    return 0;
  }
  const ProgressRange quiet(Feedback{}, 0, 1);
  const Dem dem = readDem(path, 1, quiet);
  const Tin tin = sampleTin(dem, SampleOptions{}, quiet);
  Hierarchy h = buildHierarchy(tin, dem, {}, HierarchyOptions{}, quiet);
  linkGroups(h);  // extractLod reads the groups' links
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const TinVertex& v : h.base.vertices) x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
  std::printf("%s: %zu levels, %zu triangles at level 0, %zu at the coarsest, extent %.0f x %.0f m\n", path.c_str(),
              h.levels.size(), h.levels[0].triangles, h.levels.back().triangles, x1 - x0, y1 - y0);
  std::printf("Extraction (centre in the middle):\n");
  LodOptions o;
  o.centres = {{(x0 + x1) / 2, (y0 + y1) / 2}};
  for (double dropoff : {500.0, 2000.0, 8000.0}) {
    o.dropoff = dropoff;
    extract(h, ("dropoff " + std::to_string(int(dropoff)) + " m").c_str(), o);
  }
  LodOptions e;
  for (double tol : {50.0, 10.0}) {
    e.maxError = tol;
    extract(h, ("max error " + std::to_string(int(tol)) + " m").c_str(), e);
  }
  e.maxError = 5, e.errorGrowth = 0.002, e.centres = o.centres;
  extract(h, "max error 5 m + 0.002 m/m", e);
  std::printf("Point location:\n");
  const auto start = bench::Clock::now();
  const HierarchyLocator locator(h);
  std::printf("  locator built in %.2f s\n", bench::seconds(start, bench::Clock::now()));
  for (int level : {0, h.coarsest() / 2, h.coarsest()}) locate(h, locator, level, x0, x1, y0, y1);
  std::printf("peak %.0f MB\n", bench::peakMegabytes());
  return 0;
}
