// SPDX-License-Identifier: GPL-3.0-or-later
#include <vector>

#include "stored_hierarchy.h"

namespace tinlod {
namespace {

// How many triangles each level holds, from each one's range of levels in one pass
// (levelTriangles() per level would pass over them once per level).
std::vector<std::int64_t> trianglesPerLevel(const Hierarchy& h) {
  std::vector<std::int64_t> change(h.levels.size() + 1, 0);
  for (const HierarchyTriangle& t : h.triangles) ++change[t.firstLevel], --change[t.lastLevel + 1];
  std::vector<std::int64_t> count(h.levels.size(), 0);
  for (std::size_t L = 0; L < count.size(); ++L) count[L] = (L ? count[L - 1] : 0) + change[L];
  return count;
}

// A vertex of level L (the last that holds it) is in levels 0 to L.
std::vector<std::int64_t> verticesPerLevel(const Hierarchy& h) {
  std::vector<std::int64_t> count(h.levels.size(), 0);
  for (std::int32_t level : h.vertexLevel) ++count[level];
  for (std::size_t L = count.size() - 1; L-- > 0;) count[L] += count[L + 1];
  return count;
}

std::vector<std::int64_t> groupsPerLevel(const Hierarchy& h) {
  std::vector<std::int64_t> count(h.levels.size(), 0);
  for (const Group& g : h.groups) ++count[g.level];
  return count;
}

void compare(const std::string& path, const std::vector<std::int64_t>& counted, std::size_t LevelStats::*stated,
             const Hierarchy& h, const char* what, const char* table) {
  for (std::size_t L = 0; L < counted.size(); ++L)
    if (static_cast<std::uint64_t>(counted[L]) != h.levels[L].*stated)
      throwDamaged(path, "level " + std::to_string(L) + " has " + std::to_string(counted[L]) + " " + what + " in the " +
                             table + " table but " + std::to_string(h.levels[L].*stated) + " in the levels table");
}

}  // namespace

void checkLevelCounts(const std::string& path, const Hierarchy& h) {
  compare(path, verticesPerLevel(h), &LevelStats::vertices, h, "vertices", "vertices");
  compare(path, trianglesPerLevel(h), &LevelStats::triangles, h, "triangles", "triangles");
  compare(path, groupsPerLevel(h), &LevelStats::deleted, h, "deleted vertices", "groups");
}

}  // namespace tinlod
