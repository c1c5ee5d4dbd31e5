// SPDX-License-Identifier: GPL-3.0-or-later
// Prints greedy insertion's time, vertices, RMSE, maximum error and peak memory at the
// tolerances that keep about 1 %, 0.5 % and 0.1 % of the cells. Not a timed test:
//   bench_insert [DEM]   (default: ../shared/data/alps_2x2_N46E007_N47E008.tif)
// The maximum error does not fall monotonically as points go in (a flip can make a worse
// triangle), so a run to a tolerance stops at the first count where the error is that
// low: each tolerance here is the lowest error met on the way to the target count, read
// from the error_before of one run; then a run to that tolerance is timed.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <string>

#include "bench_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/insert_job.h"

int main(int argc, char** argv) {
  using namespace tinlod;
  const std::string path = argc > 1 ? argv[1] : bench::defaultDem();
  if (!std::filesystem::exists(path)) {
    std::printf("skipped: %s is absent\n", path.c_str());
    return 0;
  }
  const ProgressRange quiet(Feedback{}, 0, 1);
  const Dem dem = readDem(path, 1, quiet);
  const std::size_t cells = dem.validCount();
  std::printf("%s: %d x %d, %zu valid cells\n", path.c_str(), dem.width, dem.height, cells);
  std::printf("%8s %10s %10s %9s %9s %10s %10s %10s %9s\n", "target", "tolerance", "vertices", "% cells", "insert s",
              "M cells/s", "RMSE m", "max err m", "peak MB");
  const CrsTransform toTin = CrsTransform::forDem(dem, "", "", quiet);
  GreedyInserter probe(makeInsertGrid(dem, toTin, nullptr), quiet);
  probe.run({0, static_cast<std::size_t>(0.01 * cells) + 1, 0}, quiet);
  for (double fraction : {0.01, 0.005, 0.001}) {
    double tolerance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 4; k <= static_cast<std::size_t>(fraction * cells); ++k)
      tolerance = std::min(tolerance, probe.inserted()[k].errorBefore);  // the error of the first k vertices
    InsertOptions o;
    o.maxError = tolerance;
    const InsertSummary s = greedyInsertionTin(dem, o, quiet).summary;
    std::printf("%7.1f%% %10.3f %10zu %9.3f %9.3f %10.2f %10.3f %10.3f %9.0f\n", 100 * fraction, tolerance, s.vertices,
                100.0 * s.vertices / cells, s.seconds, cells / s.seconds / 1e6, s.rmse, s.measuredMaxError,
                bench::peakMegabytes());
  }
  return 0;
}
