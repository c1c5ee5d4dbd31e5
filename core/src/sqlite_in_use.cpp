// SPDX-License-Identifier: GPL-3.0-or-later
#include "sqlite_in_use.h"

#include <sqlite3.h>

#include <fstream>

namespace fs = std::filesystem;

namespace tinlod {
namespace {

bool isSqliteFile(const fs::path& file) {
  char header[16] = {};
  std::ifstream in(file, std::ios::binary);
  return in.read(header, sizeof header) && std::string(header, sizeof header) == std::string("SQLite format 3", 16);
}

// Reads `file` once, opened with `flags`: SQLite's code.
int readOnce(const fs::path& file, int flags) {
  sqlite3* db = nullptr;
  int rc = sqlite3_open_v2(file.c_str(), &db, flags, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_exec(db, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  return rc;
}

const std::string kWho =
    " (QGIS, which holds a GeoPackage so once one of its layers has been edited, until all of them are removed; or a "
    "script)";

}  // namespace

std::string lockedFileWords() { return "is being written by another program" + kWho + ", locked"; }

std::string sqliteFileInUse(const fs::path& file) {
  const fs::path wal = file.string() + "-wal", journal = file.string() + "-journal";
  std::error_code ec;
  if ((!fs::exists(wal, ec) && !fs::exists(journal, ec)) || !isSqliteFile(file)) return "";
  // SQLite rolls back a journal left by a crash, and the last connection to close plays the
  // log into the file and removes it; one still open elsewhere keeps it.
  const int rc = readOnce(file, SQLITE_OPEN_READWRITE);
  if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) return lockedFileWords();
  if (fs::exists(wal, ec))
    return "is open in another program" + kWho + ", its write-ahead log '" + wal.filename().string() +
           "' in use (a file put in its place would be read with it, corrupt)";
  return "";
}

bool sqliteFileLocked(const fs::path& file) {
  if (!isSqliteFile(file)) return false;
  const int rc = readOnce(file, SQLITE_OPEN_READONLY);
  return rc == SQLITE_BUSY || rc == SQLITE_LOCKED;
}

}  // namespace tinlod
