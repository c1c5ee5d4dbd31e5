// SPDX-License-Identifier: GPL-3.0-or-later
#include "sqlite_in_use.h"

#include <sqlite3.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

bool isSqliteFile(const fs::path& file) {
  char header[16] = {};
  std::ifstream in(file, std::ios::binary);
  return in.read(header, sizeof header) && std::string(header, sizeof header) == std::string("SQLite format 3", 16);
}

// Opens `file` with `flags` and runs `sql` once: SQLite's code.
int runOnce(const fs::path& file, int flags, const char* sql) {
  sqlite3* db = nullptr;
  int rc = sqlite3_open_v2(file.c_str(), &db, flags, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_exec(db, sql, nullptr, nullptr, nullptr);
  sqlite3_close(db);
  return rc;
}

// tinlod-tiles says it alike (tiles/tinlodtiles/replace_guard.py, IN_USE_BY).
const std::string kWho =
    " (QGIS, which holds a GeoPackage so once one of its layers has been edited, until all of them are removed; or a "
    "script)";

}  // namespace

std::string lockedFileWords() { return "is being written by another program" + kWho + ", locked"; }

std::string sqliteFileInUse(const fs::path& file) {
  if (!isSqliteFile(file)) return "";
  const fs::path wal = file.string() + "-wal";
  std::error_code ec;
  // A write lock asked for and given back: refused while another program writes (a journal's
  // writer lets readers in, and its journal, beside a new file, would be played into it).
  // SQLite also rolls back a journal left by a crash, and the last connection to close plays
  // the log into the file and removes it; one still open elsewhere keeps it.
  const int rc = runOnce(file, SQLITE_OPEN_READWRITE, "BEGIN IMMEDIATE; ROLLBACK");
  if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) return lockedFileWords();
  if (fs::exists(wal, ec))
    return "is open in another program" + kWho + ", its write-ahead log '" + wal.filename().string() +
           "' in use (a file put in its place would be read with it, corrupt)";
  return "";
}

bool sqliteFileLocked(const fs::path& file) {
  if (!isSqliteFile(file)) return false;
  const int rc = runOnce(file, SQLITE_OPEN_READONLY, "SELECT count(*) FROM sqlite_master");
  return rc == SQLITE_BUSY || rc == SQLITE_LOCKED;
}

bool sqliteFileStaysLocked(const fs::path& file, std::chrono::milliseconds patience) {
  const auto until = std::chrono::steady_clock::now() + patience;
  while (sqliteFileLocked(file)) {
    if (std::chrono::steady_clock::now() >= until) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

void refuseLockedForReading(const std::string& path) {
  if (sqliteFileStaysLocked(path, std::chrono::seconds(2)))
    throw Error("'" + path + "' " + lockedFileWords() + ": try again once it is done");
}

}  // namespace tinlod
