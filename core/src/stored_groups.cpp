// SPDX-License-Identifier: GPL-3.0-or-later
#include <vector>

#include "stored_hierarchy.h"

namespace tinlod {
namespace {

constexpr std::int64_t kMaxGroups = INT32_MAX;  // group ids are int32 in the triangles

Group groupOf(const StoredRow& row, const Hierarchy& h, const int level, const int vertex) {
  Group g;
  g.level = static_cast<std::int32_t>(row.integer(level, 1, h.coarsest(), "levels a vertex can be deleted at"));
  g.vertex = static_cast<VertexId>(
      row.integer(vertex, 1, static_cast<std::int64_t>(h.base.vertices.size()), "vertex ids") - 1);
  return g;
}

// A vertex is deleted once, by its group, and is in the levels below the group's; a
// vertex no group deletes is in every level.
void checkVertexLevels(const std::string& path, const Hierarchy& h) {
  std::vector<std::int32_t> deletedBy(h.base.vertices.size(), kNoGroup);
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    std::int32_t& by = deletedBy[h.groups[g].vertex];
    if (by != kNoGroup)
      throwDamaged(path, "groups " + std::to_string(by + 1) + " and " + std::to_string(g + 1) + " both delete vertex " +
                             std::to_string(h.groups[g].vertex + 1));
    by = static_cast<std::int32_t>(g);
  }
  for (std::size_t v = 0; v < deletedBy.size(); ++v) {
    const std::int32_t by = deletedBy[v];
    const std::int32_t expected = by == kNoGroup ? h.coarsest() : h.groups[by].level - 1;
    if (h.vertexLevel[v] != expected)
      throwDamaged(
          path, "vertex " + std::to_string(v + 1) + " has level " + std::to_string(h.vertexLevel[v]) + " but " +
                    (by == kNoGroup
                         ? std::string("no group deletes it")
                         : "group " + std::to_string(by + 1) + " deletes it at level " + std::to_string(expected + 1)) +
                    ": its last level must be " + std::to_string(expected));
  }
}

}  // namespace

void readStoredGroups(const StoredTable& table, Hierarchy& h) {
  const int id = table.column("id"), level = table.column("level"), vertex = table.column("vertex");
  const int importance = table.column("importance"), error = table.column("error");
  std::vector<std::int64_t> ids;
  std::vector<GIntBig> fids;
  table.layer().SetIgnoredFields(
      std::vector<const char*>{"OGR_GEOMETRY", nullptr}.data());  // the outlines are not read
  for (auto& f : table.layer()) {
    const StoredRow row(table, *f);
    ids.push_back(row.integer(id, 1, kMaxGroups, "group ids"));
    fids.push_back(f->GetFID());
    Group g = groupOf(row, h, level, vertex);
    g.importance = f->GetFieldAsDouble(importance);  // as measured, for people: nothing computes with it
    g.error = row.nonNegative(error);
    h.groups.push_back(g);
  }
  table.checkFullyRead();
  orderById(h.groups, table.rowsById(ids, fids));
  checkVertexLevels(table.path(), h);
}

void linkStoredGroups(const std::string& path, Hierarchy& h) {
  linkGroups(h);
  for (std::size_t g = 0; g < h.groups.size(); ++g) {
    const bool noAccept = h.groups[g].acceptEnd == h.groups[g].acceptBegin;
    if (noAccept || h.groups[g].rejectEnd == h.groups[g].rejectBegin)
      throwDamaged(path, "group " + std::to_string(g + 1) + " has no " + (noAccept ? "accept" : "reject") +
                             " triangle (no triangles row has " + (noAccept ? "replaced_by " : "group_id ") +
                             std::to_string(g + 1) + ")");
  }
}

}  // namespace tinlod
