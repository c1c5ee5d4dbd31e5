// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the rows of one GeoPackage feature table (made by GDAL, empty) written
// through one prepared statement, in the caller's transaction.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "gpkg_geometry_blob.h"
#include "sqlite_batch_insert.h"
#include "sqlite_database.h"

namespace tinlod {

class GpkgFeatureRows {
 public:
  // `fields` are the table's attribute columns in the order set() numbers them; a table
  // without geometry (an attributes table) takes its rows by insert(fid).
  GpkgFeatureRows(SqliteDatabase& db, std::string table, const std::vector<std::string>& fields,
                  bool hasGeometry = true);

  void set(int field, std::int64_t value) { rows_.set(field + first_, value); }
  // NaN and infinity are written as null, as the OGR path did.
  void setReal(int field, double value) {
    if (std::isfinite(value)) rows_.setReal(field + first_, value);
    else rows_.setNull(field + first_);
  }
  void setNull(int field) { rows_.setNull(field + first_); }
  void insert(std::int64_t fid, const GpkgGeometryBlob& geometry);
  void insert(std::int64_t fid);
  // The feature count and extent GDAL and QGIS read from the GeoPackage's tables.
  void finish();
  // Writes the rows held back for the next batched statement, so that statements of the
  // caller's (an UPDATE) see every row inserted so far.
  void flush() { rows_.flush(); }
  const std::string& table() const { return table_; }

 private:
  SqliteDatabase& db_;
  std::string table_;
  int first_;  // the column of field 0: after fid, and geom when there is one
  SqliteBatchInsert rows_;
  std::int64_t count_ = 0;
  bool counted_ = false;  // GDAL's feature-count triggers were there, to be made again
  Envelope extent_ = Envelope::empty();
};

}  // namespace tinlod
