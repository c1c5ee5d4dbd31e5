// SPDX-License-Identifier: GPL-3.0-or-later
// Every reader of tinlod GeoPackages on randomly damaged copies of a small hierarchy. Each
// run must read the copy or refuse it with a tinlod::Error: another exception fails the
// test, a crash ends it, and a hang is stopped by a watchdog that names the case. The
// seed is fixed, so a failure comes back on every run; TINLOD_FUZZ_CASES and
// TINLOD_FUZZ_SEED make longer or other runs (docs/robustness.md).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <future>
#include <iostream>
#include <string>
#include <typeinfo>
#include <vector>

#include "gpkg_mutator.h"
#include "gpkg_surgery.h"
#include "test_support.h"
#include "tinlod/accuracy_job.h"
#include "tinlod/error.h"
#include "tinlod/hierarchy_info.h"
#include "tinlod/hierarchy_reader.h"
#include "tinlod/locate_job.h"
#include "tinlod/lod_job.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const ProgressRange kQuiet(Feedback{}, 0, 1);

constexpr std::uint64_t kSeed = 16;         // issue 16
constexpr std::uint64_t kCases = 300;       // some 25 s in a Release build
constexpr std::uint64_t kCaseSeconds = 60;  // a case takes well under a second, under ASan too

std::uint64_t fromEnvironment(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (*end) ADD_FAILURE() << name << "=" << text << " is not a whole number: " << fallback << " used";
  return *end ? fallback : value;
}

struct Reader {
  const char* name;
  std::function<void(const std::string& gpkg, const std::string& outDir)> run;
};

std::vector<Reader> everyReader(const test::SmallHierarchy& s) {
  return {
      {"info",
       [](const std::string& gpkg, const std::string&) {
         const HierarchyInfo info = readHierarchyInfo(gpkg);
         toText(info), toJson(info);
       }},
      {"readHierarchy", [](const std::string& gpkg, const std::string&) { readHierarchy(gpkg, kQuiet); }},
      {"lod",
       [](const std::string& gpkg, const std::string& out) {
         LodJobOptions o;
         o.lod.maxError = 0;  // refines every group: every link is followed
         runLodJob(gpkg, out + "/lod.gpkg", o, true, {});
       }},
      {"locate at level 0",
       [&s](const std::string& gpkg, const std::string& out) {
         runLocateJob(gpkg, s.points, out + "/points.gpkg", 0, true, {});
       }},
      {"locate at the coarsest level",
       [&s](const std::string& gpkg, const std::string& out) {
         const int top = static_cast<int>(readHierarchyInfo(gpkg).levels.size()) - 1;
         runLocateJob(gpkg, s.points, out + "/points.gpkg", top, true, {});
       }},
      {"accuracy",
       [&s](const std::string& gpkg, const std::string&) {
         runAccuracyJob(s.dem, gpkg, AccuracyOutputs{}, 0, "", {});
       }},
  };
}

struct CaseResult {
  std::size_t read = 0, refused = 0;
  std::vector<std::string> problems;  // anything but success or an Error
};

CaseResult runReaders(const std::vector<Reader>& readers, const std::string& gpkg, const std::string& outDir) {
  // GDAL complains of damaged files on stderr; the readers' Error says it in the user's terms.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CaseResult r;
  for (const Reader& reader : readers) {
    try {
      reader.run(gpkg, outDir);
      ++r.read;
    } catch (const Error&) {
      ++r.refused;
    } catch (const std::exception& e) {
      r.problems.push_back(std::string(reader.name) + " threw " + typeid(e).name() + " (" + e.what() + ")");
    } catch (...) {
      r.problems.push_back(std::string(reader.name) + " threw something that is not a std::exception");
    }
  }
  CPLPopErrorHandler();
  return r;
}

// A reader in a loop cannot be stopped from outside: a hang ends the test binary, and
// says which case hung.
CaseResult withWatchdog(const std::function<CaseResult()>& run, std::uint64_t seconds, const std::string& label) {
  auto result = std::async(std::launch::async, run);
  if (result.wait_for(std::chrono::seconds(seconds)) == std::future_status::timeout) {
    std::fprintf(stderr, "FAILED: the readers did not finish within %llu s (a hang) on %s\n",
                 static_cast<unsigned long long>(seconds), label.c_str());
    std::fflush(stderr);
    std::abort();
  }
  return result.get();
}

// The lod and locate outputs of damaged copies need no protection from power loss: without
// SQLite's disk syncs a case takes a tenth of the time on a busy disk.
struct NoDiskSyncs {
  NoDiskSyncs() { CPLSetConfigOption("OGR_SQLITE_SYNCHRONOUS", "OFF"); }
  ~NoDiskSyncs() { CPLSetConfigOption("OGR_SQLITE_SYNCHRONOUS", nullptr); }
};

TEST(ReaderFuzz, DamagedHierarchiesAreReadOrRefusedWithAnError) {
  const NoDiskSyncs noSyncs;
  const test::SmallHierarchy& s = test::smallHierarchy();
  const std::uint64_t seed = fromEnvironment("TINLOD_FUZZ_SEED", kSeed);
  const std::uint64_t cases = fromEnvironment("TINLOD_FUZZ_CASES", kCases);
  const std::uint64_t seconds = fromEnvironment("TINLOD_FUZZ_CASE_SECONDS", kCaseSeconds);
  const std::vector<Reader> readers = everyReader(s);
  const std::string out = test::tempDir();
  // Unless every reader reads the intact file, the damage would test nothing.
  const CaseResult intact = runReaders(readers, test::editableCopy(s.gpkg), out);
  ASSERT_EQ(intact.read, readers.size()) << (intact.problems.empty() ? "" : intact.problems.front());

  test::GpkgMutator mutator(s.gpkg, seed);
  std::size_t read = 0, refused = 0;
  for (std::uint64_t k = 1; k <= cases; ++k) {
    std::string what;
    const std::string copy = mutator.mutatedCopy(what);
    const std::string label = "case " + std::to_string(k) + " of seed " + std::to_string(seed) + ": " + what;
    const CaseResult r = withWatchdog([&] { return runReaders(readers, copy, out); }, seconds, label);
    for (const std::string& problem : r.problems) ADD_FAILURE() << label << "\n  " << problem;
    read += r.read, refused += r.refused;
    fs::remove(copy);
  }
  std::cout << cases << " damaged copies (seed " << seed << "): " << read << " reads succeeded, " << refused
            << " refused with an Error\n";
  if (cases >= 50) {  // both must happen, or the damage is too weak or too strong to test much
    EXPECT_GT(read, cases / 10);
    EXPECT_GT(refused, cases / 10);
  }
}

}  // namespace
}  // namespace tinlod
