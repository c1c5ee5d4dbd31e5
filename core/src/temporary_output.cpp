// SPDX-License-Identifier: GPL-3.0-or-later
#include "temporary_output.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <string>

namespace fs = std::filesystem;

namespace tinlod {
namespace {

const char* const kSidecars[] = {"", "-journal", "-wal", "-shm"};

fs::path resolved(const fs::path& output) {
  std::error_code ec;
  return fs::is_symlink(output, ec) ? fs::weakly_canonical(output, ec) : output;
}

std::string prefixFor(const fs::path& output) { return "." + output.stem().string() + ".tmp-"; }

void removeWithSidecars(const fs::path& file) {
  std::error_code ignored;
  for (const char* suffix : kSidecars) fs::remove(file.string() + suffix, ignored);
}

}  // namespace

TemporaryOutput::TemporaryOutput(const fs::path& output)
    : output_(resolved(output)),
      temporary_(output_.parent_path() / (prefixFor(output_) + std::to_string(getpid()) + output_.extension().string())) {
  removeWithSidecars(temporary_);
}

TemporaryOutput::~TemporaryOutput() {
  if (!committed_) remove();
}

void TemporaryOutput::commit() {
  fs::rename(temporary_, output_);
  committed_ = true;
  remove();  // sidecars only: the file itself is now the output
}

void TemporaryOutput::remove() const {
  if (committed_) {
    std::error_code ignored;
    for (const char* suffix : kSidecars)
      if (*suffix) fs::remove(temporary_.string() + suffix, ignored);
    return;
  }
  removeWithSidecars(temporary_);
}

void TemporaryOutput::removeStale(const fs::path& output) {
  const fs::path target = resolved(output);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string prefix = prefixFor(target);
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

}  // namespace tinlod
