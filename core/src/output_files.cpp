// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/output_files.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

#include "sqlite_in_use.h"
#include "staging_folder.h"
#include "text_and_paths.h"
#include "tinlod/error.h"

namespace fs = std::filesystem;

namespace tinlod {
namespace {

std::atomic<bool>& committed() {
  static auto* done = new std::atomic<bool>(false);  // read by a watchdog thread at exit
  return *done;
}
bool committedOnce() { return committed(); }

// Whether the disk that holds `folder` is full (under 1 MB left to this process).
bool diskFull(const fs::path& folder) {
  std::error_code ec;
  const fs::space_info space = fs::space(folder, ec);
  if (ec) return false;
  // Root may write into the blocks a file system keeps back from the others.
  return (geteuid() == 0 ? space.free : space.available) < (1u << 20);
}

fs::path folderOf(const fs::path& p) { return p.parent_path().empty() ? fs::path(".") : p.parent_path(); }

// A symbolic link as output is followed, so its target is what gets replaced.
fs::path resolved(const fs::path& output) {
  std::error_code ec;
  return fs::is_symlink(output, ec) ? fs::weakly_canonical(output, ec) : output;
}

struct Moved {
  fs::path target;
  fs::path backup;  // empty: nothing was there before
};

fs::filesystem_error moveError(const fs::path& from, const fs::path& to) {
  return fs::filesystem_error("cannot move", from, to, std::error_code(errno, std::generic_category()));
}

// Without overwrite the move must not replace a file that appeared since the job's
// checks (another run): RENAME_NOREPLACE, or link() where a file system lacks it.
bool moveWithoutReplacing(const fs::path& from, const fs::path& to) {
  if (renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return true;
  if (errno == EEXIST) return false;
  if (errno != EINVAL && errno != ENOSYS) throw moveError(from, to);
  if (link(from.c_str(), to.c_str()) != 0) {
    if (errno == EEXIST) return false;
    throw moveError(from, to);
  }
  unlink(from.c_str());
  return true;
}

// Puts staged at target; returns where the file it replaced is kept (empty: none was
// there), reachable in the staging folder until the commit is complete so that a later
// failure can put it back. Where the file system can, the two names are exchanged (the
// old file is then at the staged name): ext4 writes out a file renamed over another
// before the rename returns (auto_da_alloc; 50 ms for 230 MB), and an exchange leaves
// that to the kernel's writeback, as for a new file.
fs::path replaceKeepingOld(const fs::path& staged, const fs::path& target, const fs::path& backup) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(target, ec))) {
    fs::rename(staged, target);
    return {};
  }
  if (renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) return staged;
  if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) throw moveError(staged, target);
  if (link(target.c_str(), backup.c_str()) != 0) fs::rename(target, backup);
  fs::rename(staged, target);
  return backup;
}

void takeBack(const std::vector<Moved>& moved) {
  std::error_code ignored;
  for (auto m = moved.rbegin(); m != moved.rend(); ++m) {
    if (m->backup.empty()) fs::remove(m->target, ignored);
    else fs::rename(m->backup, m->target, ignored);
  }
}

fs::path sidecarOf(const StagedFile& file) { return file.target.string() + ".aux.xml"; }

// GDAL keeps a raster's statistics and histogram in NAME.aux.xml: left beside a replaced
// file that did not write one again, it would describe the old one (gdalinfo -stats showed
// the old minimum). Set aside as the replaced files are, so that a failed commit puts it back.
void setAsideOldSidecar(const StagedFile& file, const StagingFolder& folder, std::vector<Moved>& moved) {
  const fs::path sidecar = sidecarOf(file);
  std::error_code ec;
  if (!fs::is_regular_file(sidecar, ec)) return;
  const fs::path backup = folder.backupFor(sidecar.filename());
  fs::rename(sidecar, backup);
  moved.push_back({sidecar, backup});
}

// A file the commit moves, named as the user named the output's folder ("p.prj", not "./p.prj").
std::string shown(const StagedFile& file, const fs::path& target) {
  return target == file.target ? file.path : (fs::path(file.path).parent_path() / target.filename()).string();
}

// Why an existing `target` may not be replaced, as `cp` would not write it: "" when it may.
// Root may write any file, but one no one may write (chmod a-w) is a protected deliverable;
// in a sticky folder (/tmp) only its owner may move another user's file.
std::string whyNotReplaceable(const fs::path& target) {
  struct stat file {}, folder {};
  if (stat(target.c_str(), &file) != 0) return "";
  const auto mode = [](const struct stat& s) {
    char octal[8];
    std::snprintf(octal, sizeof octal, "%04o", unsigned(s.st_mode & 07777));
    return std::string(octal);
  };
  if ((file.st_mode & 0222) == 0)
    return "is write-protected (mode " + mode(file) + "): make it writable (chmod u+w) to replace it";
  if (access(target.c_str(), W_OK) != 0) return "is not yours to write (mode " + mode(file) + ")";
  const uid_t me = geteuid();
  if (me != 0 && stat(folderOf(target).c_str(), &folder) == 0 && (folder.st_mode & S_ISVTX) && file.st_uid != me &&
      folder.st_uid != me)
    return "belongs to another user, in a folder where only a file's owner may replace it (sticky, as /tmp)";
  return "";
}

// The file put in place of `target` keeps its mode, group and (for root) owner: a group's
// shared file stays theirs, a private one private.
void takeOverPermissions(const fs::path& staged, const fs::path& target) {
  struct stat old {};
  if (stat(target.c_str(), &old) != 0) return;
  if (chown(staged.c_str(), geteuid() == 0 ? old.st_uid : uid_t(-1), old.st_gid) != 0) {
    // Not in the file's group: it keeps the run's own.
  }
  chmod(staged.c_str(), old.st_mode & 07777);
}

}  // namespace

bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

OutputFiles::OutputFiles(bool overwrite, std::vector<std::string> inputs)
    : overwrite_(overwrite), inputs_(std::move(inputs)) {}

OutputFiles::~OutputFiles() = default;

void OutputFiles::checkNotInput(const fs::path& target, const std::string& option, const std::string& path) const {
  for (const std::string& input : inputs_)
    if (!input.empty() && sameFile(target, input)) {
      // A sidecar of the output (ENVI's .hdr) may be an input's file; a link to an input is the input.
      const bool itself = sameFile(path, input) || target.filename() == fs::path(path).filename();
      throw Error(option + ": '" + path + "' is " + (itself ? "" : "beside it ") + "an input of this run ('" + input +
                  "'): writing it would destroy the input; choose another name");
    }
}

void OutputFiles::checkBeside(const StagedFile& file, const std::string& name) const {
  const fs::path beside = folderOf(file.target) / name;
  const std::string shownName = shown(file, beside);
  checkNotInput(beside, file.option, shownName);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(beside, ec))) return;
  const std::string why = " (the format writes it beside '" + file.path + "')";
  if (!overwrite_) throw Error(file.option + ": '" + shownName + "' exists" + why + ": add -overwrite to replace it");
  if (const std::string held = whyNotReplaceable(beside); !held.empty())
    throw Error(file.option + ": '" + shownName + "'" + why + " " + held + ", or choose another name");
}

void OutputFiles::refuseInput(const std::string& path, const std::string& option) const {
  checkNotInput(resolved(path), option, path);
}

void refuseVirtualPath(const std::string& path, const std::string& option) {
  if (path.rfind("/vsi", 0) == 0)
    throw Error(option + ": '" + path + "' is a GDAL virtual path; outputs are written as files: give a file path "
                "(zip or copy it afterwards)");
}

const StagedFile& OutputFiles::add(const std::string& path, const std::string& option, bool keepContent) {
  if (path.empty()) throw Error(option + ": no file named");
  refuseVirtualPath(path, option);
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec))
    throw Error(option + ": '" + path + "' is a symbolic link to '" + fs::read_symlink(path, ec).string() +
                "', which does not exist: remove the link or name another file");
  const fs::path target = resolved(path);
  // First: an input's folder is often read-only (a data share), and "not writable" would
  // hide that the name itself is the mistake.
  checkNotInput(target, option, path);
  if (fs::is_directory(target, ec)) throw Error(option + ": '" + path + "' is a folder: name a file");
  const fs::path dir = folderOf(target);
  if (!fs::is_directory(dir, ec)) throw Error(option + ": the folder of '" + path + "' does not exist" + tildeHint(path));
  if (access(dir.c_str(), W_OK) != 0) throw Error(option + ": the folder of '" + path + "' is not writable");
  for (const auto& other : files_)
    if (sameFile(other->target, target))
      throw Error(option + ": '" + path + "' is also given as " + other->option + ": name two different files");
  const bool existed = fs::exists(target, ec);
  if (existed && !overwrite_) throw Error(option + ": '" + path + "' exists: add -overwrite to replace it");
  if (const std::string held = existed ? sqliteFileInUse(target) : ""; !held.empty())
    throw Error(option + ": '" + path + "' " + held + ": close it there, then run again");
  if (const std::string why = existed ? whyNotReplaceable(target) : ""; !why.empty())
    throw Error(option + ": '" + path + "' " + why + ", or choose another name");
  StagingFolder::removeStale(target);
  auto folder = std::make_unique<StagingFolder>(target);
  auto file = std::make_unique<StagedFile>(
      StagedFile{path, option, target, folder->path() / target.filename(), existed, keepContent});
  folders_.push_back(std::move(folder));
  files_.push_back(std::move(file));
  return *files_.back();
}

void copyForUpdate(const StagedFile& file) {
  std::error_code ec;
  fs::copy_file(file.target, file.staging, fs::copy_options::overwrite_existing, ec);
  if (ec) throw Error(file.option + ": cannot copy '" + file.path + "' to update it: " + ec.message());
}

void OutputFiles::commit() {
  std::vector<Moved> moved;
  {
    std::lock_guard<std::mutex> lock(StagingFolder::commitMutex());
    std::string moving = "the outputs";  // the user's name of the file being moved, for an error
    try {
      for (std::size_t i = 0; i < files_.size(); ++i) {
        const StagedFile& file = *files_[i];
        const std::vector<fs::path> staged = folders_[i]->stagedFiles();
        // Decided before the moves, which may exchange old files into the staging folder.
        const bool wroteSidecar = std::any_of(staged.begin(), staged.end(), [&file](const fs::path& p) {
          return p.filename() == sidecarOf(file).filename();
        });
        for (const fs::path& path : staged) {
          const fs::path target = folderOf(file.target) / path.filename();
          checkNotInput(target, file.option, shown(file, target));
          if (fs::is_directory(fs::symlink_status(target)))
            throw Error(file.option + ": '" + shown(file, target) + "' is now a folder: nothing was written");
          if (const std::string held = overwrite_ ? sqliteFileInUse(target) : ""; !held.empty())
            throw Error(file.option + ": '" + shown(file, target) + "' " + held +
                        " (it was opened while this run was working): nothing was written; close it there, then run again");
          moving = "'" + shown(file, target) + "'";
          if (const std::string why = overwrite_ ? whyNotReplaceable(target) : ""; !why.empty())
            throw Error(file.option + ": " + moving + " " + why + " (since this run began): nothing was written");
          if (overwrite_) {
            takeOverPermissions(path, target);
            moved.push_back({target, replaceKeepingOld(path, target, folders_[i]->backupFor(path.filename()))});
          } else if (moveWithoutReplacing(path, target)) {
            moved.push_back({target, {}});
          } else {
            throw Error(file.option + ": '" + shown(file, target) +
                        "' appeared while this run was working (another run?): it is left as it is and nothing was "
                        "written; add -overwrite to replace it");
          }
        }
        moving = "'" + shown(file, sidecarOf(file)) + "'";
        if (overwrite_ && !file.keepContent && !wroteSidecar) setAsideOldSidecar(file, *folders_[i], moved);
      }
      committed() = true;
    } catch (const fs::filesystem_error& e) {
      takeBack(moved);
      throw Error("cannot move " + moving + " into place (" + e.code().message() + "): nothing was written");
    } catch (...) {
      takeBack(moved);
      throw;
    }
  }
  folders_.clear();
}

namespace {

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

}  // namespace

std::string inUserTerms(const StagedFile& file, std::string message) {
  replaceAll(message, file.staging.string(), file.path);
  replaceAll(message, file.staging.parent_path().string(), folderOf(fs::path(file.path)).string());
  return message;
}

std::string writeFailureInUserTerms(const StagedFile& file, const std::string& driverMessage) {
  return diskFull(file.staging.parent_path()) ? "the disk is full" : inUserTerms(file, driverMessage);
}

std::string whyWriteFailed(const fs::path& folder) {
  const int error = errno;
  if (diskFull(folder)) return "the disk is full";
  return error != 0 ? std::strerror(error) : "the write failed";
}

bool abandonStagedOutputs() {
  StagingFolder::removeAllLive();
  return committedOnce();
}

}  // namespace tinlod
