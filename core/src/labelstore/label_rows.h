#pragma once
// Shared by the LabelStore's source files: labels to and from rows and JSON, validation,
// filters as SQL (label_rows.cpp, with the schema upgrades), the digests (label_digests.cpp),
// and the journal rows every edit writes and the rejections (label_journal.cpp).

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "row_checksum.h"
#include "sqlite_statement.h"
#include "tactile/error.h"
#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"

namespace tactile::label_rows {

// The labels table's columns in the order read_label() expects (schema 2: with the
// row's checksum, row_checksum.h; schema 4: with the revision).
inline constexpr const char* kColumns =
    "id, recording, t0, t1, region, class, annotator, source, confidence, note, created, "
    "modified, checksum, revision";

// Class names a label read back may carry: the skins' vocabularies and every class
// ever written to the store (a damaged name is none of them).
using KnownClasses = std::set<std::string>;
KnownClasses known_classes(sqlite3* database, const std::string& path);

// A row read and checked: its label, or what is wrong with it.
struct CheckedLabel {
  std::optional<Label> label;
  std::optional<StoreProblem> problem;
  int64_t id = 0;
  std::string recording, checksum;  // as stored, for the digests
};

// A problem of one row (`field` "" when the row is damaged as a whole).
StoreProblem row_problem(const char* table, int64_t row, std::string field, std::string what);
// The first field that disagrees with the row's stored checksum, as a problem; none when all
// agree.
std::optional<StoreProblem> checksum_problem(const char* table, int64_t row,
                                             const std::vector<row_checksum::Field>& fields,
                                             const std::string& stored);

// The current time as ISO 8601 UTC with milliseconds, e.g. "2024-05-01T12:00:00.250Z".
std::string now_utc();

// "path label 17", the `where` of an error about one label.
std::string where_label(const std::string& path, int64_t id);

// Throws tactile::Error(where, ...) naming the first invalid field.
void validate(const Label& label, const std::string& where);
// True for the ISO 8601 UTC times the store writes ("2024-05-01T12:00:00.250Z",
// fraction optional).
bool is_iso_time(const std::string& text);

// Reads the kColumns of the current row and checks its checksum and values.
CheckedLabel read_label(const sqlite::Statement& statement, const KnownClasses& classes);
// The label, or tactile::Error naming the store, the row and the field: a damaged
// row is never overwritten.
Label require(const CheckedLabel& row, const std::string& path);
// The problem as an error.
Error problem_error(const StoreProblem& problem, const std::string& path);

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

// Row access inside an open transaction. load() throws for a damaged row.
std::optional<Label> load(sqlite3* database, const std::string& path, int64_t id);
// Inserts the label with its own id, or replaces the row with that id; id 0
// inserts a new row. Returns the id. Writes the row's checksum, keeps its
// recording's digest and registers its class.
int64_t store(sqlite3* database, const std::string& path, const Label& label);
void erase(sqlite3* database, const std::string& path, int64_t id);

//---- Digests: per scope ("labels:RECORDING", "journal") the number of rows and the
// sum of their row hashes, kept by every write, compared by every read of a whole scope.

inline std::string label_scope(const std::string& recording) { return "labels:" + recording; }
inline constexpr const char* kJournalScope = "journal";
void adjust_digest(sqlite3* database, const std::string& path, const std::string& scope,
                   int64_t rows, uint64_t sum);
struct Digest {
  int64_t rows = 0;
  uint64_t sum = 0;
};
// Every digest whose scope starts with `prefix`, checked; damaged ones go to `problems`.
std::map<std::string, Digest> read_digests(sqlite3* database, const std::string& prefix,
                                           std::vector<StoreProblem>& problems);
// Compares what a read of whole scopes found with the stored digests; a scope in
// `stored` that was not found at all is lost rows too when `all_scopes`.
void compare_digests(const std::map<std::string, Digest>& found,
                     const std::map<std::string, Digest>& stored, bool all_scopes,
                     std::vector<StoreProblem>& problems);

//---- Journal

// A journal row's checksum written and added to the journal's digest (label_journal.cpp).
void seal_journal_row(sqlite3* database, const std::string& path, const JournalEntry& entry,
                      std::optional<int64_t> undone_by);
// The kJournalColumns of the statement's current row as stored.
JournalEntry journal_from_row(const sqlite::Statement& statement,
                              std::optional<int64_t>& undone_by);
// A label's state for the journal: its JSON with its revision, or "" when it does not exist.
std::string state_json(const std::optional<Label>& label);
// The same without the revision (what an undo compares: the revision moves on at every
// undo and redo, the values come back).
std::string content_json(const std::optional<Label>& label);
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

// Rejections (suggestions an annotator rejected), inside the caller's transaction: the fields
// their checksum covers; one remembered for `suggestion`; and the newest one of `suggestion` by
// `annotator` forgotten again (an undone reject).
std::vector<row_checksum::Field> rejection_fields(const Rejection& rejection);
void remember_rejection(sqlite3* database, const std::string& path, const Label& suggestion,
                        const std::string& annotator);
void forget_rejection(sqlite3* database, const std::string& path, const Label& suggestion,
                      const std::string& annotator);

// The journal's columns in the order read_journal() expects.
inline constexpr const char* kJournalColumns =
    "sequence, batch, time, annotator, action, label_id, before_json, after_json, undone, "
    "undone_by, checksum";
struct CheckedJournal {
  std::optional<JournalEntry> entry;
  std::optional<int64_t> undone_by;
  std::optional<StoreProblem> problem;
  int64_t sequence = 0;
  std::string checksum;
};
CheckedJournal read_journal(const sqlite::Statement& statement);
// Marks a journal row undone (by the undo batch) or not; refuses a damaged row.
void set_undone(sqlite3* database, const std::string& path, int64_t sequence, bool undone,
                std::optional<int64_t> undone_by);

//---- Several writers (label_store_writers.cpp)

// The refusal of an edit of label `id` that someone else changed or removed since its editor
// read it: names the label (id, class, span) and the last journal row's annotator and action.
// `consequence` ends the message: "your edit was not saved", "nothing was undone".
EditConflict conflict(sqlite3* database, const std::string& path, int64_t id,
                      const std::string& consequence);
// The label `seen` names, read inside the caller's (immediate) transaction, when its revision is
// still the one seen; otherwise the conflict (or tactile::Error "no such label to VERB" for an
// id never used). `verb`: "update", "remove", "reject".
Label require_seen(sqlite3* database, const std::string& path, const LabelRef& seen,
                   const char* verb);

// Schema 1 to 2: checksums for every row, digests, the classes written. Inside the
// caller's transaction.
void add_checksums(sqlite3* database, const std::string& path);
// Schema 3 to 4: a revision for every label (1), covered by its checksum. Inside the
// caller's transaction.
void add_revisions(sqlite3* database, const std::string& path);

}  // namespace tactile::label_rows
