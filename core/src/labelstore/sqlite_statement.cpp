#include "sqlite_statement.h"

#include <utility>

#include "tactile/error.h"

namespace tactile::sqlite {

void fail(sqlite3* database, const std::string& where, const std::string& what, int code) {
  // sqlite3_errmsg describes the connection's last error, which is the one we
  // are reporting; sqlite3_errstr is the fallback without a connection.
  const char* detail = database != nullptr ? sqlite3_errmsg(database) : sqlite3_errstr(code);
  std::string message = what + ": " + (detail != nullptr ? detail : sqlite3_errstr(code));
  if ((code & 0xff) == SQLITE_NOTADB) message = "not a SQLite database (" + message + ")";
  throw Error(where, message);
}

void execute(sqlite3* database, const std::string& where, const char* sql) {
  const int code = sqlite3_exec(database, sql, nullptr, nullptr, nullptr);
  if (code != SQLITE_OK) fail(database, where, std::string("cannot run ") + sql, code);
}

//---- Statement

Statement::Statement(sqlite3* database, std::string where, const std::string& sql)
    : database_(database), where_(std::move(where)) {
  const int code = sqlite3_prepare_v2(database_, sql.c_str(), static_cast<int>(sql.size()),
                                      &statement_, nullptr);
  if (code != SQLITE_OK) fail(database_, where_, "cannot prepare query", code);
}

Statement::~Statement() { sqlite3_finalize(statement_); }

Statement& Statement::bind(int index, int64_t value) {
  const int code = sqlite3_bind_int64(statement_, index, value);
  if (code != SQLITE_OK) fail(database_, where_, "cannot bind parameter", code);
  return *this;
}

Statement& Statement::bind(int index, double value) {
  const int code = sqlite3_bind_double(statement_, index, value);
  if (code != SQLITE_OK) fail(database_, where_, "cannot bind parameter", code);
  return *this;
}

Statement& Statement::bind(int index, const std::string& value) {
  const int code = sqlite3_bind_text(statement_, index, value.data(),
                                     static_cast<int>(value.size()), SQLITE_TRANSIENT);
  if (code != SQLITE_OK) fail(database_, where_, "cannot bind parameter", code);
  return *this;
}

Statement& Statement::bind_null(int index) {
  const int code = sqlite3_bind_null(statement_, index);
  if (code != SQLITE_OK) fail(database_, where_, "cannot bind parameter", code);
  return *this;
}

bool Statement::step() {
  const int code = sqlite3_step(statement_);
  if (code == SQLITE_ROW) return true;
  if (code == SQLITE_DONE) return false;
  fail(database_, where_, std::string("query failed (") + sqlite3_sql(statement_) + ")", code);
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

int64_t Statement::integer(int column) const { return sqlite3_column_int64(statement_, column); }

double Statement::real(int column) const { return sqlite3_column_double(statement_, column); }

std::string Statement::text(int column) const {
  const auto* bytes = reinterpret_cast<const char*>(sqlite3_column_text(statement_, column));
  const int size = sqlite3_column_bytes(statement_, column);
  return bytes != nullptr ? std::string(bytes, static_cast<size_t>(size)) : std::string();
}

bool Statement::is_null(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

//---- Transaction

Transaction::Transaction(sqlite3* database, std::string where)
    : database_(database), where_(std::move(where)) {
  execute(database_, where_, "BEGIN IMMEDIATE");
  open_ = true;
}

Transaction::~Transaction() {
  // A failed statement may already have ended the transaction; rolling back
  // then is harmless, and a destructor must not throw.
  if (open_ && !sqlite3_get_autocommit(database_))
    sqlite3_exec(database_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  execute(database_, where_, "COMMIT");
  open_ = false;
}

}  // namespace tactile::sqlite
