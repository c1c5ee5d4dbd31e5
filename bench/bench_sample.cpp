// SPDX-License-Identifier: GPL-3.0-or-later
// Prints the throughput of the sample step (read, sample, transform, triangulate, cut
// out nodata) and of writing the GeoPackage, and the peak memory. Not a timed test:
//   bench_sample [DEM] [-block k]   (default DEM: ../shared/data/alps_2x2_N46E007_N47E008.tif)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench_support.h"
#include "tinlod/dem_reader.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/sample_job.h"

namespace {

using tinlod::bench::Clock;
using tinlod::bench::peakMegabytes;
using tinlod::bench::seconds;

// Times each phase the core names in its progress reports.
struct PhaseTimer {
  std::vector<std::pair<std::string, double>> phases;
  std::string current;
  Clock::time_point start = Clock::now();

  tinlod::Feedback feedback() {
    tinlod::Feedback f;
    f.progress = [this](double, const std::string& phase) {
      if (phase != current) switchTo(phase);
      return true;
    };
    f.info = [](const std::string& m) { std::printf("  (%s)\n", m.c_str()); };
    f.warning = [](const std::string& m) { std::printf("  warning: %s\n", m.c_str()); };
    return f;
  }
  void switchTo(const std::string& phase) {
    const Clock::time_point now = Clock::now();
    if (!current.empty()) phases.emplace_back(current, seconds(start, now));
    current = phase;
    start = now;
  }
};

}  // namespace

int main(int argc, char** argv) {
  std::string path = tinlod::bench::defaultDem();
  tinlod::SampleOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-block" && i + 1 < argc) options.block = std::atoi(argv[++i]);
    else path = a;
  }
  if (!std::filesystem::exists(path)) {
    std::printf("bench_sample: %s not found (set TINLOD_TEST_DATA or pass a DEM)\n", path.c_str());
    return 1;
  }
  PhaseTimer timer;
  const tinlod::Feedback feedback = timer.feedback();
  const tinlod::ProgressRange all(feedback, 0, 1);

  const Clock::time_point t0 = Clock::now();
  const tinlod::Dem dem = tinlod::readDem(path, options.band, all);
  const Clock::time_point t1 = Clock::now();
  const tinlod::Tin tin = tinlod::sampleTin(dem, options, all);
  const Clock::time_point t2 = Clock::now();
  timer.switchTo("Writing the GeoPackage");
  const std::string out = (std::filesystem::temp_directory_path() / "tinlod_bench_sample.gpkg").string();
  std::filesystem::remove(out);
  tinlod::writeTinGpkg(tin, out, tinlod::GpkgWriteOptions(), tinlod::ProgressRange(tinlod::Feedback{}, 0, 1));
  const Clock::time_point t3 = Clock::now();
  timer.switchTo("end");

  const double points = tin.vertices.size();
  std::printf("DEM %s: %d x %d cells, block %d\n", path.c_str(), dem.width, dem.height, options.block);
  std::printf("TIN: %zu vertices, %zu triangles\n", tin.vertices.size(), tin.triangles.size());
  std::printf("phases:\n");
  for (const auto& [phase, s] : timer.phases) std::printf("  %-26s %8.3f s\n", phase.c_str(), s);
  std::printf("read DEM                     %8.3f s  %6.2f M cells/s\n", seconds(t0, t1),
              double(dem.width) * dem.height / seconds(t0, t1) / 1e6);
  std::printf("sample step (sample..nodata) %8.3f s  %6.3f M points/s\n", seconds(t1, t2),
              points / seconds(t1, t2) / 1e6);
  std::printf("read + sample step           %8.3f s  %6.3f M points/s\n", seconds(t0, t2),
              points / seconds(t0, t2) / 1e6);
  std::printf("write GeoPackage             %8.3f s  %6.3f M features/s, %.1f MB\n", seconds(t2, t3),
              (tin.vertices.size() + tin.triangles.size()) / seconds(t2, t3) / 1e6,
              std::filesystem::file_size(out) / 1e6);
  std::printf("peak memory                  %8.1f MB\n", peakMegabytes());
  std::filesystem::remove(out);
  return 0;
}
