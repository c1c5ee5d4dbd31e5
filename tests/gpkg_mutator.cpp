// SPDX-License-Identifier: GPL-3.0-or-later
#include "gpkg_mutator.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "gpkg_surgery.h"

namespace fs = std::filesystem;

namespace tinlod::test {
namespace {

struct TableColumns {
  const char* table;
  std::vector<const char*> columns;
};

const std::vector<TableColumns>& tinlodTables() {
  static const std::vector<TableColumns> tables = {
      {"vertices", {"fid", "id", "row", "col", "outline", "level", "fixed"}},
      {"triangles", {"fid", "id", "v0", "v1", "v2", "first_level", "last_level", "group_id", "replaced_by", "error"}},
      {"groups", {"fid", "id", "level", "vertex", "importance", "error"}},
      {"levels",
       {"fid", "level", "vertices", "triangles", "deleted", "select_seconds", "delete_seconds", "max_error", "rmse",
        "cells", "cells_given_up", "outline_vertices", "method", "delete_pct", "stop_pct"}},
  };
  return tables;
}

std::string quotedName(const std::string& name) { return "\"" + name + "\""; }

}  // namespace

GpkgMutator::GpkgMutator(const std::string& source, std::uint64_t seed) : source_(source), random_(seed) {
  for (const TableColumns& t : tinlodTables())
    rows_[t.table] = sqlInteger(source, "SELECT count(*) FROM " + quotedName(t.table));
}

std::string GpkgMutator::mutatedCopy(std::string& what) {
  const std::string copy = editableCopy(source_);
  what.clear();
  for (int k = 0, n = 1 + below(3); k < n; ++k) {
    std::string one = change(copy);
    if (one.size() > 300) one = one.substr(0, 300) + "...";  // a long hostile text
    what += (k ? "; " : "") + one;
  }
  return copy;
}

std::string GpkgMutator::change(const std::string& copy) {
  const int pick = below(100);
  if (pick < 50) return changeField(copy);
  if (pick < 60) return changeGeometry(copy);
  if (pick < 70) return dropRows(copy);
  if (pick < 77) return dropSchema(copy);
  if (pick < 87) return changeMetadata(copy);
  if (pick < 93) return changeFeatureCount(copy);
  return damageBytes(copy);
}

std::string GpkgMutator::changeField(const std::string& copy) {
  const TableColumns& t = tinlodTables()[below(static_cast<int>(tinlodTables().size()))];
  const std::string column = t.columns[below(static_cast<int>(t.columns.size()))];
  const std::string value = hostileValue(t.table, column);
  // Mostly one row; sometimes many, as a systematic error would.
  const std::string where =
      below(5) ? "fid = " + std::to_string(anyRow(t.table)) : "fid % 7 = " + std::to_string(below(7));
  const std::string statement =
      "UPDATE " + quotedName(t.table) + " SET " + quotedName(column) + " = " + value + " WHERE " + where;
  return statement + sql(copy, statement);
}

std::string GpkgMutator::changeGeometry(const std::string& copy) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // 1e11: accepted (within 1e12), but beyond int's range as a DEM row or column.
  const double hostile[] = {nan, inf, -inf, 1e300, -1e300, 1e13, 1e11, -1e11, 0, 400500, 5200500, 1e-300};
  auto any = [&] { return hostile[below(12)]; };
  const std::string geometries[] = {pointBlobLiteral(any(), any(), any(), 32632), "NULL", "X'00'", "X'47500001'",
                                    "substr(geom, 1, " + std::to_string(below(40)) + ")",
                                    "(SELECT geom FROM triangles WHERE fid = " +
                                        std::to_string(anyRow("triangles")) + ")",
                                    "randomblob(" + std::to_string(below(64)) + ")"};
  const std::string table = below(4) ? "vertices" : below(2) ? "groups" : "triangles";
  const std::string statement = "UPDATE " + table + " SET geom = " + geometries[below(7)] +
                                " WHERE fid = " + std::to_string(anyRow(table));
  return statement + sql(copy, statement);
}

std::string GpkgMutator::dropRows(const std::string& copy) {
  const std::string table = tinlodTables()[below(static_cast<int>(tinlodTables().size()))].table;
  const int how = below(10);
  const std::string where = how < 7   ? "fid = " + std::to_string(anyRow(table))
                            : how < 9 ? "fid % " + std::to_string(2 + below(20)) + " = 0"
                                      : "1";
  const std::string statement = "DELETE FROM " + table + " WHERE " + where;
  return statement + sql(copy, statement);
}

std::string GpkgMutator::dropSchema(const std::string& copy) {
  const TableColumns& t = tinlodTables()[below(static_cast<int>(tinlodTables().size()))];
  std::string statement;
  switch (below(5)) {
    case 0:  // a careless DROP: GDAL still finds the table in gpkg_contents
      statement = "DROP TABLE " + quotedName(t.table);
      break;
    case 1:  // as GDAL would drop it
      statement = "DROP TABLE " + quotedName(t.table) + "; DELETE FROM gpkg_contents WHERE table_name = '" + t.table +
                  "'; DELETE FROM gpkg_geometry_columns WHERE table_name = '" + t.table + "'";
      break;
    case 2:  // SQLite refuses columns that an index or view uses
      statement = "ALTER TABLE " + quotedName(t.table) + " DROP COLUMN " +
                  quotedName(t.columns[1 + below(static_cast<int>(t.columns.size()) - 1)]);
      break;
    case 3:
      statement = "UPDATE gpkg_spatial_ref_sys SET definition = 'not a CRS' WHERE srs_id = 32632";
      break;
    default:
      statement = below(2) ? "DELETE FROM gpkg_metadata"
                           : "UPDATE gpkg_metadata SET metadata = '<GDALMultiDomainMetadata><Metadata>'";
  }
  return statement + sql(copy, statement);
}

std::string GpkgMutator::changeMetadata(const std::string& copy) {
  const char* const keys[] = {"KIND", "METHOD", "DELETE_PCT", "STOP_PCT", "BAND", "MAX_ERROR"};
  const std::string key = keys[below(6)];
  const std::string value = below(3) ? hostileText() : key == "KIND" ? (below(2) ? "tin" : "lod") : "";
  return "TINLOD_" + key + " = '" + value + "'" + (setTinlodItem(copy, key, value) ? "" : " (no such item)");
}

std::string GpkgMutator::changeFeatureCount(const std::string& copy) {
  const char* const counts[] = {"-1", "0", "NULL", "9000000000000000000", "2147483648", "1"};
  const std::string table = tinlodTables()[below(static_cast<int>(tinlodTables().size()))].table;
  const std::string statement = "UPDATE gpkg_ogr_contents SET feature_count = " + std::string(counts[below(6)]) +
                                " WHERE table_name = '" + table + "'";
  return statement + sql(copy, statement);
}

std::string GpkgMutator::damageBytes(const std::string& copy) {
  const auto size = static_cast<std::uintmax_t>(fs::file_size(copy));
  if (below(2)) {
    const std::uintmax_t keep = random_() % size;
    fs::resize_file(copy, keep);
    return "truncated to " + std::to_string(keep) + " of " + std::to_string(size) + " bytes";
  }
  std::fstream file(copy, std::ios::in | std::ios::out | std::ios::binary);
  const int n = 1 + below(20);
  for (int k = 0; k < n; ++k) {
    file.seekp(static_cast<std::streamoff>(random_() % size));
    file.put(static_cast<char>(random_()));
  }
  return std::to_string(n) + " random bytes overwritten";
}

std::string GpkgMutator::hostileValue(const std::string& table, const std::string& column) {
  const long long n = rows_[table], most = std::max({rows_["vertices"], rows_["triangles"], rows_["groups"]});
  const char* const extremes[] = {"2147483647", "2147483648",   "-2147483649", "9223372036854775807",
                                  "-9223372036854775808", "1e308", "-1e308", "9e999", "-9e999", "0.5", "-0.0"};
  const TableColumns& t = *std::find_if(tinlodTables().begin(), tinlodTables().end(),
                                        [&](const TableColumns& c) { return table == c.table; });
  switch (below(12)) {
    case 0: return "NULL";
    case 1: return std::to_string(below(4) - 1);  // -1 to 2
    case 2: return std::to_string(n + below(3) - 1);
    case 3: return std::to_string(static_cast<long long>(random_() % static_cast<std::uint64_t>(most + 7)) - 3);
    case 4: return extremes[below(11)];
    case 5: return "'" + hostileText() + "'";
    case 6:  // another row's
      return "(SELECT " + quotedName(column) + " FROM " + table + " WHERE fid = " + std::to_string(anyRow(table)) + ")";
    case 7:  // another column of the row
      return quotedName(t.columns[below(static_cast<int>(t.columns.size()))]);
    default:  // off by one or two
      return quotedName(column) + (below(2) ? " + " : " - ") + std::to_string(1 + below(2));
  }
}

std::string GpkgMutator::hostileText() {
  const char* const texts[] = {"", "x", "-1", "0", "1", "100", "1e999", "nan", "inf", "99999999999999999999",
                               "none", "5x", " 5", "hierarchy", "volume", "1,5", "'; DROP TABLE triangles; --"};
  if (below(20) == 0) return std::string(100000, 'a');
  return texts[below(17)];
}

long long GpkgMutator::anyRow(const std::string& table) {
  const long long n = std::max(1LL, rows_[table]);
  return 1 + static_cast<long long>(random_() % static_cast<std::uint64_t>(n));
}

std::string GpkgMutator::sql(const std::string& copy, const std::string& statement) {
  const std::string refused = runSql(copy, statement);
  return refused.empty() ? "" : " (SQLite refused: " + refused + ")";
}

}  // namespace tinlod::test
