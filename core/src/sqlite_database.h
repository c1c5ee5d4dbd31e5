// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a SQLite connection and its prepared statements, for writing a staged
// GeoPackage at SQLite's own speed. SQLite stays in the GeoPackage I/O files.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <functional>
#include <string>

namespace tinlod {

class SqliteStatement;

// A table or column name as SQL writes one: in double quotes, its own quotes doubled.
std::string sqlName(const std::string& name);

class SqliteDatabase {
 public:
  // `userName` words errors in the user's terms (the staged file's path means nothing to them).
  SqliteDatabase(const std::string& path, std::string userName);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  void execute(const std::string& sql);
  SqliteStatement prepare(const std::string& sql);
  // The first column of the first row of `sql`, or `otherwise` when there is no row.
  std::int64_t integer(const std::string& sql, std::int64_t otherwise = 0);
  // A table, view, index or trigger of that name.
  bool hasSchemaObject(const std::string& name);
  [[noreturn]] void fail(const std::string& what) const;
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
  std::string userName_;
};

// One prepared statement, run many times: bind, then step() runs it and resets it.
class SqliteStatement {
 public:
  SqliteStatement(SqliteDatabase& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  SqliteStatement& operator=(SqliteStatement&&) = delete;

  // Parameters count from 1, as in SQLite.
  void bind(int parameter, std::int64_t value) { check(sqlite3_bind_int64(stmt_, parameter, value)); }
  void bindReal(int parameter, double value) { check(sqlite3_bind_double(stmt_, parameter, value)); }
  void bindNull(int parameter) { check(sqlite3_bind_null(stmt_, parameter)); }
  void bindText(int parameter, const std::string& text) {
    check(sqlite3_bind_text(stmt_, parameter, text.c_str(), int(text.size()), SQLITE_TRANSIENT));
  }
  // SQLITE_STATIC: the bytes must live until step() returns.
  void bindBlob(int parameter, const void* bytes, std::size_t size);
  // Runs the statement; true while it yields rows (then read with integerColumn).
  bool step();
  std::int64_t integerColumn(int column) const { return sqlite3_column_int64(stmt_, column); }
  std::string textColumn(int column) const {
    const unsigned char* text = sqlite3_column_text(stmt_, column);
    return text ? std::string(reinterpret_cast<const char*>(text), sqlite3_column_bytes(stmt_, column)) : std::string();
  }
  void reset() { sqlite3_reset(stmt_); }

 private:
  void check(int rc) {
    if (rc != SQLITE_OK) db_->fail("binding a value");
  }
  SqliteDatabase* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace tinlod
