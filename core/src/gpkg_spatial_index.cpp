// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_spatial_index.h"

#include "sqlite_batch_insert.h"
#include "tinlod/error.h"

namespace tinlod {
namespace {

// The extension's triggers keep the index true when the table is edited afterwards (in
// QGIS, say), in the words GDAL 3.6 writes them.
void createTriggers(SqliteDatabase& db, const std::string& t, const std::string& rtree) {
  const std::string bounds = "(NEW.\"fid\",ST_MinX(NEW.\"geom\"), ST_MaxX(NEW.\"geom\"),ST_MinY(NEW.\"geom\"), ST_MaxY(NEW.\"geom\"))";
  const std::string on = " ON " + sqlName(t) + " WHEN ";
  const std::string present = "(NEW.\"geom\" NOTNULL AND NOT ST_IsEmpty(NEW.\"geom\"))";
  const std::string absent = "(NEW.\"geom\" ISNULL OR ST_IsEmpty(NEW.\"geom\"))";
  const std::string insert = "INSERT OR REPLACE INTO " + sqlName(rtree) + " VALUES " + bounds + "; END";
  const std::string trigger = "CREATE TRIGGER " ;
  db.execute(trigger + sqlName(rtree + "_insert") + " AFTER INSERT ON " + sqlName(t) +
             " WHEN (new.\"geom\" NOT NULL AND NOT ST_IsEmpty(NEW.\"geom\")) BEGIN " + insert);
  db.execute(trigger + sqlName(rtree + "_update1") + " AFTER UPDATE OF \"geom\"" + on + "OLD.\"fid\" = NEW.\"fid\" AND " +
             present + " BEGIN " + insert);
  db.execute(trigger + sqlName(rtree + "_update2") + " AFTER UPDATE OF \"geom\"" + on + "OLD.\"fid\" = NEW.\"fid\" AND " +
             absent + " BEGIN DELETE FROM " + sqlName(rtree) + " WHERE id = OLD.\"fid\"; END");
  db.execute(trigger + sqlName(rtree + "_update3") + " AFTER UPDATE" + on + "OLD.\"fid\" != NEW.\"fid\" AND " + present +
             " BEGIN DELETE FROM " + sqlName(rtree) + " WHERE id = OLD.\"fid\"; " + insert);
  db.execute(trigger + sqlName(rtree + "_update4") + " AFTER UPDATE" + on + "OLD.\"fid\" != NEW.\"fid\" AND " + absent +
             " BEGIN DELETE FROM " + sqlName(rtree) + " WHERE id IN (OLD.\"fid\", NEW.\"fid\"); END");
  db.execute(trigger + sqlName(rtree + "_delete") + " AFTER DELETE ON " + sqlName(t) +
             " WHEN old.\"geom\" NOT NULL BEGIN DELETE FROM " + sqlName(rtree) + " WHERE id = OLD.\"fid\"; END");
}

void registerExtension(SqliteDatabase& db, const std::string& table) {
  if (!db.hasSchemaObject("gpkg_extensions"))
    db.execute("CREATE TABLE gpkg_extensions (table_name TEXT, column_name TEXT, extension_name TEXT NOT NULL, "
               "definition TEXT NOT NULL, scope TEXT NOT NULL, "
               "CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name))");
  SqliteStatement add = db.prepare(
      "INSERT INTO gpkg_extensions (table_name, column_name, extension_name, definition, scope) VALUES "
      "(?, 'geom', 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', 'write-only')");
  add.bindText(1, table);
  add.step();
}

void writeNodes(SqliteDatabase& db, const std::string& rtree, const PackedRtree& tree, std::size_t nodeBytes,
                const ProgressRange& progress) {
  db.execute("DELETE FROM " + sqlName(rtree + "_node"));  // the empty root SQLite made
  SqliteStatement node = db.prepare("INSERT INTO " + sqlName(rtree + "_node") + " (nodeno, data) VALUES (?, ?)");
  std::vector<unsigned char> blob;
  for (std::size_t n = 1; n <= tree.nodes(); ++n) {
    tree.nodeBlob(n, nodeBytes, blob);
    node.bind(1, static_cast<std::int64_t>(n));
    node.bindBlob(2, blob.data(), blob.size());
    node.step();
    if ((n & 0x3FF) == 0) progress.report(double(n) / tree.nodes(), "Writing the spatial index");
  }
  const std::vector<std::uint32_t> parent = tree.parents();
  SqliteStatement link = db.prepare("INSERT INTO " + sqlName(rtree + "_parent") + " (nodeno, parentnode) VALUES (?, ?)");
  for (std::size_t n = 2; n < parent.size(); ++n) {
    link.bind(1, static_cast<std::int64_t>(n));
    link.bind(2, parent[n]);
    link.step();
  }
}

void writeRowids(SqliteDatabase& db, const std::string& rtree, const PackedRtree& tree,
                 const ProgressRange& progress) {
  const std::vector<std::uint32_t> leaf = tree.leaves();
  SqliteBatchInsert rows(db, rtree + "_rowid", {"rowid", "nodeno"}, 256);
  for (std::size_t i = 0; i < leaf.size(); ++i) {
    rows.set(0, static_cast<std::int64_t>(i) + 1);
    rows.set(1, leaf[i]);
    rows.endRow();
    if ((i & 0x3FFF) == 0) progress.report(double(i) / leaf.size(), "Writing the spatial index");
  }
  rows.flush();
}

}  // namespace

int gpkgRtreeCapacity(SqliteDatabase& db) {
  return rtreeNodeCapacity(static_cast<int>(db.integer("PRAGMA page_size", 4096)));
}

void writeGpkgSpatialIndex(SqliteDatabase& db, const std::string& table, PackedRtree tree,
                           const ProgressRange& progress) {
  const std::string rtree = "rtree_" + table + "_geom";
  db.execute("CREATE VIRTUAL TABLE " + sqlName(rtree) + " USING rtree(id, minx, maxx, miny, maxy)");
  const auto nodeBytes = static_cast<std::size_t>(db.integer("SELECT length(data) FROM " + sqlName(rtree + "_node") + " WHERE nodeno = 1"));
  if (nodeBytes < 4 + 24 * std::size_t(gpkgRtreeCapacity(db)))
    throw Error("SQLite made R-tree nodes of " + std::to_string(nodeBytes) + " bytes, too small for the packed index");
  if (tree.entries() > 0) {
    const double nodeShare = double(tree.nodes()) / (tree.nodes() + tree.entries() / 8.0);
    writeNodes(db, rtree, tree, nodeBytes, progress.sub(0, nodeShare));
    tree.dropEntryBoxes();
    writeRowids(db, rtree, tree, progress.sub(nodeShare, 1));
  }
  createTriggers(db, table, rtree);
  registerExtension(db, table);
}

}  // namespace tinlod
