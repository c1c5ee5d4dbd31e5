// SPDX-License-Identifier: GPL-3.0-or-later
// Private: whether another program holds an SQLite file (a GeoPackage) that a run would replace.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

namespace tinlod {

// An SQLite file has its rollback journal or write-ahead log (NAME-journal, NAME-wal) beside
// it while a program writes it, and after one that crashed. A file moved over it alone is
// paired with the old log, which every reader then plays into it: a corrupt GeoPackage.
// Returns why `file` may not be replaced now ("is open in another program (...)"), or "" when
// nothing holds it; a log left by a program that ended is played back into the file first, as
// any SQLite reader would do.
std::string sqliteFileInUse(const std::filesystem::path& file);

// For a reader that could not open `file`: whether another program holds it locked (a
// transaction under way), which is no reason to call it no GeoPackage.
bool sqliteFileLocked(const std::filesystem::path& file);

// For a reader about to open `file`: whether another program keeps it locked for longer than
// `patience` (a commit takes far less). GDAL's open would wait out SQLite's busy timeout,
// 10 s at each open of a reader (17-25 s for lod), before failing without a word.
bool sqliteFileStaysLocked(const std::filesystem::path& file, std::chrono::milliseconds patience);

// Throws Error ("... is being written by another program ...: try again once it is done")
// when `path` stays locked for 2 s; the first thing every reader of a TIN file does.
void refuseLockedForReading(const std::string& path);

// The words for a reader's error on a locked file: "is being written by another program ...".
std::string lockedFileWords();

}  // namespace tinlod
