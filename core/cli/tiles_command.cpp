// SPDX-License-Identifier: GPL-3.0-or-later
// `tinlod tiles ...` is `tinlod-tiles ...`: the Dask tile driver is a Python program (it
// runs on Debian's Python, with GDAL's bindings and Dask), so this command only finds it
// beside this binary and hands over the process to it.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.h"
#include "tinlod/error.h"

namespace tinlod::cli {
namespace {

namespace fs = std::filesystem;

// Installed, bin/tinlod-tiles is beside bin/tinlod; in the build tree, build/tiles/tinlod-tiles
// is beside build/core/.
fs::path tilesProgram() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw Error("cannot find tinlod-tiles: /proc/self/exe is unreadable; run tinlod-tiles itself");
  for (const fs::path& candidate : {self.parent_path() / "tinlod-tiles",
                                    self.parent_path().parent_path() / "tiles" / "tinlod-tiles"}) {
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  throw Error("tinlod-tiles is not installed beside " + self.string() +
              ": install tinlod whole (it ships bin/tinlod-tiles), or run tinlod-tiles from the build tree");
}

}  // namespace

int tilesCommand(std::vector<std::string> args) {
  const fs::path program = tilesProgram();
  std::vector<char*> argv{const_cast<char*>("tinlod-tiles")};
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(program.c_str(), argv.data());
  throw Error("cannot run " + program.string() + ": " + std::strerror(errno));
}

}  // namespace tinlod::cli
