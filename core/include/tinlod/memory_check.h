// SPDX-License-Identifier: GPL-3.0-or-later
// A DEM too large for the machine is said before a height is read: otherwise the run fails
// with "std::bad_alloc", or fills the memory for minutes until the system kills it (in the
// QGIS desktop, QGIS with it).
#pragma once

#include <cstdint>
#include <string>

#include "tinlod/feedback.h"

namespace tinlod {

// What a job holds at its peak for each cell of the DEM it reads (docs/performance.md,
// "Memory"), and what to do instead, for the messages.
struct MemoryUse {
  std::string doing;  // "building its hierarchy"
  double bytesPerCell = 0;
  std::string instead;  // "cut it into tiles with tinlod tiles, ..."
  // What no option can lower (the DEM's own cells), and what to do when even that is too
  // much: a larger -block would not help then.
  double floorBytesPerCell = 0;
  std::string insteadAtFloor;
};

// This machine's memory in bytes, RAM and swap, within a cgroup's limit (a container's) and
// this process's address-space limit (ulimit -v, as batch clusters set); 0 where unknown.
struct MachineMemory {
  double total = 0, available = 0;
};
MachineMemory machineMemory();

enum class MemoryVerdict { Fits, Tight, TooLarge };

// TooLarge when even 3/4 of `needBytes` (the estimates run up to a quarter high) exceeds
// the machine's memory and swap; Tight when `needBytes` exceeds what is available now.
MemoryVerdict memoryVerdict(double needBytes, const MachineMemory& memory);

// Throws Error (too large) or warns (tight) for `use` over `width` x `height` cells of `path`.
void checkMemory(const std::string& path, std::int64_t width, std::int64_t height, const MemoryUse& use,
                 const ProgressRange& progress, const MachineMemory& memory = machineMemory());

}  // namespace tinlod
