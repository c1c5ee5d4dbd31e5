// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <filesystem>

namespace tinlod {

// A hidden sibling file that becomes the output only when commit() renames it into
// place: until then the output is untouched, and on destruction without commit the
// temporary file (and any SQLite journal beside it) is removed. A symbolic link as
// output is followed, so its target is what gets replaced.
class TemporaryOutput {
 public:
  explicit TemporaryOutput(const std::filesystem::path& output);
  ~TemporaryOutput();
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;

  const std::filesystem::path& path() const { return temporary_; }
  const std::filesystem::path& output() const { return output_; }
  void commit();

  // Removes temporary files that runs killed outright (SIGKILL, power loss) left
  // beside `output`: those whose process no longer exists.
  static void removeStale(const std::filesystem::path& output);

 private:
  void remove() const;
  std::filesystem::path output_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

}  // namespace tinlod
