// The journal and the rejections of label_rows.h: every edit's rows, undo's marks, the
// suggestions a person rejected.
#include <nlohmann/json.hpp>

#include "label_rows.h"
#include "row_checksum.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::label_rows {

using row_checksum::Field;

//---- Journal

std::string state_json(const std::optional<Label>& label) {
  if (!label) return {};
  nlohmann::json object = to_json(*label);
  object["revision"] = label->revision;
  return object.dump();
}

std::string content_json(const std::optional<Label>& label) {
  return label ? to_json(*label).dump() : std::string();
}

std::optional<Label> state_from_json(const std::string& text, const std::string& where) {
  if (text.empty()) return std::nullopt;
  nlohmann::json object;
  try {
    object = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, std::string("malformed journal JSON: ") + error.what());
  }
  return from_json(object, where);
}

int64_t next_batch(sqlite3* database, const std::string& path) {
  sqlite::Statement select(database, path, "SELECT COALESCE(MAX(batch), 0) + 1 FROM journal");
  select.step();
  return select.integer(0);
}

namespace {

std::vector<Field> journal_fields(int64_t batch, const std::string& time,
                                  const std::string& annotator, const std::string& action,
                                  int64_t label_id, const std::string& before_json,
                                  const std::string& after_json, bool undone,
                                  std::optional<int64_t> undone_by) {
  return {{"batch", batch},
          {"time", time},
          {"annotator", annotator},
          {"action", action},
          {"label_id", label_id},
          {"before_json", before_json},
          {"after_json", after_json},
          {"undone", int64_t{undone ? 1 : 0}},
          {"undone_by", undone_by ? row_checksum::Value(*undone_by) : row_checksum::Value()}};
}

std::vector<Field> journal_fields(const JournalEntry& entry, std::optional<int64_t> undone_by) {
  return journal_fields(entry.batch, entry.time, entry.annotator, entry.action, entry.label_id,
                        entry.before_json, entry.after_json, entry.undone, undone_by);
}

CheckedJournal load_journal(sqlite3* database, const std::string& path, int64_t sequence) {
  sqlite::Statement select(
      database, path,
      std::string("SELECT ") + kJournalColumns + " FROM journal WHERE sequence = ?");
  select.bind(1, sequence);
  if (!select.step()) throw Error(path + " journal row " + std::to_string(sequence), "missing");
  return read_journal(select);
}

}  // namespace

void seal_journal_row(sqlite3* database, const std::string& path, const JournalEntry& entry,
                      std::optional<int64_t> undone_by) {
  const std::string checksum =
      row_checksum::compute("journal", entry.sequence, journal_fields(entry, undone_by));
  sqlite::Statement update(database, path, "UPDATE journal SET checksum = ? WHERE sequence = ?");
  update.bind(1, checksum).bind(2, entry.sequence);
  update.run();
  adjust_digest(database, path, kJournalScope, 1, row_checksum::row_hash(entry.sequence, checksum));
}

void write_journal(sqlite3* database, const std::string& path, int64_t batch,
                   const std::string& annotator, const std::string& action, int64_t label_id,
                   const std::string& before_json, const std::string& after_json,
                   const std::string& time) {
  JournalEntry entry;
  entry.batch = batch;
  entry.time = time.empty() ? now_utc() : time;
  entry.annotator = annotator;
  entry.action = action;
  entry.label_id = label_id;
  entry.before_json = before_json;
  entry.after_json = after_json;
  {
    sqlite::Statement insert(database, where_label(path, label_id),
                             "INSERT INTO journal (batch, time, annotator, action, label_id, "
                             "before_json, after_json, checksum) VALUES (?, ?, ?, ?, ?, ?, ?, '')");
    insert.bind(1, batch)
        .bind(2, entry.time)
        .bind(3, annotator)
        .bind(4, action)
        .bind(5, label_id)
        .bind(6, before_json)
        .bind(7, after_json);
    insert.run();
  }
  entry.sequence = sqlite3_last_insert_rowid(database);
  seal_journal_row(database, path, entry, std::nullopt);
}

namespace {}  // namespace

JournalEntry journal_from_row(const sqlite::Statement& statement,
                              std::optional<int64_t>& undone_by) {
  JournalEntry entry;
  entry.sequence = statement.integer(0);
  entry.batch = statement.integer(1);
  entry.time = statement.text(2);
  entry.annotator = statement.text(3);
  entry.action = statement.text(4);
  entry.label_id = statement.integer(5);
  entry.before_json = statement.text(6);
  entry.after_json = statement.text(7);
  entry.undone = statement.integer(8) != 0;
  undone_by.reset();
  if (!statement.is_null(9)) undone_by = statement.integer(9);
  return entry;
}

CheckedJournal read_journal(const sqlite::Statement& statement) {
  CheckedJournal row;
  JournalEntry entry = journal_from_row(statement, row.undone_by);
  row.sequence = entry.sequence;
  const int64_t undone = statement.integer(8);
  row.checksum = statement.text(10);
  row.problem = checksum_problem("journal", entry.sequence, journal_fields(entry, row.undone_by),
                                 row.checksum);
  auto bad = [&row, &entry](const char* field, const std::string& what) {
    row.problem = row_problem("journal", entry.sequence, field, what);
  };
  static const std::set<std::string> kActions = {"insert", "update", "delete",
                                                 "reject", "undo",   "redo"};
  if (row.problem) return row;
  if (undone != 0 && undone != 1) return bad("undone", "neither 0 nor 1"), row;
  if (!is_iso_time(entry.time)) return bad("time", "'" + entry.time + "' is not a time"), row;
  if (kActions.count(entry.action) == 0)
    return bad("action", "'" + entry.action + "' is not an action"), row;
  for (const auto& [field, text] :
       {std::pair{"before_json", &entry.before_json}, std::pair{"after_json", &entry.after_json}}) {
    try {
      state_from_json(*text, "");
    } catch (const Error& error) {
      return bad(field, error.message()), row;
    }
  }
  row.entry = std::move(entry);
  return row;
}

void set_undone(sqlite3* database, const std::string& path, int64_t sequence, bool undone,
                std::optional<int64_t> undone_by) {
  const CheckedJournal row = load_journal(database, path, sequence);
  if (row.problem) throw problem_error(*row.problem, path);
  adjust_digest(database, path, kJournalScope, -1,
                0 - row_checksum::row_hash(sequence, row.checksum));
  sqlite::Statement update(database, path,
                           "UPDATE journal SET undone = ?, undone_by = ? WHERE sequence = ?");
  update.bind(1, int64_t{undone ? 1 : 0});
  if (undone_by)
    update.bind(2, *undone_by);
  else
    update.bind_null(2);
  update.bind(3, sequence);
  update.run();
  JournalEntry entry = *row.entry;
  entry.undone = undone;
  seal_journal_row(database, path, entry, undone_by);
}

void clear_redo_chain(sqlite3* database, const std::string& path) {
  std::vector<std::pair<int64_t, bool>> rows;
  {
    sqlite::Statement select(database, path,
                             "SELECT sequence, undone FROM journal WHERE undone_by IS NOT NULL");
    while (select.step()) rows.emplace_back(select.integer(0), select.integer(1) != 0);
  }
  for (const auto& [sequence, undone] : rows)
    set_undone(database, path, sequence, undone, std::nullopt);
}

std::vector<row_checksum::Field> rejection_fields(const Rejection& rejection) {
  return {{"recording", rejection.recording},
          {"method", rejection.method},
          {"t0", rejection.t0},
          {"t1", rejection.t1},
          {"annotator", rejection.annotator},
          {"time", rejection.time}};
}

namespace {

// Parameters 1-5 of a statement: what names a rejection (recording, method, span, annotator).
sqlite::Statement& bind_rejection(sqlite::Statement& statement, const Rejection& rejection) {
  return statement.bind(1, rejection.recording)
      .bind(2, rejection.method)
      .bind(3, rejection.t0)
      .bind(4, rejection.t1)
      .bind(5, rejection.annotator);
}

}  // namespace

void remember_rejection(sqlite3* database, const std::string& path, const Label& suggestion,
                        const std::string& annotator) {
  const std::string where = where_label(path, suggestion.id);
  Rejection rejection{
      0,        suggestion.recording, suggestion.annotator, suggestion.t0, suggestion.t1, annotator,
      now_utc()};
  {
    sqlite::Statement insert(database, where,
                             "INSERT INTO rejections (recording, method, t0, t1, annotator, time, "
                             "checksum) VALUES (?, ?, ?, ?, ?, ?, '')");
    bind_rejection(insert, rejection).bind(6, rejection.time);
    insert.run();
  }
  rejection.id = sqlite3_last_insert_rowid(database);
  sqlite::Statement seal(database, where, "UPDATE rejections SET checksum = ? WHERE id = ?");
  seal.bind(1, row_checksum::compute("rejections", rejection.id, rejection_fields(rejection)))
      .bind(2, rejection.id);
  seal.run();
}

void forget_rejection(sqlite3* database, const std::string& path, const Label& suggestion,
                      const std::string& annotator) {
  sqlite::Statement erase(database, where_label(path, suggestion.id),
                          "DELETE FROM rejections WHERE id = (SELECT MAX(id) FROM rejections WHERE "
                          "recording = ? AND method = ? AND t0 = ? AND t1 = ? AND annotator = ?)");
  bind_rejection(erase, {0, suggestion.recording, suggestion.annotator, suggestion.t0,
                         suggestion.t1, annotator, ""});
  erase.run();
}

}  // namespace tactile::label_rows
