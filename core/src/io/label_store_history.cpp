// The LabelStore's undo, redo and journal. Every edit writes journal rows with
// the label's state before and after; undo walks them back, redo forward.
#include "label_rows.h"
#include "sqlite_statement.h"
#include "tactile/error.h"
#include "tactile/io/label_store.h"

namespace tactile {

namespace {

constexpr const char* kEditActions = "action IN ('insert', 'update', 'delete')";

struct EditRow {
  int64_t sequence = 0;
  std::string annotator, action;
  int64_t label_id = 0;
  std::string before_json, after_json;
};

std::vector<EditRow> edit_rows(sqlite3* database, const std::string& path,
                               const std::string& condition, int64_t value, const char* order) {
  sqlite::Statement select(
      database, path,
      std::string("SELECT sequence, annotator, action, label_id, before_json, after_json "
                  "FROM journal WHERE ") +
          kEditActions + " AND " + condition + " ORDER BY sequence " + order);
  select.bind(1, value);
  std::vector<EditRow> rows;
  while (select.step())
    rows.push_back({select.integer(0), select.text(1), select.text(2), select.integer(3),
                    select.text(4), select.text(5)});
  return rows;
}

// Moves one label from the state `expected_json` to `target_json` and journals
// it as `verb` ("undo" or "redo"). A label that is no longer in the expected
// state was changed by a later edit; overwriting it would silently lose that
// edit, so this refuses instead.
void move_label(sqlite3* database, const std::string& path, const EditRow& row,
                const std::string& expected_json, const std::string& target_json, const char* verb,
                int64_t batch, const std::string& annotator) {
  const std::string where = label_rows::where_label(path, row.label_id);
  const std::string current_json =
      label_rows::state_json(label_rows::load(database, path, row.label_id));
  // Both sides re-serialised the same way, so equal labels give equal text.
  const std::string expected_state =
      label_rows::state_json(label_rows::state_from_json(expected_json, where));
  if (current_json != expected_state)
    throw Error(where, std::string("cannot ") + verb + " the " + row.action + " of journal entry " +
                           std::to_string(row.sequence) +
                           ": the label was changed since by another edit");
  const std::optional<Label> target = label_rows::state_from_json(target_json, where);
  if (target)
    label_rows::store(database, path, *target);
  else
    label_rows::erase(database, path, row.label_id);
  label_rows::write_journal(database, path, batch, annotator.empty() ? row.annotator : annotator,
                            verb, row.label_id, current_json, target_json);
}

}  // namespace

bool LabelStore::undo(const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  int64_t target_batch = 0;
  {
    sqlite::Statement find(database_, path_,
                           std::string("SELECT batch FROM journal WHERE ") + kEditActions +
                               " AND undone = 0" + (annotator.empty() ? "" : " AND annotator = ?") +
                               " ORDER BY sequence DESC LIMIT 1");
    if (!annotator.empty()) find.bind(1, annotator);
    if (!find.step()) return false;
    target_batch = find.integer(0);
  }
  const int64_t undo_batch = label_rows::next_batch(database_, path_);
  sqlite::Statement mark(database_, path_,
                         "UPDATE journal SET undone = 1, undone_by = ? WHERE sequence = ?");
  // Newest first, so a label edited twice in one batch steps back in order.
  for (const EditRow& row :
       edit_rows(database_, path_, "undone = 0 AND batch = ?", target_batch, "DESC")) {
    move_label(database_, path_, row, row.after_json, row.before_json, "undo", undo_batch,
               annotator);
    mark.reset();
    mark.bind(1, undo_batch).bind(2, row.sequence);
    mark.run();
  }
  transaction.commit();
  return true;
}

bool LabelStore::redo(const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  int64_t undo_batch = 0;
  {
    // The batch undone most recently is the one whose undo has the highest batch.
    sqlite::Statement find(
        database_, path_,
        std::string("SELECT undone_by FROM journal WHERE undone = 1 AND undone_by IS NOT NULL") +
            (annotator.empty() ? "" : " AND annotator = ?") + " ORDER BY undone_by DESC LIMIT 1");
    if (!annotator.empty()) find.bind(1, annotator);
    if (!find.step()) return false;
    undo_batch = find.integer(0);
  }
  const int64_t redo_batch = label_rows::next_batch(database_, path_);
  sqlite::Statement mark(database_, path_,
                         "UPDATE journal SET undone = 0, undone_by = NULL WHERE sequence = ?");
  for (const EditRow& row : edit_rows(database_, path_, "undone_by = ?", undo_batch, "ASC")) {
    move_label(database_, path_, row, row.before_json, row.after_json, "redo", redo_batch,
               annotator);
    mark.reset();
    mark.bind(1, row.sequence);
    mark.run();
  }
  transaction.commit();
  return true;
}

std::vector<JournalEntry> LabelStore::journal(int64_t limit) const {
  sqlite::Statement select(database_, path_,
                           "SELECT sequence, time, annotator, action, label_id, before_json, "
                           "after_json, undone, batch FROM journal ORDER BY sequence DESC LIMIT ?");
  select.bind(1, limit);
  std::vector<JournalEntry> entries;
  while (select.step()) {
    JournalEntry entry;
    entry.sequence = select.integer(0);
    entry.time = select.text(1);
    entry.annotator = select.text(2);
    entry.action = select.text(3);
    entry.label_id = select.integer(4);
    entry.before_json = select.text(5);
    entry.after_json = select.text(6);
    entry.undone = select.integer(7) != 0;
    entry.batch = select.integer(8);
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace tactile
