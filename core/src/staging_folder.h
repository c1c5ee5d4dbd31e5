// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the hidden folder beside an output in which a job writes it.
#pragma once

#include <filesystem>
#include <mutex>
#include <vector>

namespace tinlod {

// `.<output name>.tinlod-<random>` beside the output. A lock on the `.lock` file inside
// marks it live for as long as its process runs: a run on another host or in another PID
// namespace sharing the folder sees that lock, where a test of a PID could not. A folder
// nobody holds was left by a run killed outright, and the next run for the same output
// removes it.
class StagingFolder {
 public:
  explicit StagingFolder(const std::filesystem::path& target);
  ~StagingFolder();  // removes the folder and everything still in it
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The files written in the folder: the output and its sidecars.
  std::vector<std::filesystem::path> stagedFiles() const;
  // Where the old file `name` is kept while a commit could still be taken back.
  std::filesystem::path backupFor(const std::filesystem::path& name) const;

  // The staging folders beside `target` that no run holds (any output's: one run killed
  // outright leaves a folder the size of its output).
  static void removeStale(const std::filesystem::path& target);
  // Every folder this process holds, removed at once; the lock of commitMutex() is taken
  // first, so a commit is never cut in half.
  static void removeAllLive();
  // Held while a commit moves files into place.
  static std::mutex& commitMutex();

 private:
  bool tryCreate(const std::filesystem::path& dir, const std::filesystem::path& target);
  std::filesystem::path path_;
  int lockFd_ = -1;
};

}  // namespace tinlod
