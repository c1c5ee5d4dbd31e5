// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>

#include "tinlod/feedback.h"
#include "tinlod/gpkg_writer.h"
#include "tinlod/hierarchy.h"
#include "tinlod/hierarchy_layers.h"

namespace tinlod {

// One GeoPackage holds the whole hierarchy, in its CRS:
// - vertices (PointZ): id, row, col, outline, level (the highest level holding it), fixed
// - triangles (PolygonZ): every distinct triangle once: id, v0, v1, v2, first_level,
//   last_level, group_id (the group that made it; empty at level 0), replaced_by (the
//   group that replaced it), error (metres, to the DEM at the valid cell centres under it)
// - level_0, level_1, ...: views of the triangles of each level (stored once, not per
//   level), those of `layers`
// - groups (Polygon, or a table without `layers.groupOutlines`): the outline of each deleted vertex's neighbourhood: id, level,
//   vertex, importance, error; its accept triangles are those with replaced_by = id,
//   its reject triangles those with group_id = id
// - levels (table): level, vertices, triangles, deleted, select_seconds, delete_seconds,
//   max_error, and the method, delete_pct and stop_pct that made it
// Ids count from 1 and equal the fid. Written atomically, as writeTinGpkg.
void writeHierarchyGpkg(const Hierarchy& hierarchy, const std::string& path, const GpkgWriteOptions& options,
                        const ProgressRange& progress, const HierarchyLayers& layers = {});
// The same into a file of a job's OutputFiles, moved into place with the job's other outputs.
void writeHierarchyGpkg(const Hierarchy& hierarchy, const StagedFile& file, const GpkgWriteOptions& options,
                        const ProgressRange& progress, const HierarchyLayers& layers = {});

}  // namespace tinlod
