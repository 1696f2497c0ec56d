#pragma once
// Internal to the LabelStore: a checksum of every field of a row, so that a value
// changed on disk (a bad sector, a half-copied file) is named, with its row and
// field, instead of being read as data. SQLite checks its pages, not the values in
// its rows.
//
// A row's checksum is one CRC-32 (8 hex digits) per field, in field order. Each
// CRC covers the table, the row id, the field name and the value, so a value moved
// to another row or field does not match either.

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace tactile::row_checksum {

// A field as read from or written to SQLite. NULL is std::monostate.
using Value = std::variant<std::monostate, int64_t, double, std::string>;

struct Field {
  const char* name;
  Value value;
};

std::string compute(const std::string& table, int64_t row, const std::vector<Field>& fields);

// Names of the fields whose value no longer matches `stored` (every field when
// `stored` itself is malformed); empty when the row is intact.
std::vector<std::string> mismatches(const std::string& table, int64_t row,
                                    const std::vector<Field>& fields, const std::string& stored);

// A 64-bit hash of a row (its id and checksum): rows are summed per scope into a
// digest, so a row lost or added on disk is noticed by whoever reads the scope.
uint64_t row_hash(int64_t row, const std::string& checksum);

}  // namespace tactile::row_checksum
