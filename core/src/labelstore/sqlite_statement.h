#pragma once
// A thin RAII layer over the SQLite C API for the LabelStore: prepared
// statements and BEGIN IMMEDIATE transactions. Every failure becomes a
// tactile::Error naming the database (and label) it happened on.

#include <sqlite3.h>

#include <cstdint>
#include <string>

namespace tactile::sqlite {

// Throws tactile::Error(where, what + ": " + SQLite's message for `code`).
[[noreturn]] void fail(sqlite3* database, const std::string& where, const std::string& what,
                       int code);

// Runs statements that return no rows.
void execute(sqlite3* database, const std::string& where, const char* sql);

class Statement {
 public:
  Statement(sqlite3* database, std::string where, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Parameters are numbered from 1, as in SQLite.
  Statement& bind(int index, int64_t value);
  Statement& bind(int index, double value);
  Statement& bind(int index, const std::string& value);
  Statement& bind_null(int index);

  // True while a row is available; false when done.
  bool step();
  // Steps to the end, for statements that return nothing.
  void run();
  // Rewinds to run again with new bindings.
  void reset();

  // Columns are numbered from 0.
  int64_t integer(int column) const;
  double real(int column) const;
  std::string text(int column) const;
  bool is_null(int column) const;

 private:
  sqlite3* database_;
  sqlite3_stmt* statement_ = nullptr;
  std::string where_;
};

// BEGIN IMMEDIATE takes the write lock up front, so two writers queue on the
// busy timeout instead of one failing when it upgrades a read lock. Rolls back
// unless commit() was reached.
class Transaction {
 public:
  Transaction(sqlite3* database, std::string where);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

 private:
  sqlite3* database_;
  std::string where_;
  bool open_ = false;
};

}  // namespace tactile::sqlite
