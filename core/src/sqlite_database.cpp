// SPDX-License-Identifier: GPL-3.0-or-later
#include "sqlite_database.h"

#include <utility>

#include "tinlod/error.h"

namespace tinlod {

std::string sqlName(const std::string& name) {
  std::string out = "\"";
  for (char c : name) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

SqliteDatabase::SqliteDatabase(const std::string& path, std::string userName) : userName_(std::move(userName)) {
  // One thread uses the connection: SQLite's own locking of it would only cost time.
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw Error("cannot open GeoPackage '" + userName_ + "' to write it: " + message);
  }
  try {
    // The file is a staged copy that is thrown away on any failure, and moved into place
    // only when complete: a rollback journal and syncs would buy nothing.
    execute("PRAGMA journal_mode = OFF");
    execute("PRAGMA synchronous = OFF");
    execute("PRAGMA cache_size = -8192");  // 8 MiB: rows and index nodes are appended in key order
    // The R-trees are loaded into the rtree module's own tables, which a defensive build
    // of SQLite would make read-only.
    sqlite3_db_config(db_, SQLITE_DBCONFIG_DEFENSIVE, 0, nullptr);
  } catch (...) {
    sqlite3_close_v2(db_);
    db_ = nullptr;
    throw;
  }
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close_v2(db_); }

void SqliteDatabase::fail(const std::string& what) const {
  const int code = sqlite3_errcode(db_);
  std::string message = sqlite3_errmsg(db_);
  if (code == SQLITE_FULL) message = "the disk is full";
  throw Error("cannot write GeoPackage '" + userName_ + "' (" + what + "): " + message);
}

void SqliteDatabase::execute(const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    sqlite3_free(message);
    fail(sql.substr(0, sql.find(' ', 20)));
  }
}

SqliteStatement SqliteDatabase::prepare(const std::string& sql) { return SqliteStatement(*this, sql); }

std::int64_t SqliteDatabase::integer(const std::string& sql, std::int64_t otherwise) {
  SqliteStatement statement(*this, sql);
  return statement.step() ? statement.integerColumn(0) : otherwise;
}

bool SqliteDatabase::hasSchemaObject(const std::string& name) {
  SqliteStatement statement(*this, "SELECT 1 FROM sqlite_master WHERE name = ?");
  statement.bindText(1, name);
  return statement.step();
}

SqliteStatement::SqliteStatement(SqliteDatabase& db, const std::string& sql) : db_(&db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) db.fail("preparing " + sql);
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

SqliteStatement::SqliteStatement(SqliteStatement&& other) noexcept
    : db_(other.db_), stmt_(std::exchange(other.stmt_, nullptr)) {}

void SqliteStatement::bindBlob(int parameter, const void* bytes, std::size_t size) {
  // An empty blob is a blob, not null (SQLite takes a null pointer for null).
  check(size ? sqlite3_bind_blob64(stmt_, parameter, bytes, size, SQLITE_STATIC) : sqlite3_bind_zeroblob(stmt_, parameter, 0));
}

bool SqliteStatement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  sqlite3_reset(stmt_);
  if (rc != SQLITE_DONE) db_->fail("writing a row");
  return false;
}

}  // namespace tinlod
