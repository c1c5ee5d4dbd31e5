// SPDX-License-Identifier: GPL-3.0-or-later
#include "sqlite_batch_insert.h"

#include <utility>

namespace tinlod {

SqliteBatchInsert::SqliteBatchInsert(SqliteDatabase& db, std::string table, std::vector<std::string> columns,
                                     int rowsPerStatement)
    : db_(db), table_(std::move(table)), columns_(std::move(columns)), batch_(rowsPerStatement),
      cells_(columns_.size() * static_cast<std::size_t>(rowsPerStatement)) {}

void SqliteBatchInsert::setBlob(int column, const unsigned char* bytes, std::size_t size) {
  Cell& c = cell(column);
  c.type = Type::Blob;
  c.blob.assign(bytes, bytes + size);  // the cell keeps its buffer from row to row
}

void SqliteBatchInsert::endRow() {
  if (++rows_ == batch_) writeRows(rows_);
}

void SqliteBatchInsert::flush() {
  if (rows_ > 0) writeRows(rows_);
}

SqliteStatement& SqliteBatchInsert::statementFor(int rows) {
  auto found = statements_.find(rows);
  if (found != statements_.end()) return found->second;
  std::string sql = "INSERT INTO " + sqlName(table_) + " (";
  for (std::size_t c = 0; c < columns_.size(); ++c) sql += (c ? ", " : "") + sqlName(columns_[c]);
  sql += ") VALUES ";
  for (int r = 0; r < rows; ++r) {
    sql += r ? ", (" : "(";
    for (std::size_t c = 0; c < columns_.size(); ++c) sql += c ? ", ?" : "?";
    sql += ")";
  }
  return statements_.emplace(rows, db_.prepare(sql)).first->second;
}

void SqliteBatchInsert::writeRows(int rows) {
  SqliteStatement& statement = statementFor(rows);
  const std::size_t n = static_cast<std::size_t>(rows) * columns_.size();
  for (std::size_t k = 0; k < n; ++k) {
    Cell& c = cells_[k];
    const int parameter = static_cast<int>(k) + 1;
    switch (c.type) {
      case Type::Null: statement.bindNull(parameter); break;
      case Type::Integer: statement.bind(parameter, c.integer); break;
      case Type::Real: statement.bindReal(parameter, c.real); break;
      case Type::Blob: statement.bindBlob(parameter, c.blob.data(), c.blob.size()); break;
    }
    c.type = Type::Null;  // the next rows start unset
  }
  statement.step();
  rows_ = 0;
}

}  // namespace tinlod
