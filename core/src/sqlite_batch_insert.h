// SPDX-License-Identifier: GPL-3.0-or-later
// Private: rows inserted into one table many at a time, one multi-row INSERT per batch.
// A GeoPackage feature table is AUTOINCREMENT by the spec, and SQLite reads and writes
// its sqlite_sequence row once per statement: one statement per row paid that, and the
// statement's own start and end, for every triangle.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "sqlite_database.h"

namespace tinlod {

class SqliteBatchInsert {
 public:
  SqliteBatchInsert(SqliteDatabase& db, std::string table, std::vector<std::string> columns, int rowsPerStatement = 64);

  // Values of the current row, by column index; a column left unset is null.
  void set(int column, std::int64_t value) {
    Cell& c = cell(column);
    c.type = Type::Integer, c.integer = value;
  }
  void setReal(int column, double value) {
    Cell& c = cell(column);
    c.type = Type::Real, c.real = value;
  }
  void setNull(int column) { cell(column).type = Type::Null; }
  void setBlob(int column, const unsigned char* bytes, std::size_t size);
  // Ends the current row; a full batch is written.
  void endRow();
  // Writes the rows still held (call before anything reads the table).
  void flush();

 private:
  enum class Type { Null, Integer, Real, Blob };
  struct Cell {
    Type type = Type::Null;
    std::int64_t integer = 0;
    double real = 0;
    std::vector<unsigned char> blob;
  };
  Cell& cell(int column) { return cells_[rows_ * columns_.size() + column]; }
  SqliteStatement& statementFor(int rows);
  void writeRows(int rows);
  SqliteDatabase& db_;
  std::string table_;
  std::vector<std::string> columns_;
  int batch_;
  int rows_ = 0;
  std::vector<Cell> cells_;
  std::map<int, SqliteStatement> statements_;
};

}  // namespace tinlod
