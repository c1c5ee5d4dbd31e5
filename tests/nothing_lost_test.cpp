// SPDX-License-Identifier: GPL-3.0-or-later
// Nothing lost, whatever happens: the jobs and the command line against existing files,
// their own inputs, a concurrent run, a full disk, and a stop at every phase.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "test_support.h"
#include "tinlod/build_job.h"
#include "tinlod/error.h"
#include "tinlod/synthetic_dem.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

using CliRun = test::CommandRun;

CliRun tinlod(const std::string& args) { return test::runCommand(std::string(TINLOD_CLI) + " " + args); }

bool has(const std::string& text, const std::string& fragment) { return test::contains(text, fragment); }

// Every file of a folder with its bytes: what "nothing changed" is checked against.
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files[e.path().filename().string()] = test::readFile(e.path().string());
  return files;
}

std::string demFile(int width, int height, double cell) {
  SyntheticDemOptions o;
  o.width = width, o.height = height, o.cellSize = cell;
  const std::string p = test::tempDir() + "/dem.tif";
  writeDemGeoTiff(makeSyntheticDem(o), p);
  return p;
}

std::string smallDem() {
  static const std::string path = demFile(150, 120, 25);
  return path;
}

// A folder holding a DEM, a hierarchy built from it and its accuracy files.
std::string builtFolder() {
  const std::string dir = test::tempDir();
  fs::copy_file(smallDem(), dir + "/d.tif");
  const CliRun build = tinlod("build -q -max_levels 3 -accuracy " + dir + "/acc.tif -report " + dir + "/r.csv " + dir +
                              "/d.tif " + dir + "/h.gpkg");
  EXPECT_EQ(build.exitCode, 0) << build.err;
  return dir;
}

TEST(NothingLost, AccuracyOutputsNeverReplaceTheInputs) {
  const std::string dir = builtFolder();
  const auto before = snapshot(dir);
  for (const std::string& args : {"accuracy -q " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/d.tif",
                                  "accuracy -q -overwrite " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/h.gpkg",
                                  "accuracy -q -overwrite " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/./d.tif",
                                  "build -q -overwrite -max_levels 2 " + dir + "/d.tif " + dir + "/h2.gpkg -accuracy " + dir + "/d.tif"}) {
    const CliRun run = tinlod(args);
    EXPECT_EQ(run.exitCode, 1) << args;
    EXPECT_TRUE(has(run.err, "is an input of this run")) << run.err;
  }
  EXPECT_EQ(snapshot(dir), before);
}

TEST(NothingLost, AccuracyFilesNeedOverwriteLikeEveryOutput) {
  const std::string dir = builtFolder();
  const auto before = snapshot(dir);
  const CliRun run = tinlod("accuracy -q " + dir + "/d.tif " + dir + "/h.gpkg -report " + dir + "/r.csv");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_TRUE(has(run.err, "-report: '" + dir + "/r.csv' exists: add -overwrite")) << run.err;
  EXPECT_EQ(snapshot(dir), before);
  EXPECT_EQ(tinlod("accuracy -q -overwrite " + dir + "/d.tif " + dir + "/h.gpkg -report " + dir + "/r.csv").exitCode, 0);
}

// A cancel anywhere, the accuracy stage and the spatial index included, leaves the old
// hierarchy, raster and report as they were and no staging folder behind.
TEST(NothingLost, BuildOverwriteCancelledAtAnyPhaseKeepsEveryOldFile) {
  const std::string dir = builtFolder();
  const auto before = snapshot(dir);
  AccuracyOutputs accuracy;
  accuracy.rasterPath = dir + "/acc.tif", accuracy.reportPath = dir + "/r.csv";
  HierarchyOptions options;
  options.maxLevels = 3;
  std::set<std::string> cancelledIn;  // the phase each cancel came in
  for (double at : {0.01, 0.1, 0.3, 0.62, 0.7, 0.74, 0.8, 0.95, 0.995}) {
    std::string phaseAtCancel;
    Feedback cancelling;
    cancelling.progress = [&](double f, const std::string& phase) {
      if (f >= at && phaseAtCancel.empty()) phaseAtCancel = phase;
      return f < at;
    };
    EXPECT_THROW(runBuildJob(dir + "/d.tif", dir + "/h.gpkg", SampleOptions(), options, true, cancelling, accuracy), Cancelled)
        << "cancelled at " << at;
    EXPECT_EQ(snapshot(dir), before) << "cancelled at " << at;
    cancelledIn.insert(phaseAtCancel);
  }
  EXPECT_GE(cancelledIn.size(), 5u) << "the cancels came in too few of the job's phases to test each";
}

// Two runs started together for one output without -overwrite: one wins, the other says
// the file appeared meanwhile; the output is the winner's, whole.
TEST(NothingLost, TwoRunsForOneOutputDoNotBothSucceed) {
  const std::string dir = test::tempDir();
  fs::copy_file(smallDem(), dir + "/d.tif");
  const std::string run = std::string(TINLOD_CLI) + " sample -q -block 1 " + dir + "/d.tif " + dir + "/t.gpkg";
  const std::string cmd = "cd " + dir + " && (" + run + " 2>e1 & p1=$!; " + run + " 2>e2 & p2=$!; wait $p1; echo $? > rc1; wait $p2; echo $? > rc2)";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string rc = test::readFile(dir + "/rc1") + test::readFile(dir + "/rc2");
  EXPECT_TRUE(rc == "0\n1\n" || rc == "1\n0\n") << rc;
  const std::string err = test::readFile(dir + "/e1") + test::readFile(dir + "/e2");
  EXPECT_TRUE(has(err, "appeared while this run was working") || has(err, "exists: add -overwrite")) << err;
  EXPECT_EQ(tinlod("info " + dir + "/t.gpkg").exitCode, 0);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST(NothingLost, AMultiFileRasterFormatMovesAllItsFiles) {
  const std::string dir = builtFolder();
  const CliRun run = tinlod("accuracy -q -of ENVI " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/e.img");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir + "/e.hdr"));
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen((dir + "/e.img").c_str(), GA_ReadOnly));
  ASSERT_NE(ds, nullptr);
  EXPECT_EQ(ds->GetRasterCount(), 4);
  GDALClose(ds);
  // A file the format writes beside it that is there already is said before the work.
  const std::string other = dir + "/f.hdr";
  std::ofstream(other) << "someone's header";
  const CliRun beside = tinlod("accuracy -q -of ENVI " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/f.img");
  EXPECT_EQ(beside.exitCode, 1);
  EXPECT_TRUE(has(beside.err, "-accuracy: '" + other + "' exists (the format writes it beside '" + dir +
                                  "/f.img'): add -overwrite to replace it"))
      << beside.err;
  EXPECT_FALSE(has(beside.err, "appeared while")) << beside.err;
  EXPECT_FALSE(fs::exists(dir + "/f.img"));
  EXPECT_EQ(test::readFile(other), "someone's header");
  // EHdr writes the CRS's .prj too (the format was tried without a CRS, and missed it).
  std::ofstream(dir + "/g.prj") << "someone's CRS";
  const CliRun prj = tinlod("accuracy -q " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/g.bil");
  EXPECT_TRUE(has(prj.err, "-accuracy: '" + dir + "/g.prj' exists (the format writes it beside")) << prj.err;
  // An older raster's statistics left beside the name: read as the new raster's, they were.
  std::ofstream(dir + "/s.tif.aux.xml") << "<PAMDataset/>";
  const CliRun stale = tinlod("accuracy -q " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/s.tif");
  EXPECT_TRUE(has(stale.err, "-accuracy: '" + dir + "/s.tif.aux.xml' exists")) << stale.err;
  const CliRun replaced = tinlod("accuracy -q -overwrite " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/s.tif");
  EXPECT_EQ(replaced.exitCode, 0) << replaced.err;
  EXPECT_NE(test::readFile(dir + "/s.tif.aux.xml"), "<PAMDataset/>");  // set aside, or written anew
  // A raster named with all of a file system's 255 bytes: its scratch file was named longer.
  const std::string longest = dir + "/" + std::string(251, 'b') + ".tif";
  const CliRun named = tinlod("accuracy -q " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + longest);
  EXPECT_EQ(named.exitCode, 0) << named.err;
  EXPECT_TRUE(fs::exists(longest));
  const CliRun vrt = tinlod("accuracy -q -of VRT " + dir + "/d.tif " + dir + "/h.gpkg -accuracy " + dir + "/e.vrt");
  EXPECT_EQ(vrt.exitCode, 1);
  EXPECT_TRUE(has(vrt.err, "-of: VRT cannot hold")) << vrt.err;
}

// A disk that fills up mid-write: the old output is kept, nothing half-written is left.
TEST(NothingLost, AFullDiskLeavesTheOldOutput) {
  const std::string dir = test::tempDir() + "/small_disk";
  fs::create_directories(dir);
  if (mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=3m") != 0) GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  // The old output, a small TIN: a file of another kind would be refused before any write.
  ASSERT_EQ(tinlod("sample -q -block 15 " + smallDem() + " " + dir + "/t.gpkg").exitCode, 0);
  const auto before = snapshot(dir);
  const CliRun run = tinlod("sample -q -overwrite -block 1 " + smallDem() + " " + dir + "/t.gpkg");
  const auto left = snapshot(dir);
  umount(dir.c_str());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_FALSE(has(run.err, ".tinlod-")) << run.err;  // the user's file is named, not the staging one
  EXPECT_TRUE(has(run.err, "t.gpkg")) << run.err;
  EXPECT_TRUE(has(run.err, "the disk is full")) << run.err;
  ASSERT_EQ(before.size(), 1u);
  EXPECT_TRUE(left == before) << "the old output was changed, or something was left beside it";
}

// An input named as the output, in a read-only folder (a data share): said to be an input,
// not that the folder is read-only; a link to an input is the input, not "beside it".
TEST(NothingLost, AnInputAsOutputIsSaidToBeOneInAReadOnlyFolderOrThroughALink) {
  const std::string built = builtFolder(), dir = test::tempDir() + "/read_only";
  fs::create_directories(dir);
  if (mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=8m") != 0) GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  fs::copy_file(built + "/d.tif", dir + "/d.tif");
  ASSERT_EQ(tinlod("sample -q -block 15 " + dir + "/d.tif " + dir + "/p.gpkg").exitCode, 0);
  mount(nullptr, dir.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr);
  const CliRun fixed = tinlod("build -q -overwrite " + dir + "/d.tif " + dir + "/p.gpkg -fixed " + dir + "/p.gpkg");
  const CliRun raster = tinlod("accuracy -q -overwrite " + dir + "/d.tif " + built + "/h.gpkg -accuracy " + dir + "/d.tif");
  umount(dir.c_str());
  EXPECT_TRUE(has(fixed.err, "output: '" + dir + "/p.gpkg' is an input of this run")) << fixed.err;
  EXPECT_TRUE(has(raster.err, "-accuracy: '" + dir + "/d.tif' is an input of this run")) << raster.err;
  fs::create_symlink(built + "/h.gpkg", built + "/link.gpkg");
  const CliRun link = tinlod("lod -q -overwrite -max_error 5 " + built + "/link.gpkg " + built + "/link.gpkg");
  EXPECT_TRUE(has(link.err, "output: '" + built + "/link.gpkg' is an input of this run")) << link.err;
}

// A disk with almost no room: said as such in one line, where GDAL said "WriteEncodedTile/
// Strip() failed" of the accuracy raster's scratch file, twice, and a new GeoPackage's
// "no such table: gpkg_spatial_ref_sys" a dozen times; nothing left.
TEST(NothingLost, AFullDiskIsSaidInOneLine) {
  const std::string built = builtFolder(), dir = test::tempDir() + "/small_disk";
  fs::create_directories(dir);
  if (mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=3m") != 0) GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  std::ofstream(dir + "/fill") << std::string(3 * 1024 * 1024 - 64 * 1024, 'x');
  const CliRun raster = tinlod("accuracy -q -step 1 " + built + "/d.tif " + built + "/h.gpkg -accuracy " + dir + "/a.tif");
  const CliRun tin = tinlod("sample -q " + built + "/d.tif " + dir + "/t.gpkg");
  const CliRun lod = tinlod("lod -q -max_error 5 " + built + "/h.gpkg " + dir + "/l.gpkg");
  {  // the last bytes too: a report is small
    std::ofstream rest(dir + "/rest");
    for (int k = 0; k < 1024 && rest; ++k) rest << std::string(4096, 'x') << std::flush;
  }
  const CliRun report = tinlod("accuracy -q " + built + "/d.tif " + built + "/h.gpkg -report " + dir + "/r.html");
  const CliRun dem = tinlod("makedem " + dir + "/m.tif");
  fs::remove(dir + "/fill");
  fs::remove(dir + "/rest");
  const auto left = snapshot(dir);
  umount(dir.c_str());
  EXPECT_EQ(raster.exitCode, 1);
  EXPECT_EQ(raster.err, "ERROR: -accuracy: cannot write the accuracy raster '" + dir + "/a.tif': the disk is full\n");
  EXPECT_EQ(report.err, "ERROR: -report: cannot write '" + dir + "/r.html': the disk is full\n");
  EXPECT_TRUE(has(dem.err, "ERROR: cannot write '" + dir + "/m.tif': the disk is full\n")) << dem.err;  // after progress
  for (const CliRun& r : {tin, lod}) {
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err.rfind("ERROR: ", 0), 0u) << r.err;
    EXPECT_TRUE(has(r.err, "': the disk is full\n")) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_TRUE(left.empty()) << left.begin()->first;
}

// Ctrl-C is answered within a second or two whatever the run is doing (reading, sampling,
// writing features, building the spatial index), and a second Ctrl-C at once; no file is
// left. The signal is sent once the progress on stderr shows `mark`, then `signals` run.
void expectPromptStop(const std::string& dem, const std::string& mark, const char* signals) {
  const std::string dir = test::tempDir();
  const std::string waitForMark = "until grep -q '" + mark + "' err 2>/dev/null || ! kill -0 $pid 2>/dev/null; do sleep 0.02; done; ";
  const std::string cmd = "cd " + dir + " && (" + std::string(TINLOD_CLI) + " sample -block 1 " + dem +
                          " tin.gpkg 2>err & pid=$!; " + waitForMark + signals +
                          " start=$(date +%s%N); wait $pid; echo $? > rc; echo $(( ($(date +%s%N) - start) / 1000000 )) > ms)";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string rc = test::readFile(dir + "/rc");
  ASSERT_EQ(rc, "130\n") << "signal at '" << mark << "': " << test::readFile(dir + "/err");
  EXPECT_LT(std::stoi(test::readFile(dir + "/ms")), 2500) << "signal at '" << mark << "'";
  EXPECT_TRUE(has(test::readFile(dir + "/err"), "stopped before the end; nothing was written"));
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "err" || name == "rc" || name == "ms") << "left behind: " << name;
  }
}

std::string mediumDem() {
  static const std::string path = demFile(1200, 1000, 10);
  return path;
}

// The phases as progress shows them: reading and sampling (0 to 60), writing the features
// (60 to 88), the spatial index (88 to 99; GDAL builds it while closing the file, where no
// progress can be reported and a cancel cannot be heard).
TEST(NothingLost, CtrlCStopsWithinTwoSecondsInEveryPhase) {
  for (const char* mark : {"0", "20", "Writing", "70", "80"}) expectPromptStop(mediumDem(), mark, "kill -INT $pid;");
}

TEST(NothingLost, ASecondCtrlCStopsAtOnceAndStillCleansUp) {
  expectPromptStop(mediumDem(), "Writing", "kill -INT $pid; sleep 0.1; kill -INT $pid;");
}

// A connection of another program's to a GeoPackage, in SQLite's write-ahead-log mode (as
// QGIS edits one), with a table of its own.
struct OtherProgram {
  sqlite3* db = nullptr;
  explicit OtherProgram(const std::string& path) {
    EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    run("PRAGMA journal_mode=WAL; CREATE TABLE IF NOT EXISTS notes(a); INSERT INTO notes VALUES('kept');");
  }
  ~OtherProgram() { sqlite3_close(db); }
  void run(const std::string& sql) { EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sql; }
};

// What a fresh reader finds: the notes' rows, or -1 when the file cannot be read.
long long notesIn(const std::string& path) {
  sqlite3* db = nullptr;
  sqlite3_stmt* st = nullptr;
  long long rows = -1;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK &&
      sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM notes", -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
    rows = sqlite3_column_int64(st, 0);
  sqlite3_finalize(st);
  sqlite3_close(db);
  return rows;
}

TEST(NothingLost, AGeoPackageAnotherProgramHoldsIsNotReplaced) {
  // Replaced beside the other program's write-ahead log, the new file was read with the old
  // log by every reader: "malformed database schema", the user's table lost.
  const std::string dir = builtFolder(), h = dir + "/h.gpkg";
  const std::string rebuild = "build -q -overwrite -max_levels 3 " + dir + "/d.tif " + h;
  {
    OtherProgram qgis(h);
    ASSERT_TRUE(fs::exists(h + "-wal"));
    const CliRun held = tinlod(rebuild);
    EXPECT_EQ(held.exitCode, 1);
    EXPECT_TRUE(has(held.err, "output 'h.gpkg' is open in another program") || has(held.err, "/h.gpkg' is open in another program"))
        << held.err;
    EXPECT_TRUE(has(held.err, "write-ahead log 'h.gpkg-wal' in use")) << held.err;
    EXPECT_TRUE(has(held.err, "close it there, then run again")) << held.err;
  }
  EXPECT_FALSE(fs::exists(h + "-wal"));  // the other program's close played it back
  {
    // Without the log, a transaction under way locks the file (its journal beside it).
    OtherProgram script(h);
    script.run("PRAGMA journal_mode=DELETE; BEGIN EXCLUSIVE; INSERT INTO notes VALUES('pending');");
    const CliRun locked = tinlod(rebuild);
    EXPECT_EQ(locked.exitCode, 1);
    EXPECT_TRUE(has(locked.err, "is being written by another program (QGIS, which holds a GeoPackage so once one of its "
                                "layers has been edited, until all of them are removed; or a script), locked: close it "
                                "there, then run again"))
        << locked.err;
    script.run("ROLLBACK; DELETE FROM notes WHERE rowid > 1;");
    // A writer that has not yet spilled its changes holds a lock readers pass: still refused
    // (its journal, beside a new file, would be played into it).
    script.run("BEGIN IMMEDIATE; INSERT INTO notes VALUES('pending');");
    const CliRun reserved = tinlod(rebuild);
    EXPECT_EQ(reserved.exitCode, 1);
    EXPECT_TRUE(has(reserved.err, "is being written by another program")) << reserved.err;
    script.run("ROLLBACK;");
  }
  const CliRun free = tinlod(rebuild);
  EXPECT_EQ(free.exitCode, 0) << free.err;
  EXPECT_EQ(notesIn(h), 1);  // its other tables kept, as -overwrite promises
}

TEST(NothingLost, AReaderOfALockedGeoPackageSaysSoInSecondsNotAfterSqlitesTimeouts) {
  // info waited 10 s and lod 25 s (SQLite's busy timeout at each of their opens) in silence.
  const std::string dir = builtFolder(), h = dir + "/h.gpkg";
  OtherProgram script(h);
  script.run("PRAGMA journal_mode=DELETE; BEGIN EXCLUSIVE; INSERT INTO notes VALUES('pending');");
  for (const std::string& command : {"info " + h, "lod -q -max_error 5 " + h + " " + dir + "/lod.gpkg"}) {
    const auto start = std::chrono::steady_clock::now();
    const CliRun run = tinlod(command);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(run.exitCode, 1) << command;
    EXPECT_TRUE(has(run.err, "is being written by another program")) << run.err;
    EXPECT_TRUE(has(run.err, "try again once it is done")) << run.err;
    EXPECT_LT(seconds, 6.0) << command;  // 2 s of patience, for a commit, then said
  }
  script.run("ROLLBACK;");
  EXPECT_FALSE(fs::exists(dir + "/lod.gpkg"));
  EXPECT_EQ(tinlod("info " + h).exitCode, 0);  // free again
}

TEST(NothingLost, ALogLeftByAProgramThatCrashedIsPlayedBackFirst) {
  const std::string dir = builtFolder(), h = dir + "/h.gpkg";
  const pid_t child = fork();
  if (child == 0) {
    sqlite3* db = nullptr;
    sqlite3_open(h.c_str(), &db);
    sqlite3_exec(db, "PRAGMA journal_mode=WAL; CREATE TABLE notes(a); INSERT INTO notes VALUES('kept');", nullptr, nullptr,
                 nullptr);
    _exit(0);  // killed, as it were: the log stays
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(fs::exists(h + "-wal"));
  const CliRun run = tinlod("build -q -overwrite -max_levels 3 " + dir + "/d.tif " + h);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_FALSE(fs::exists(h + "-wal"));
  EXPECT_EQ(notesIn(h), 1);
}

TEST(NothingLost, AWriteProtectedOutputIsRefusedAndAReplacedOneKeepsItsMode) {
  const std::string dir = builtFolder();
  const std::string again = "accuracy -q -overwrite " + dir + "/d.tif " + dir + "/h.gpkg -report " + dir + "/r.csv";
  fs::permissions(dir + "/r.csv", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::map<std::string, std::string> before = snapshot(dir);
  const CliRun refused = tinlod(again);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_TRUE(has(refused.err, "-report: '" + dir + "/r.csv' is write-protected (mode 0444): make it writable (chmod u+w) "
                                "to replace it, or choose another name"))
      << refused.err;
  EXPECT_EQ(snapshot(dir), before);
  fs::permissions(dir + "/r.csv", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const CliRun replaced = tinlod(again);
  EXPECT_EQ(replaced.exitCode, 0) << replaced.err;
  EXPECT_EQ(fs::status(dir + "/r.csv").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);  // not the run's 0644
}

TEST(NothingLost, ADanglingLinkAsOutputIsRefusedBeforeTheWork) {
  const std::string dir = builtFolder();
  fs::create_symlink("gone/h2.gpkg", dir + "/link.gpkg");
  const CliRun run = tinlod("build -q " + dir + "/d.tif " + dir + "/link.gpkg");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_TRUE(has(run.err, "link.gpkg' is a symbolic link to 'gone/h2.gpkg', which does not exist: remove the link or "
                           "name another file"))
      << run.err;
  EXPECT_FALSE(has(run.err, "appeared while")) << run.err;
}

}  // namespace
}  // namespace tinlod
