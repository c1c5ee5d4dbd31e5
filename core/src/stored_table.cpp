// SPDX-License-Identifier: GPL-3.0-or-later
#include "stored_table.h"

#include <cpl_error.h>

#include <algorithm>

#include "text_and_paths.h"
#include "tinlod/error.h"

namespace tinlod {

void throwDamaged(const std::string& path, const std::string& what) {
  throw Error("'" + path + "' is damaged: " + what);
}

StoredTable::StoredTable(const std::string& path, OGRLayer& layer)
    : path_(path), name_(layer.GetName()), layer_(layer) {
  CPLErrorReset();
}

int StoredTable::column(const char* name) const {
  const int i = optionalColumn(name);
  if (i < 0) damaged("has no column " + std::string(name));
  return i;
}

int StoredTable::optionalColumn(const char* name) const { return layer_.GetLayerDefn()->GetFieldIndex(name); }

void StoredTable::checkFullyRead() const {
  if (CPLGetLastErrorType() >= CE_Failure)
    throwDamaged(path_, "its " + name_ + " table cannot be read to the end (" + CPLGetLastErrorMsg() + ")");
}

void StoredTable::damaged(const std::string& what) const { throwDamaged(path_, "its " + name_ + " table " + what); }

std::vector<std::size_t> StoredTable::rowsById(const std::vector<std::int64_t>& ids,
                                               const std::vector<GIntBig>& fids) const {
  constexpr std::size_t kUnseen = std::numeric_limits<std::size_t>::max();
  const std::size_t n = ids.size();
  std::vector<std::size_t> rows(n, kUnseen);
  for (std::size_t i = 0; i < n; ++i) {
    if (ids[i] < 1 || static_cast<std::uint64_t>(ids[i]) > n)
      throwDamaged(path_, name_ + " row " + std::to_string(fids[i]) + " has id " + std::to_string(ids[i]) +
                              " but the table's " + std::to_string(n) + " rows should have ids 1 to " +
                              std::to_string(n));
    std::size_t& at = rows[static_cast<std::size_t>(ids[i] - 1)];
    if (at != kUnseen)
      throwDamaged(path_, name_ + " rows " + std::to_string(fids[at]) + " and " + std::to_string(fids[i]) +
                              " both have id " + std::to_string(ids[i]));
    at = i;
  }
  return rows;
}

std::size_t StoredTable::plausibleRows(std::uintmax_t fileBytes) const {
  constexpr std::uintmax_t kLeastBytesPerRow = 16;  // an id and a few numbers take more
  const GIntBig stated = layer_.GetFeatureCount();
  if (stated <= 0) return 0;
  return static_cast<std::size_t>(
      std::min<std::uintmax_t>(static_cast<std::uintmax_t>(stated), fileBytes / kLeastBytesPerRow));
}

void StoredRow::damaged(const std::string& what) const {
  throwDamaged(table_.path(), table_.name() + " row " + std::to_string(fid()) + " " + what);
}

std::string StoredRow::columnName(int column) const { return f_.GetFieldDefnRef(column)->GetNameRef(); }

void StoredRow::missing(int column) const { damaged("has no " + columnName(column) + " (NULL)"); }

void StoredRow::outOfRange(int column, std::int64_t v, std::int64_t lo, std::int64_t hi, const char* range) const {
  const std::string is = "has " + columnName(column) + " " + std::to_string(v);
  if (hi < lo) damaged(is + " but there are no " + range);
  damaged(is + " but the " + range + " are " + std::to_string(lo) + " to " + std::to_string(hi));
}

void StoredRow::notNonNegative(int column, double v) const {
  damaged("has " + columnName(column) + " " + formatNumber(v) + ": it must be a number, 0 or more");
}

}  // namespace tinlod
