// SPDX-License-Identifier: GPL-3.0-or-later
#include "staging_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <thread>

#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const char* const kLock = ".lock";
const char* const kBackupPrefix = ".old-";

// ".NAME.tinlod-": a name of over 200 bytes is cut (at a whole UTF-8 character) and told apart
// by its hash, so that the folder's name, 25 bytes longer, stays within the 255 a file
// system allows wherever the output's own name fits.
std::string prefixFor(const fs::path& target) {
  std::string name = target.filename().string();
  if (name.size() > 200) {
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a: the same in every build
    for (unsigned char c : name) hash = (hash ^ c) * 1099511628211ull;
    std::size_t cut = 180;
    while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
    char tail[18];
    std::snprintf(tail, sizeof tail, "~%016llx", static_cast<unsigned long long>(hash));
    name = name.substr(0, cut) + tail;
  }
  return "." + name + ".tinlod-";
}

fs::path folderOf(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

// Random rather than a PID: PIDs repeat across hosts and namespaces.
std::string randomName() {
  std::random_device device;
  const std::uint64_t bits = (std::uint64_t(device()) << 32) ^ device();
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
  return text;
}

// The folders of this process, for removeAllLive(). Never destroyed: a watchdog thread
// may use them while the process exits.
std::mutex& registryMutex() {
  static auto* m = new std::mutex;
  return *m;
}
std::set<fs::path>& registry() {
  static auto* s = new std::set<fs::path>;
  return *s;
}

void removeQuietly(const fs::path& p) {
  std::error_code ignored;
  fs::remove_all(p, ignored);
}

// A folder without its lock file yet may be one another run has just made.
bool oldEnoughToBeAbandoned(const fs::path& folder) {
  std::error_code ec;
  const auto written = fs::last_write_time(folder, ec);
  return !ec && fs::file_time_type::clock::now() - written > std::chrono::minutes(1);
}

// An empty one is removed at once: a run that made it and finds it gone before its lock
// is made tries another name (tryCreate).
// ".NAME.tinlod-<16 hex>", any output's: a run killed outright leaves its folder (a whole
// hierarchy's worth), which the next run writing beside it removes, whatever it writes.
bool isStagingName(const std::string& name) {
  const std::size_t tail = std::string(".tinlod-").size() + 16;
  if (name.size() <= tail || name[0] != '.' || name.compare(name.size() - tail, 8, ".tinlod-") != 0) return false;
  return std::all_of(name.end() - 16, name.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

void removeIfAbandoned(const fs::path& folder) {
  const int fd = open((folder / kLock).c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) {
    if (errno != ENOENT) return;
    std::error_code ec;
    if (oldEnoughToBeAbandoned(folder))
      removeQuietly(folder);
    else
      fs::remove(folder, ec);  // rmdir: fails, leaving it, if a run has just made its lock there
    return;
  }
  // Removed while holding the lock, so nobody can take the folder for theirs meanwhile.
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) removeQuietly(folder);
  close(fd);
}

}  // namespace

StagingFolder::StagingFolder(const fs::path& target) {
  const fs::path dir = folderOf(target);
  for (int attempt = 0; attempt < 8; ++attempt)
    if (tryCreate(dir, target)) {
      std::lock_guard<std::mutex> lock(registryMutex());
      registry().insert(path_);
      return;
    }
  throw Error("cannot make a temporary folder beside '" + target.string() + "': " + std::strerror(errno));
}

bool StagingFolder::tryCreate(const fs::path& dir, const fs::path& target) {
  path_ = dir / (prefixFor(target) + randomName());
  if (mkdir(path_.c_str(), 0700) != 0) {
    if (errno == EEXIST) return false;
    throw Error("cannot make a temporary folder beside '" + target.string() + "': " + std::strerror(errno));
  }
  const fs::path lockPath = path_ / kLock;
  lockFd_ = open(lockPath.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (lockFd_ < 0) return false;  // a cleaner took the new folder for a stale one: try another name
  struct stat held {}, named {};
  // The lock must be on the file that is still there: a cleaner may have removed the folder
  // between mkdir and flock.
  if (flock(lockFd_, LOCK_EX | LOCK_NB) == 0 && fstat(lockFd_, &held) == 0 && stat(lockPath.c_str(), &named) == 0 &&
      held.st_ino == named.st_ino && held.st_dev == named.st_dev)
    return true;
  close(lockFd_);
  lockFd_ = -1;
  return false;
}

StagingFolder::~StagingFolder() {
  {
    std::lock_guard<std::mutex> lock(registryMutex());
    registry().erase(path_);
  }
  removeQuietly(path_);
  if (lockFd_ >= 0) close(lockFd_);
}

std::vector<fs::path> StagingFolder::stagedFiles() const {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(path_)) {
    const std::string name = e.path().filename().string();
    if (name != kLock && name.rfind(kBackupPrefix, 0) != 0) files.push_back(e.path());
  }
  return files;
}

fs::path StagingFolder::backupFor(const fs::path& name) const { return path_ / (kBackupPrefix + name.filename().string()); }

void StagingFolder::removeStale(const fs::path& target) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(folderOf(target), ec))
    if (isStagingName(entry.path().filename().string()) && entry.is_directory(ec)) removeIfAbandoned(entry.path());
}

std::mutex& StagingFolder::commitMutex() {
  static auto* m = new std::mutex;
  return *m;
}

void StagingFolder::removeAllLive() {
  std::lock_guard<std::mutex> commit(commitMutex());
  std::lock_guard<std::mutex> lock(registryMutex());
  std::error_code ignored;  // this runs on the signal watcher's thread: nothing may throw
  // The job's threads may still be writing: a file made while remove_all ran (a
  // database's journal) leaves the folder behind, empty once that file goes. Again, then.
  for (const fs::path& p : registry())
    for (int attempt = 0; attempt < 5 && fs::exists(p, ignored); ++attempt) {
      if (attempt) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      removeQuietly(p);
    }
  registry().clear();
}

}  // namespace tinlod
