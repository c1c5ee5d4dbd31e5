// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the tables of a stored hierarchy (or TIN), read one at a time and each checked
// against those read before it: the levels (from the file's info), the vertices, the
// groups, then the triangles. Once read, every id the readers index with is in range,
// every triangle's levels agree with the groups that make and replace it, and so each
// link between levels leads to a finer level: a damaged or crafted file can make no
// reader loop, nor read or write out of bounds. Every function throws Error naming the
// file, the table and the row.
#pragma once

#include <cstdint>
#include <string>

#include "stored_table.h"
#include "tinlod/feedback.h"
#include "tinlod/hierarchy.h"

namespace tinlod {

// `levelled`: the file is a hierarchy, whose levels h.levels already holds. Any other file
// is one level of its own, whatever levels its rows carry as plain attributes.
void readStoredVertices(const StoredTable& table, Hierarchy& h, bool levelled, std::uintmax_t fileBytes,
                        const ProgressRange& progress);
// Also checks that each vertex a group deletes has the level that deletion gives it.
void readStoredGroups(const StoredTable& table, Hierarchy& h);
void readStoredTriangles(const StoredTable& table, Hierarchy& h, bool levelled, std::uintmax_t fileBytes,
                         const ProgressRange& progress);
// Fills each group's accept and reject triangles from the triangles' replaced_by and
// group_id; every group must have both.
void linkStoredGroups(const std::string& path, Hierarchy& h);
// Each level's vertices, triangles and deleted vertices against its levels row: a row
// dropped from a table shows here.
void checkLevelCounts(const std::string& path, const Hierarchy& h);

}  // namespace tinlod
