// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/memory_check.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "tinlod/error.h"

namespace tinlod {
namespace {

// /proc/meminfo's items, in bytes.
std::map<std::string, double> meminfo() {
  std::map<std::string, double> items;
  std::ifstream in("/proc/meminfo");
  std::string name;
  double kib = 0;
  std::string unit;
  while (in >> name >> kib) {
    std::getline(in, unit);
    if (!name.empty() && name.back() == ':') name.pop_back();
    items[name] = kib * 1024;
  }
  return items;
}

// A cgroup v2 limit (a container's memory), as a number of bytes; 0 for none.
double cgroupValue(const char* file) {
  std::ifstream in(std::string("/sys/fs/cgroup/") + file);
  std::string text;
  if (!(in >> text) || text == "max") return 0;
  return std::strtod(text.c_str(), nullptr);
}

// ulimit -v: every mapping counts, the libraries' and the threads' stacks as the heap.
double addressSpaceLimit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return double(limit.rlim_cur);
}

double addressSpaceUsed() {
  std::ifstream in("/proc/self/statm");
  double pages = 0;
  in >> pages;
  return pages * double(sysconf(_SC_PAGE_SIZE));
}

void capAt(MachineMemory& m, double total, double available) {
  m.total = m.total > 0 ? std::min(m.total, total) : total;
  m.available = m.available > 0 ? std::min(m.available, available) : available;
}

std::string bytesText(double bytes) {
  const char* units[] = {"bytes", "KB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000 && u < 5) bytes /= 1000, ++u;
  std::ostringstream out;
  out.precision(bytes < 10 ? 2 : 3);
  out << bytes << " " << units[u];
  return out.str();
}

}  // namespace

MachineMemory machineMemory() {
  const std::map<std::string, double> m = meminfo();
  const auto item = [&m](const char* name) { const auto i = m.find(name); return i == m.end() ? 0.0 : i->second; };
  MachineMemory out;
  out.total = item("MemTotal") + item("SwapTotal");
  out.available = item("MemAvailable") + item("SwapFree");
  if (out.total == 0) {
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && size > 0) out.total = double(pages) * double(size);
  }
  if (const double limit = cgroupValue("memory.max"); limit > 0)
    capAt(out, limit, std::max(0.0, limit - cgroupValue("memory.current")));
  if (const double limit = addressSpaceLimit(); limit > 0) capAt(out, limit, std::max(0.0, limit - addressSpaceUsed()));
  return out;
}

MemoryVerdict memoryVerdict(double needBytes, const MachineMemory& memory) {
  if (memory.total > 0 && 0.75 * needBytes > memory.total) return MemoryVerdict::TooLarge;
  if (memory.available > 0 && needBytes > memory.available) return MemoryVerdict::Tight;
  return MemoryVerdict::Fits;
}

void checkMemory(const std::string& path, std::int64_t width, std::int64_t height, const MemoryUse& use,
                 const ProgressRange& progress, const MachineMemory& memory) {
  const double cells = double(width) * double(height), need = cells * use.bytesPerCell;
  const std::string what = "'" + path + "' has " + std::to_string(width * height) + " cells (" + std::to_string(width) +
                           " x " + std::to_string(height) + "): " + use.doing + " holds about " + bytesText(need) +
                           " for them (" + std::to_string(static_cast<int>(std::lround(use.bytesPerCell))) +
                           " bytes a cell)";
  switch (memoryVerdict(need, memory)) {
    case MemoryVerdict::TooLarge: {
      const bool atFloor = !use.insteadAtFloor.empty() &&
                           memoryVerdict(cells * use.floorBytesPerCell, memory) == MemoryVerdict::TooLarge;
      throw Error(what + ", more than the " + bytesText(memory.total) + " of memory and swap this run may use: " +
                  (atFloor ? use.insteadAtFloor : use.instead));
    }
    case MemoryVerdict::Tight:
      progress.warn(what + ", more than the " + bytesText(memory.available) +
                    " of memory free now: the run may be slow, or stopped by the system; " + use.instead);
      break;
    case MemoryVerdict::Fits:
      break;
  }
}

}  // namespace tinlod
