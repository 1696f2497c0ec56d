// Several writers of one label store: the revision check every edit passes, the refusal that
// names who changed a label meanwhile, and the change check and journal reads a writer uses to
// follow the others.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "label_rows.h"
#include "sqlite_statement.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

namespace label_rows {

namespace {

// "pat, 12.30-12.85 s"
std::string label_summary(const Label& label) {
  char span[64];
  std::snprintf(span, sizeof(span), "%.2f-%.2f s", label.t0, label.t1);
  return label.class_name + ", " + span;
}

// What a journal row did to its label, as the refusal says it.
std::string change_verb(const std::string& action, bool label_exists) {
  if (action == "update") return "changed";
  if (action == "delete") return "removed";
  if (action == "reject") return "rejected";
  if (action == "insert") return "added";
  // An undo or redo either brought the label to other values or took it away.
  return (label_exists ? "changed (" : "removed (") + action + ")";
}

}  // namespace

EditConflict conflict(sqlite3* database, const std::string& path, int64_t id,
                      const std::string& consequence) {
  const std::optional<Label> now = load(database, path, id);
  std::string annotator = "someone", action;
  std::optional<Label> described = now;
  {
    sqlite::Statement last(database, where_label(path, id),
                           "SELECT annotator, action, before_json FROM journal WHERE label_id = ? "
                           "ORDER BY sequence DESC LIMIT 1");
    last.bind(1, id);
    if (last.step()) {
      annotator = last.text(0);
      action = last.text(1);
      // A label gone is described as it was before it went.
      if (!described) {
        try {
          described = state_from_json(last.text(2), where_label(path, id));
        } catch (const Error&) {
          described.reset();
        }
      }
    }
  }
  const std::string verb =
      action.empty() ? (now ? "changed" : "removed") : change_verb(action, now.has_value());
  const std::string label =
      "label " + std::to_string(id) + (described ? " (" + label_summary(*described) + ")" : "");
  return EditConflict(where_label(path, id),
                      label + " was " + verb + " by " + annotator + " meanwhile; " + consequence,
                      id, annotator, verb);
}

Label require_seen(sqlite3* database, const std::string& path, const LabelRef& seen,
                   const char* verb) {
  const std::optional<Label> now = load(database, path, seen.id);
  if (!now) {
    sqlite::Statement known(database, path, "SELECT COUNT(*) FROM journal WHERE label_id = ?");
    known.bind(1, seen.id);
    known.step();
    if (known.integer(0) == 0)
      throw Error(where_label(path, seen.id), std::string("no such label to ") + verb);
    throw conflict(database, path, seen.id, "your edit was not saved");
  }
  if (seen.revision == 0)
    throw Error(where_label(path, seen.id) + " (" + label_summary(*now) + ")",
                std::string("the ") + verb +
                    " states no revision (the label's revision as last read); nothing was saved");
  // Inside the edit's immediate transaction no other writer can commit between this check and
  // the write: the check is the `WHERE id = ? AND revision = ?` of the write.
  if (now->revision != seen.revision)
    throw conflict(database, path, seen.id, "your edit was not saved");
  return *now;
}

}  // namespace label_rows

int64_t LabelStore::change_count() const {
  sqlite::Statement version(database_, path_, "PRAGMA data_version");
  version.step();
  return version.integer(0) + others_commits_;
}

void LabelStore::note_others_commits() {
  const int64_t newest = last_sequence();
  if (newest != known_sequence_) ++others_commits_;
  known_sequence_ = newest;
}

void LabelStore::note_own_commit() { known_sequence_ = last_sequence(); }

std::vector<JournalEntry> LabelStore::journal_after(int64_t sequence) const {
  sqlite::Statement select(database_, path_,
                           std::string("SELECT ") + label_rows::kJournalColumns +
                               " FROM journal WHERE sequence > ? ORDER BY sequence");
  select.bind(1, sequence);
  std::vector<JournalEntry> entries;
  std::vector<StoreProblem> problems;
  while (select.step()) {
    label_rows::CheckedJournal row = label_rows::read_journal(select);
    if (row.problem)
      problems.push_back(*row.problem);
    else
      entries.push_back(std::move(*row.entry));
  }
  note_problems(problems);
  return entries;
}

int64_t LabelStore::last_sequence() const {
  sqlite::Statement select(database_, path_, "SELECT COALESCE(MAX(sequence), 0) FROM journal");
  select.step();
  return select.integer(0);
}

}  // namespace tactile
