// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a GeoPackage's spatial index (the gpkg_rtree_index extension) bulk-loaded
// from a packed R-tree, with the triggers the extension requires.
#pragma once

#include <string>

#include "packed_rtree.h"
#include "sqlite_database.h"
#include "tinlod/feedback.h"

namespace tinlod {

// Creates rtree_<table>_geom and fills its node, parent and rowid tables from `tree`,
// whose entries are the table's fids 1..n. The tree is taken, and its entries' boxes freed
// once the nodes are written, before the rowid table's lookup is made.
void writeGpkgSpatialIndex(SqliteDatabase& db, const std::string& table, PackedRtree tree,
                           const ProgressRange& progress);

// The node capacity SQLite will give a new rtree in this database.
int gpkgRtreeCapacity(SqliteDatabase& db);

}  // namespace tinlod
