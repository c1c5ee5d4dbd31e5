// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_feature_rows.h"

#include <utility>

namespace tinlod {
namespace {

std::vector<std::string> columnsOf(const std::vector<std::string>& fields, bool hasGeometry) {
  std::vector<std::string> columns{"fid"};
  if (hasGeometry) columns.emplace_back("geom");
  columns.insert(columns.end(), fields.begin(), fields.end());
  return columns;
}

// GDAL's triggers count features one UPDATE per row; they are set aside while the rows
// go in and made again, with the count written once, at the end.
std::string countTrigger(const std::string& table, bool insert) {
  return "CREATE TRIGGER " + sqlName(std::string("trigger_") + (insert ? "insert" : "delete") + "_feature_count_" + table) +
         (insert ? " AFTER INSERT" : " AFTER DELETE") + " ON " + sqlName(table) +
         " BEGIN UPDATE gpkg_ogr_contents SET feature_count = feature_count " + (insert ? "+" : "-") +
         " 1 WHERE lower(table_name) = lower('" + table + "'); END";
}

}  // namespace

GpkgFeatureRows::GpkgFeatureRows(SqliteDatabase& db, std::string table, const std::vector<std::string>& fields,
                                 bool hasGeometry)
    : db_(db), table_(std::move(table)), first_(hasGeometry ? 2 : 1), rows_(db, table_, columnsOf(fields, hasGeometry)) {
  counted_ = db_.hasSchemaObject("trigger_insert_feature_count_" + table_);
  db_.execute("DROP TRIGGER IF EXISTS " + sqlName("trigger_insert_feature_count_" + table_));
  db_.execute("DROP TRIGGER IF EXISTS " + sqlName("trigger_delete_feature_count_" + table_));
}

void GpkgFeatureRows::insert(std::int64_t fid, const GpkgGeometryBlob& geometry) {
  rows_.set(0, fid);
  rows_.setBlob(1, geometry.data(), geometry.size());
  rows_.endRow();
  ++count_;
  extent_.extend(geometry.envelope());
}

void GpkgFeatureRows::insert(std::int64_t fid) {
  rows_.set(0, fid);
  rows_.endRow();
  ++count_;
}

void GpkgFeatureRows::finish() {
  rows_.flush();
  // A file made without GDAL's gpkg_ogr_contents (ADD_GPKG_OGR_CONTENTS=NO, another tool)
  // has no count to keep.
  if (db_.hasSchemaObject("gpkg_ogr_contents")) {
    SqliteStatement count = db_.prepare("UPDATE gpkg_ogr_contents SET feature_count = ? WHERE lower(table_name) = lower(?)");
    count.bind(1, count_);
    count.bindText(2, table_);
    count.step();
  }
  if (counted_) {
    db_.execute(countTrigger(table_, true));
    db_.execute(countTrigger(table_, false));
  }
  if (extent_.isEmpty()) return;
  SqliteStatement extent = db_.prepare(
      "UPDATE gpkg_contents SET min_x = ?, min_y = ?, max_x = ?, max_y = ?, "
      "last_change = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE lower(table_name) = lower(?)");
  extent.bindReal(1, extent_.minX);
  extent.bindReal(2, extent_.minY);
  extent.bindReal(3, extent_.maxX);
  extent.bindReal(4, extent_.maxY);
  extent.bindText(5, table_);
  extent.step();
}

}  // namespace tinlod
