// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a table of a GeoPackage tinlod wrote, read as data that may have been damaged
// or crafted. Nothing read is trusted before it is checked, and every refusal names the
// file, the table and the row, so that a user can look at it with any SQLite tool.
#pragma once

#include <ogrsf_frmts.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace tinlod {

// Throws Error "'path' is damaged: <what>".
[[noreturn]] void throwDamaged(const std::string& path, const std::string& what);

class StoredTable {
 public:
  // Clears GDAL's last error, so that checkFullyRead() sees only this table's.
  StoredTable(const std::string& path, OGRLayer& layer);

  // The index of a column the table must have; throws when the file lacks it.
  int column(const char* name) const;
  // -1 when the file lacks it (files written by older versions).
  int optionalColumn(const char* name) const;
  // GDAL ends a loop over a malformed or truncated file early, with an error it only
  // logs: without this check the rows read so far would pass for the whole table.
  void checkFullyRead() const;
  [[noreturn]] void damaged(const std::string& what) const;
  // Where the row of each id was read, ids[i] and fids[i] being the i-th row's: the ids
  // must be 1 to n, each once, n the rows read (the count a file states is not trusted).
  std::vector<std::size_t> rowsById(const std::vector<std::int64_t>& ids, const std::vector<GIntBig>& fids) const;
  // Rows a vector may reserve: what the file says, but no more than its size could hold.
  std::size_t plausibleRows(std::uintmax_t fileBytes) const;

  OGRLayer& layer() const { return layer_; }
  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }

 private:
  std::string path_, name_;
  OGRLayer& layer_;
};

// One row of a StoredTable. The checks are inline and cheap: a hierarchy has millions of
// rows, and only a refusal builds a message.
class StoredRow {
 public:
  StoredRow(const StoredTable& table, const OGRFeature& f) : table_(table), f_(f) {}

  // An integer column's value, which must be set and within [lo, hi]; `range` says what
  // the bounds are ("levels", "vertex ids") in the message.
  std::int64_t integer(int column, std::int64_t lo, std::int64_t hi, const char* range) const {
    if (!f_.IsFieldSetAndNotNull(column)) missing(column);
    const std::int64_t v = f_.GetFieldAsInteger64(column);
    if (v < lo || v > hi) outOfRange(column, v, lo, hi, range);
    return v;
  }
  // The same for a column where NULL means none: `none` then.
  std::int64_t optionalInteger(int column, std::int64_t lo, std::int64_t hi, const char* range,
                               std::int64_t none) const {
    return f_.IsFieldSetAndNotNull(column) ? integer(column, lo, hi, range) : none;
  }
  // A real column's value: a number (not NaN), 0 or more; infinity is allowed (an error
  // bound that was never met). NULL reads as 0.
  double nonNegative(int column) const {
    const double v = f_.IsFieldSetAndNotNull(column) ? f_.GetFieldAsDouble(column) : 0.0;
    if (!(v >= 0)) notNonNegative(column, v);
    return v;
  }
  GIntBig fid() const { return f_.GetFID(); }
  // "<table> row <fid> <what>".
  [[noreturn]] void damaged(const std::string& what) const;

 private:
  [[noreturn]] void missing(int column) const;
  [[noreturn]] void outOfRange(int column, std::int64_t v, std::int64_t lo, std::int64_t hi, const char* range) const;
  [[noreturn]] void notNonNegative(int column, double v) const;
  std::string columnName(int column) const;

  const StoredTable& table_;
  const OGRFeature& f_;
};

// `values` in id order, from the read order and rowsById(); tinlod writes rows in id
// order, so usually nothing moves.
template <class T>
void orderById(std::vector<T>& values, const std::vector<std::size_t>& rows) {
  bool inOrder = true;
  for (std::size_t i = 0; i < rows.size() && inOrder; ++i) inOrder = rows[i] == i;
  if (inOrder) return;
  std::vector<T> out;
  out.reserve(rows.size());
  for (std::size_t r : rows) out.push_back(std::move(values[r]));
  values.swap(out);
}

constexpr std::int64_t kMaxStoredCount = std::numeric_limits<std::int64_t>::max();

}  // namespace tinlod
