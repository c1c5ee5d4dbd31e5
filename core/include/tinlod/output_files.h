// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace tinlod {

class StagingFolder;

// Where a writer puts one output: `staging` while the job runs, a file in a hidden folder
// beside the output, named as the output is so that sidecar files a driver adds (.aux.xml,
// ENVI's .hdr) are named right too; `path` is the user's name for it, for messages.
struct StagedFile {
  std::string path;
  std::string option;  // how the user gave it: "output", "-accuracy", "-report"
  std::filesystem::path target;   // `path`, or the file a symbolic link there points to
  std::filesystem::path staging;
  bool existed = false;           // the output existed when the job started
  bool keepContent = false;       // its writer keeps what else an existing file holds
};

// Every file one job writes. Each is checked when added, before the long work (it is
// not an input, not named twice, its folder is writable, it does not exist unless
// `overwrite`), written in its staging folder, and moved into place by commit() only
// when the whole job has succeeded: all outputs or none. An error, a cancel or a crash
// before commit() leaves every old file as it was.
class OutputFiles {
 public:
  // `inputs`: every file the job reads (a DEM's sidecars included): none may be replaced.
  explicit OutputFiles(bool overwrite, std::vector<std::string> inputs = {});
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  // With `keepContent`, the writer keeps what else an existing output holds (a
  // GeoPackage's other layers): it copies the file into the staging folder when it has
  // such content (copyForUpdate), and starts a new file when it has none.
  const StagedFile& add(const std::string& path, const std::string& option, bool keepContent = false);
  // A file the writer of `file` adds beside it (ENVI's .hdr), named `name` in its folder:
  // checked as add checks `file`, so that one there already is said before the work, not
  // when the outputs are moved into place.
  void checkBeside(const StagedFile& file, const std::string& name) const;
  // add's first refusal alone: an output that is an input of the job, which -overwrite
  // would not make right (for a check that would otherwise ask for -overwrite first).
  void refuseInput(const std::string& path, const std::string& option) const;
  // Moves every staged file (and its sidecars) into place. Without overwrite a file that
  // appeared meanwhile is not replaced: the error names it and every output moved so far
  // is taken back, as are replaced ones with overwrite.
  void commit();

 private:
  void checkNotInput(const std::filesystem::path& target, const std::string& option, const std::string& path) const;
  bool overwrite_;
  std::vector<std::string> inputs_;
  std::vector<std::unique_ptr<StagingFolder>> folders_;
  std::vector<std::unique_ptr<StagedFile>> files_;
};

// Copies an existing output into its staging file, for a writer that updates it.
void copyForUpdate(const StagedFile& file);

// Removes every staging folder this process still holds. For a front end that must stop
// at once (a second Ctrl-C, a cancel the work does not answer in time): waits while a
// commit is moving files, so outputs are either all in place or none. Returns whether a
// commit had already put outputs in place.
bool abandonStagedOutputs();

// `message` (a driver's, say) with the staging file's name replaced by the user's, and
// the staging folder's by the output's folder (for sidecar files).
std::string inUserTerms(const StagedFile& file, std::string message);

// Throws Error, naming `option`, for a GDAL virtual path (/vsimem/, /vsizip/...): outputs are
// staged and moved into place as files, which those are not.
void refuseVirtualPath(const std::string& path, const std::string& option);

// A driver's message on a failed write of `file`, in the user's terms (inUserTerms); on a
// full disk, that, which drivers word every way ("no such table", "WriteEncodedTile/Strip()
// failed").
std::string writeFailureInUserTerms(const StagedFile& file, const std::string& driverMessage);

// Why a write into `folder` just failed, for a message: "the disk is full", or the system's
// reason (errno) as far as it gave one.
std::string whyWriteFailed(const std::filesystem::path& folder);

// Whether `a` and `b` name the same file (hard links, symbolic links, ./ and ../ alike).
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace tinlod
