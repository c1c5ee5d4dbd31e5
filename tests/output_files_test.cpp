// SPDX-License-Identifier: GPL-3.0-or-later
// OutputFiles: every output checked up front, staged, and moved into place all together.
#include "tinlod/output_files.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "test_support.h"
#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::set<std::string> namesIn(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}


bool has(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

TEST(OutputFiles, NothingAppearsBeforeCommitAndEverythingAfter) {
  const std::string dir = test::tempDir();
  OutputFiles files(false);
  const StagedFile& a = files.add(dir + "/a.csv", "-report");
  const StagedFile& b = files.add(dir + "/b.tif", "-accuracy");
  write(a.staging, "report");
  write(b.staging, "raster");
  write(b.staging.string() + ".aux.xml", "statistics");  // a sidecar the driver added
  EXPECT_EQ(a.staging.filename(), "a.csv");
  EXPECT_EQ(namesIn(dir).count("a.csv") + namesIn(dir).count("b.tif"), 0u);
  files.commit();
  EXPECT_EQ(namesIn(dir), (std::set<std::string>{"a.csv", "b.tif", "b.tif.aux.xml"}));
  EXPECT_EQ(test::readFile(dir + "/b.tif.aux.xml"), "statistics");
}

TEST(OutputFiles, WithoutCommitNothingChangesAndNoStagingIsLeft) {
  const std::string dir = test::tempDir();
  write(dir + "/old.gpkg", "old");
  {
    OutputFiles files(true);
    const StagedFile& f = files.add(dir + "/old.gpkg", "output", true);
    EXPECT_TRUE(f.existed && f.keepContent);
    EXPECT_FALSE(fs::exists(f.staging));  // the writer copies it only when it has content to keep
    copyForUpdate(f);
    EXPECT_EQ(test::readFile(f.staging), "old");
    write(f.staging, "new");
  }
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"old.gpkg"});
  EXPECT_EQ(test::readFile(dir + "/old.gpkg"), "old");
}

TEST(OutputFiles, AnInputIsNeverAnOutputEvenWithOverwrite) {
  const std::string dir = test::tempDir();
  write(dir + "/dem.tif", "dem");
  fs::create_hard_link(dir + "/dem.tif", dir + "/alias.tif");
  OutputFiles files(true, {dir + "/dem.tif"});
  for (const std::string& name : {dir + "/dem.tif", dir + "/./dem.tif", dir + "/alias.tif"}) {
    const std::string e = test::errorOf([&] { files.add(name, "-accuracy"); });
    EXPECT_TRUE(has(e, "-accuracy: '" + name + "' is an input of this run")) << e;
  }
  EXPECT_EQ(test::readFile(dir + "/dem.tif"), "dem");
}

TEST(OutputFiles, TheSameFileTwiceIsRefused) {
  const std::string dir = test::tempDir();
  OutputFiles files(true);
  files.add(dir + "/r.csv", "-report");
  const std::string e =
      test::errorOf([&] { files.add(dir + "/../" + fs::path(dir).filename().string() + "/r.csv", "-accuracy"); });
  EXPECT_TRUE(has(e, "is also given as -report")) << e;
}

TEST(OutputFiles, ChecksTheFolderAndExistingFilesUpFront) {
  const std::string dir = test::tempDir();
  write(dir + "/there.csv", "x");
  fs::create_directories(dir + "/folder.csv");
  OutputFiles files(false);
  EXPECT_TRUE(has(test::errorOf([&] { files.add(dir + "/there.csv", "-report"); }), "exists: add -overwrite"));
  EXPECT_TRUE(has(test::errorOf([&] { files.add(dir + "/folder.csv", "-report"); }), "is a folder"));
  EXPECT_TRUE(has(test::errorOf([&] { files.add(dir + "/none/r.csv", "-report"); }), "the folder of"));
}

// Two runs for one output: without -overwrite the later one must not replace the file the
// earlier one put there meanwhile; it says so and moves nothing, its other outputs included.
TEST(OutputFiles, AFileThatAppearedMeanwhileIsNotReplacedAndNothingElseMoves) {
  const std::string dir = test::tempDir();
  OutputFiles files(false);
  write(files.add(dir + "/first.csv", "-report").staging, "mine");
  write(files.add(dir + "/out.gpkg", "output").staging, "mine");
  write(dir + "/out.gpkg", "the other run's");
  const std::string e = test::errorOf([&] { files.commit(); });
  EXPECT_TRUE(has(e, "output: '" + dir + "/out.gpkg' appeared while this run was working")) << e;
  EXPECT_EQ(test::readFile(dir + "/out.gpkg"), "the other run's");
  EXPECT_FALSE(fs::exists(dir + "/first.csv"));  // taken back
}

TEST(OutputFiles, AFailedCommitPutsBackEveryFileItReplaced) {
  const std::string dir = test::tempDir();
  write(dir + "/a.gpkg", "old a");
  std::string e;
  {
    OutputFiles files(true);
    write(files.add(dir + "/a.gpkg", "output").staging, "new a");
    write(files.add(dir + "/b.csv", "-report").staging, "new b");
    fs::create_directories(dir + "/b.csv");  // the second move cannot happen
    e = test::errorOf([&] { files.commit(); });
  }
  EXPECT_TRUE(has(e, "is now a folder")) << e;
  EXPECT_EQ(test::readFile(dir + "/a.gpkg"), "old a");
  EXPECT_TRUE(fs::is_directory(dir + "/b.csv"));
  EXPECT_EQ(namesIn(dir), (std::set<std::string>{"a.gpkg", "b.csv"}));
}

TEST(OutputFiles, OverwriteReplacesAndLeavesNoBackups) {
  const std::string dir = test::tempDir();
  write(dir + "/a.gpkg", "old");
  OutputFiles files(true);
  write(files.add(dir + "/a.gpkg", "output").staging, "new");
  files.commit();
  EXPECT_EQ(test::readFile(dir + "/a.gpkg"), "new");
  EXPECT_EQ(namesIn(dir), std::set<std::string>{"a.gpkg"});
}

TEST(OutputFiles, ASymbolicLinkIsFollowed) {
  const std::string dir = test::tempDir();
  fs::create_directories(dir + "/store");
  write(dir + "/store/t.gpkg", "old");
  fs::create_symlink(dir + "/store/t.gpkg", dir + "/link.gpkg");
  OutputFiles files(true);
  write(files.add(dir + "/link.gpkg", "output").staging, "new");
  files.commit();
  EXPECT_TRUE(fs::is_symlink(dir + "/link.gpkg"));
  EXPECT_EQ(test::readFile(dir + "/store/t.gpkg"), "new");
}

// A staging folder is stale when nobody holds its lock, whatever PID or host made it; one
// held (here by another open file description, as another process would) is left alone.
TEST(OutputFiles, OnlyStagingFoldersNobodyHoldsAreRemoved) {
  const std::string dir = test::tempDir();
  const fs::path dead = dir + "/.out.gpkg.tinlod-0000000000000001", live = dir + "/.out.gpkg.tinlod-0000000000000002";
  for (const fs::path& p : {dead, live}) {
    fs::create_directories(p);
    write(p / ".lock", "");
    write(p / "out.gpkg", "partial");
  }
  const int held = open((live / ".lock").c_str(), O_RDWR);
  ASSERT_EQ(flock(held, LOCK_EX | LOCK_NB), 0);
  {
    OutputFiles files(false);
    files.add(dir + "/out.gpkg", "output");
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live / "out.gpkg"));
  }
  close(held);
  // Another output's run, beside it, removes it too: a killed build's 200 MB stayed until a
  // run for the same output came.
  OutputFiles again(false);
  again.add(dir + "/other.csv", "-report");
  EXPECT_FALSE(fs::exists(live));
  // A folder of the user's that only looks alike is no staging folder.
  fs::create_directories(dir + "/.notes.tinlod-2026");
  OutputFiles third(false);
  third.add(dir + "/third.csv", "-report");
  EXPECT_TRUE(fs::exists(dir + "/.notes.tinlod-2026"));
}

// A run stopped while a writer made a file in its folder may leave the folder, empty and
// without its lock: the next run for the output removes it, however new it is. One with
// files but no lock may be one another run has just made, and waits a minute.
TEST(OutputFiles, AnEmptyStagingFolderWithoutItsLockIsRemoved) {
  const std::string dir = test::tempDir();
  const fs::path empty = dir + "/.out.gpkg.tinlod-0000000000000003", young = dir + "/.out.gpkg.tinlod-0000000000000004";
  fs::create_directories(empty);
  fs::create_directories(young);
  write(young / "out.gpkg", "partial");
  OutputFiles files(false);
  files.add(dir + "/out.gpkg", "output");
  EXPECT_FALSE(fs::exists(empty));
  EXPECT_TRUE(fs::exists(young / "out.gpkg"));
}

// A replaced raster's old statistics (NAME.aux.xml, which the new one did not write) go
// with it; one the new raster wrote replaces the old; a failed commit puts the old back.
TEST(OutputFiles, AReplacedRastersOldStatisticsGoWithIt) {
  const std::string dir = test::tempDir();
  write(dir + "/a.tif", "old"), write(dir + "/a.tif.aux.xml", "old stats");
  write(dir + "/b.tif", "old"), write(dir + "/b.tif.aux.xml", "old stats");
  write(dir + "/c.tif", "old");  // no statistics yet: the new ones stay
  {
    OutputFiles files(true);
    write(files.add(dir + "/a.tif", "-accuracy").staging, "new");
    for (const char* name : {"/b.tif", "/c.tif"}) {
      const StagedFile& f = files.add(dir + name, "makedem");
      write(f.staging, "new"), write(f.staging.string() + ".aux.xml", "new stats");
    }
    files.commit();
  }
  EXPECT_EQ(namesIn(dir), (std::set<std::string>{"a.tif", "b.tif", "b.tif.aux.xml", "c.tif", "c.tif.aux.xml"}));
  EXPECT_EQ(test::readFile(dir + "/b.tif.aux.xml"), "new stats");
  EXPECT_EQ(test::readFile(dir + "/c.tif.aux.xml"), "new stats");
  write(dir + "/a.tif.aux.xml", "old stats");
  {
    OutputFiles files(true);
    write(files.add(dir + "/a.tif", "-accuracy").staging, "newer");
    write(files.add(dir + "/c.csv", "-report").staging, "x");
    fs::create_directory(dir + "/c.csv");  // the second move cannot happen
    EXPECT_THROW(files.commit(), Error);
  }
  EXPECT_EQ(test::readFile(dir + "/a.tif"), "new");
  EXPECT_EQ(test::readFile(dir + "/a.tif.aux.xml"), "old stats");
}

TEST(OutputFiles, MessagesNameTheUsersFileNotTheStagingOne) {
  const std::string dir = test::tempDir();
  OutputFiles files(false);
  const StagedFile& f = files.add(dir + "/a.tif", "-accuracy");
  const std::string said = inUserTerms(f, "cannot write " + f.staging.string() + " and " + f.staging.parent_path().string() + "/a.hdr");
  EXPECT_EQ(said, "cannot write " + dir + "/a.tif and " + dir + "/a.hdr");
}

TEST(OutputFiles, ANameAsLongAsAFileSystemAllowsIsStagedAndMovedIntoPlace) {
  // ".NAME.tinlod-<16 hex>" was 25 bytes beyond NAME: names of 231-255 bytes failed with
  // "File name too long", where ogr2ogr writes them.
  const std::string dir = test::tempDir(), name = std::string(245, 'c') + ".csv";
  OutputFiles files(false);
  const StagedFile& f = files.add(dir + "/" + name, "-report");
  EXPECT_LE(f.staging.parent_path().filename().string().size(), 255u);
  write(f.staging, "report");
  files.commit();
  EXPECT_EQ(namesIn(dir), std::set<std::string>{name});
}

TEST(OutputFiles, AbandoningRemovesEveryStagingFolder) {
  const std::string dir = test::tempDir();
  OutputFiles files(false);
  write(files.add(dir + "/a.csv", "-report").staging, "x");
  abandonStagedOutputs();
  EXPECT_TRUE(namesIn(dir).empty());
}

}  // namespace
}  // namespace tinlod
