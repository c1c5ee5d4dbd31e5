// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <vector>

#include "stored_hierarchy.h"

namespace tinlod {
namespace {

// Triangle indices are uint32 and each is linked twice at most: the links fit too.
constexpr std::size_t kMaxTriangles = INT32_MAX;

// Field positions looked up once: by name, each row would search them again.
struct TriangleColumns {
  int corner[3];
  int first = -1, last = -1, group = -1, replacedBy = -1, error = -1;
};

TriangleColumns triangleColumns(const StoredTable& table, bool levelled) {
  TriangleColumns c{{table.column("v0"), table.column("v1"), table.column("v2")}};
  if (levelled) {
    c.first = table.column("first_level"), c.last = table.column("last_level");
    c.group = table.column("group_id"), c.replacedBy = table.column("replaced_by");
    c.error = table.column("error");
  }
  return c;
}

// Three distinct vertices: a triangle with a repeated corner has no area, and the
// locator and the rasterizer would divide by it.
Triangle cornersOf(const StoredRow& row, const TriangleColumns& c, std::size_t vertices) {
  Triangle t;
  for (int k = 0; k < 3; ++k)
    t[k] = static_cast<VertexId>(row.integer(c.corner[k], 1, static_cast<std::int64_t>(vertices), "vertex ids") - 1);
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    row.damaged("repeats a vertex (v0, v1, v2 = " + std::to_string(t[0] + 1) + ", " + std::to_string(t[1] + 1) + ", " +
                std::to_string(t[2] + 1) + ")");
  return t;
}

std::int32_t groupIdOf(const StoredRow& row, int column, const Hierarchy& h) {
  const auto groups = static_cast<std::int64_t>(h.groups.size());
  return static_cast<std::int32_t>(row.optionalInteger(column, 1, groups, "group ids", 0) - 1);  // NULL: kNoGroup
}

// A triangle appears at the level of the group whose deletion made it (level 0 when none
// did) and goes one level below that of the group that replaces it (never, when none
// does). As every group's level is above 0, each link then leads from a level to a finer
// one: the links cannot form a cycle, and a search along them ends.
void checkLinks(const StoredRow& row, const HierarchyTriangle& t, const Hierarchy& h) {
  // The message is built only for a refusal: this runs for every triangle.
  auto refuse = [&](const std::string& why) {
    row.damaged("has first_level " + std::to_string(t.firstLevel) + " and last_level " + std::to_string(t.lastLevel) +
                why);
  };
  if (t.lastLevel < t.firstLevel) refuse(": its last level is before its first");
  if (t.group == kNoGroup && t.firstLevel != 0)
    refuse(" but no group_id: only triangles of level 0 were made by no group");
  if (t.group != kNoGroup && h.groups[t.group].level != t.firstLevel)
    refuse(" but its group_id " + std::to_string(t.group + 1) + " made it at level " +
           std::to_string(h.groups[t.group].level) + " (a broken link)");
  if (t.replacedBy == kNoGroup && t.lastLevel != h.coarsest())
    refuse(" but no replaced_by: only triangles of the coarsest level, " + std::to_string(h.coarsest()) +
           ", are replaced by no group");
  if (t.replacedBy != kNoGroup && h.groups[t.replacedBy].level != t.lastLevel + 1)
    refuse(" but its replaced_by " + std::to_string(t.replacedBy + 1) + " replaces it at level " +
           std::to_string(h.groups[t.replacedBy].level) + " (a broken link, or one that would make a cycle)");
}

HierarchyTriangle levelledTriangle(const StoredRow& row, const TriangleColumns& c, const Hierarchy& h) {
  HierarchyTriangle t;
  t.v = cornersOf(row, c, h.base.vertices.size());
  // The levels table said there are at most kMaxLevel + 1 levels.
  t.firstLevel = static_cast<std::int16_t>(row.integer(c.first, 0, h.coarsest(), "levels"));
  t.lastLevel = static_cast<std::int16_t>(row.integer(c.last, 0, h.coarsest(), "levels"));
  t.group = groupIdOf(row, c.group, h);
  t.replacedBy = groupIdOf(row, c.replacedBy, h);
  checkLinks(row, t, h);
  t.error = roundedUpError(row.nonNegative(c.error));
  return t;
}

}  // namespace

void readStoredTriangles(const StoredTable& table, Hierarchy& h, bool levelled, std::uintmax_t fileBytes,
                         const ProgressRange& progress) {
  const TriangleColumns c = triangleColumns(table, levelled);
  const std::size_t expected = table.plausibleRows(fileBytes);
  table.layer().SetIgnoredFields(std::vector<const char*>{"OGR_GEOMETRY", nullptr}.data());  // corners come from v0..v2
  h.triangles.reserve(expected);
  for (auto& f : table.layer()) {
    const StoredRow row(table, *f);
    if (h.triangles.size() == kMaxTriangles)
      row.damaged("is beyond the " + std::to_string(kMaxTriangles) + " triangles tinlod reads");
    HierarchyTriangle t;
    if (levelled)
      t = levelledTriangle(row, c, h);
    else
      t.v = cornersOf(row, c, h.base.vertices.size());
    if (t.firstLevel == 0) h.base.triangles.push_back(t.v);
    h.triangles.push_back(t);
    if ((h.triangles.size() & 0xFFFF) == 0)
      progress.report(double(h.triangles.size()) / std::max<std::size_t>(1, expected), "Reading triangles");
  }
  table.checkFullyRead();
}

}  // namespace tinlod
