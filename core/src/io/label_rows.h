#pragma once
// Shared by the LabelStore's source files: labels to and from rows and JSON,
// validation, filters as SQL, and the journal rows every edit writes.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sqlite_statement.h"
#include "tactile/io/label.h"
#include "tactile/io/label_store.h"

namespace tactile::label_rows {

// The labels table's columns in the order read_label() expects.
inline constexpr const char* kColumns =
    "id, recording, t0, t1, region, class, annotator, source, confidence, note, created, modified";

// The current time as ISO 8601 UTC with milliseconds, e.g. "2024-05-01T12:00:00.250Z".
std::string now_utc();

// "path label 17", the `where` of an error about one label.
std::string where_label(const std::string& path, int64_t id);

// Throws tactile::Error(where, ...) naming the first invalid field.
void validate(const Label& label, const std::string& where);

// Reads the kColumns of the current row.
Label read_label(const sqlite::Statement& statement, const std::string& path);

// The export's JSON object for one label, and back.
nlohmann::json to_json(const Label& label);
Label from_json(const nlohmann::json& object, const std::string& where);

// A filter as " WHERE ..." (or "") with its parameters bound by bind().
struct FilterClause {
  std::string sql;
  std::vector<std::variant<std::string, double>> parameters;  // in placeholder order, from 1
  void bind(sqlite::Statement& statement) const;
};
FilterClause filter_clause(const LabelFilter& filter);

// Row access inside an open transaction.
std::optional<Label> load(sqlite3* database, const std::string& path, int64_t id);
// Inserts the label with its own id, or replaces the row with that id; id 0
// inserts a new row (its id is sqlite3_last_insert_rowid).
void store(sqlite3* database, const std::string& path, const Label& label);
void erase(sqlite3* database, const std::string& path, int64_t id);

//---- Journal

// A label's state for the journal: its JSON, or "" when it does not exist.
std::string state_json(const std::optional<Label>& label);
std::optional<Label> state_from_json(const std::string& text, const std::string& where);

// The number shared by the journal rows of one call.
int64_t next_batch(sqlite3* database, const std::string& path);
// `time` "" = now.
void write_journal(sqlite3* database, const std::string& path, int64_t batch,
                   const std::string& annotator, const std::string& action, int64_t label_id,
                   const std::string& before_json, const std::string& after_json,
                   const std::string& time = {});
// A new edit makes the undone edits unrecoverable by redo.
void clear_redo_chain(sqlite3* database, const std::string& path);

}  // namespace tactile::label_rows
