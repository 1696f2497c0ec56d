// The LabelStore's undo, redo and journal. Every edit writes journal rows with
// the label's state before and after; undo walks them back, redo forward.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>

#include "label_rows.h"
#include "row_checksum.h"
#include "sqlite_statement.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

namespace {

constexpr const char* kEditActions = "action IN ('insert', 'update', 'delete', 'reject')";

struct EditRow {
  int64_t sequence = 0;
  std::string annotator, action;
  int64_t label_id = 0;
  std::string before_json, after_json;
};

// The journal rows an undo or redo replays; a damaged one stops it, changing nothing.
std::vector<EditRow> edit_rows(sqlite3* database, const std::string& path,
                               const std::string& condition, int64_t value, const char* order) {
  sqlite::Statement select(database, path,
                           std::string("SELECT ") + label_rows::kJournalColumns +
                               " FROM journal WHERE " + kEditActions + " AND " + condition +
                               " ORDER BY sequence " + order);
  select.bind(1, value);
  std::vector<EditRow> rows;
  while (select.step()) {
    const label_rows::CheckedJournal row = label_rows::read_journal(select);
    if (row.problem) throw label_rows::problem_error(*row.problem, path);
    const JournalEntry& entry = *row.entry;
    rows.push_back({entry.sequence, entry.annotator, entry.action, entry.label_id,
                    entry.before_json, entry.after_json});
  }
  return rows;
}

// Moves one label from the state `expected_json` to `target_json` and journals
// it as `verb` ("undo" or "redo"). A label that is no longer in the expected
// state was changed by a later edit (another annotator's, another writer's);
// overwriting it would silently lose that edit, so this refuses instead, naming
// the label and who changed it. The label moved gets a new revision, so that an
// editor who saw it before the undo or redo is refused in turn.
void move_label(sqlite3* database, const std::string& path, const EditRow& row,
                const std::string& expected_json, const std::string& target_json, const char* verb,
                int64_t batch, const std::string& annotator) {
  const std::string where = label_rows::where_label(path, row.label_id);
  const std::optional<Label> current = label_rows::load(database, path, row.label_id);
  // Both sides re-serialised the same way, so equal labels give equal text. The revision is
  // left out: it moves on at every undo and redo while the values come back.
  const std::string expected_state =
      label_rows::content_json(label_rows::state_from_json(expected_json, where));
  if (label_rows::content_json(current) != expected_state)
    throw label_rows::conflict(database, path, row.label_id,
                               std::string("cannot ") + verb + " the " + row.action +
                                   " of journal entry " + std::to_string(row.sequence) +
                                   ", nothing was " +
                                   (verb == std::string("undo") ? "undone" : "redone"));
  std::optional<Label> target = label_rows::state_from_json(target_json, where);
  if (target) {
    target->revision = std::max(current ? current->revision : 0, target->revision) + 1;
    label_rows::store(database, path, *target);
  } else {
    label_rows::erase(database, path, row.label_id);
  }
  // A reject also remembered the suggestion's span: forgotten when it comes back, remembered
  // again when it goes (by whom the reject was journalled).
  if (row.action == "reject") {
    if (target)
      label_rows::forget_rejection(database, path, *target, row.annotator);
    else
      label_rows::remember_rejection(
          database, path, *label_rows::state_from_json(expected_json, where), row.annotator);
  }
  label_rows::write_journal(database, path, batch, annotator.empty() ? row.annotator : annotator,
                            verb, row.label_id, label_rows::state_json(current),
                            label_rows::state_json(target));
}

// The batch undo() takes back for `annotator` (anyone's when empty): the newest edit batch
// not undone; none when there is none.
std::optional<int64_t> newest_undoable_batch(sqlite3* database, const std::string& path,
                                             const std::string& annotator) {
  sqlite::Statement find(database, path,
                         std::string("SELECT batch FROM journal WHERE ") + kEditActions +
                             " AND undone = 0" + (annotator.empty() ? "" : " AND annotator = ?") +
                             " ORDER BY sequence DESC LIMIT 1");
  if (!annotator.empty()) find.bind(1, annotator);
  if (!find.step()) return std::nullopt;
  return find.integer(0);
}

}  // namespace

bool LabelStore::undo(const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const std::optional<int64_t> target_batch = newest_undoable_batch(database_, path_, annotator);
  if (!target_batch) return false;
  const int64_t undo_batch = label_rows::next_batch(database_, path_);
  // Newest first, so a label edited twice in one batch steps back in order.
  for (const EditRow& row :
       edit_rows(database_, path_, "undone = 0 AND batch = ?", *target_batch, "DESC")) {
    move_label(database_, path_, row, row.after_json, row.before_json, "undo", undo_batch,
               annotator);
    label_rows::set_undone(database_, path_, row.sequence, true, undo_batch);
  }
  note_own_commit();
  transaction.commit();
  return true;
}

bool LabelStore::redo(const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
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
  for (const EditRow& row : edit_rows(database_, path_, "undone_by = ?", undo_batch, "ASC")) {
    move_label(database_, path_, row, row.before_json, row.after_json, "redo", redo_batch,
               annotator);
    label_rows::set_undone(database_, path_, row.sequence, false, std::nullopt);
  }
  note_own_commit();
  transaction.commit();
  return true;
}

std::vector<JournalEntry> LabelStore::next_undo(const std::string& annotator) const {
  const std::optional<int64_t> target_batch = newest_undoable_batch(database_, path_, annotator);
  if (!target_batch) return {};
  sqlite::Statement select(database_, path_,
                           std::string("SELECT ") + label_rows::kJournalColumns +
                               " FROM journal WHERE " + kEditActions +
                               " AND undone = 0 AND batch = ? ORDER BY sequence ASC");
  select.bind(1, *target_batch);
  std::vector<JournalEntry> entries;
  while (select.step()) {
    label_rows::CheckedJournal row = label_rows::read_journal(select);
    if (row.problem) throw label_rows::problem_error(*row.problem, path_);
    entries.push_back(std::move(*row.entry));
  }
  return entries;
}

std::vector<JournalEntry> LabelStore::journal(int64_t limit) const {
  sqlite::Statement select(database_, path_,
                           std::string("SELECT ") + label_rows::kJournalColumns +
                               " FROM journal ORDER BY sequence DESC LIMIT ?");
  select.bind(1, limit);
  std::vector<JournalEntry> entries;
  std::vector<StoreProblem> problems;
  label_rows::Digest found;
  while (select.step()) {
    label_rows::CheckedJournal row = label_rows::read_journal(select);
    ++found.rows;
    found.sum += row_checksum::row_hash(row.sequence, row.checksum);
    if (row.problem)
      problems.push_back(*row.problem);
    else
      entries.push_back(std::move(*row.entry));
  }
  // The whole journal read: its digest says whether rows were lost.
  if (limit < 0)
    label_rows::compare_digests(
        {{label_rows::kJournalScope, found}},
        label_rows::read_digests(database_, label_rows::kJournalScope, problems), true, problems);
  note_problems(problems);
  return entries;
}

}  // namespace tactile
