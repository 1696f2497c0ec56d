#pragma once
// The LabelStore: every label edit saved at once in a SQLite database, with a
// journal of who did what and when, undo and redo, and CSV / JSON export.
//
// Every edit is one transaction that also writes its journal rows, so an edit
// that returned survives a killed process or a power cut. Several processes may
// share one database: writers wait for each other (busy timeout) instead of
// failing. One LabelStore is one connection: use it from one thread at a time
// (open one per thread for parallel work).
//
// Several writers (two workbenches, a workbench and `tactile segment`): every label carries a
// revision, and every update or removal states the revision its editor last saw. An edit of a
// label that someone else changed or removed since is refused whole (EditConflict, naming the
// label and who did what), so no edit is lost; undo and redo refuse the same way. A writer
// notices the others' commits with change_count() (microseconds) and reads what they did with
// journal_after().

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/labelstore/label.h"

struct sqlite3;

namespace tactile {

// Which labels a query, an export or a bulk removal touches. Unset fields match
// everything. The overlap bounds select labels whose [t0, t1) intersects
// [overlapping_t0, overlapping_t1); either bound may be given alone.
struct LabelFilter {
  std::optional<std::string> recording, region, class_name, annotator;
  std::optional<LabelSource> source;
  std::optional<double> overlapping_t0, overlapping_t1;
};

// One row of the journal. Edits are "insert", "update", "delete"; "undo" and
// "redo" rows record what an undo or redo changed. before_json / after_json
// hold the label as JSON (the export's fields), or "" when it did not exist.
// `undone` is true for an edit that is currently undone.
struct JournalEntry {
  int64_t sequence = 0;
  std::string time, annotator, action;
  int64_t label_id = 0;
  std::string before_json, after_json;
  bool undone = false;
  int64_t batch = 0;  // rows written by one call (add_many, remove_where, undo) share a batch
};

// A suggestion (a segmenter's label) an annotator rejected: its span is remembered so
// that a rerun of the method does not bring it back.
struct Rejection {
  int64_t id = 0;
  std::string recording;
  std::string method;  // the segmenter's annotator, "segmenter:threshold"
  double t0 = 0.0, t1 = 0.0;
  std::string annotator, time;
};

// A row of the store whose stored values no longer match their checksum, or are
// not valid (a time not finite or out of order, a class in no vocabulary, a date
// that does not parse), or rows lost or added on disk (a digest that disagrees).
struct StoreProblem {
  std::string table;  // "labels", "journal", "digests", "schema" or "database"
  int64_t row = 0;    // the row id (label id, journal sequence); 0 for a table or a digest
  std::string field;  // the damaged field, digest scope or schema object; "" when not one
  std::string what;
  // "labels.db: labels row 17 field t1"
  std::string where(const std::string& path) const;
};

// A label as its editor last saw it: the id, and the revision (Label::revision) read with it.
struct LabelRef {
  int64_t id = 0;
  int64_t revision = 0;
};
inline LabelRef ref_of(const Label& label) { return {label.id, label.revision}; }

// An edit, undo or redo refused because another writer changed or removed a label since its
// editor read it: "label 42 (pat, 12.30-12.85 s) was changed by bob meanwhile; your edit was
// not saved". Nothing of the refused edit is written.
class EditConflict : public Error {
 public:
  EditConflict(std::string where, std::string message, int64_t label_id, std::string annotator,
               std::string action)
      : Error(std::move(where), std::move(message)),
        label_id_(label_id),
        annotator_(std::move(annotator)),
        action_(std::move(action)) {}
  int64_t label_id() const { return label_id_; }
  // Who changed the label last, and how ("changed", "removed", "rejected", ...).
  const std::string& annotator() const { return annotator_; }
  const std::string& action() const { return action_; }

 private:
  int64_t label_id_;
  std::string annotator_, action_;
};

// One user action on the labels, as a whole (the command of the workbench and the command
// line): the labels it removes, rejects, changes and adds. A segmenter run removes its earlier
// suggestions and adds new ones; a prediction replaces the model's lane; an accept adds one
// label. LabelStore::apply writes it as one journal batch, so one undo reverts it all.
// Removals, updates and rejections state the revision their editor last saw (LabelRef,
// Label::revision); additions never conflict.
struct LabelEdit {
  std::vector<LabelRef> remove;  // existing labels
  std::vector<Label> add;        // new labels (id, times and revision are assigned by the store)
  std::vector<Label> update;     // existing labels (by id and revision) with their new values
  std::vector<LabelRef> reject;  // suggestions rejected: removed, their spans remembered
  bool empty() const { return remove.empty() && add.empty() && update.empty() && reject.empty(); }
};

// The JSON export's document for these labels: {"labels": [...]}, indented.
std::string labels_json(const std::vector<Label>& labels);
// One label as that document holds it (with its revision when it has one), and back: what a
// shard's part keeps of the labels its merge stores (shards/shard.h). Throws tactile::Error
// naming `where` on a malformed label.
nlohmann::json label_json(const Label& label);
Label label_from_json(const nlohmann::json& object, const std::string& where);

class LabelStore {
 public:
  enum class OpenMode {
    kCreate,    // create the database file when it is missing
    kExisting,  // a missing file is an error (command-line readers must not create one)
    kReadOnly   // existing, and never written: no schema upgrade, no journal mode change
                // (tactile verify); edits throw
  };

  // Opens or creates the database: WAL journal, synchronous=FULL, 5 s busy
  // timeout, schema created or checked. Throws tactile::Error(path, ...) for a
  // file that is not a SQLite database, a foreign database, or a newer schema.
  explicit LabelStore(const std::string& path, OpenMode mode = OpenMode::kCreate);
  ~LabelStore();
  LabelStore(LabelStore&& other) noexcept;
  LabelStore& operator=(LabelStore&& other) noexcept;
  LabelStore(const LabelStore&) = delete;
  LabelStore& operator=(const LabelStore&) = delete;

  // The store assigns the id and the created / modified times; label.id,
  // label.created and label.modified are ignored. Validates t0 < t1 (finite),
  // confidence in [0, 1], non-empty recording, region and class.
  int64_t add(const Label& label);
  // Labels added from now on through this store are stamped `iso_time` (ISO 8601 UTC)
  // instead of the wall clock: for outputs that must be reproducible, such as simulated
  // ground truth (same seed, same bytes). "" returns to the wall clock.
  void use_fixed_time(std::string iso_time) { fixed_time_ = std::move(iso_time); }
  // Replaces the label with id label.id (keeping its created time); throws if absent, and
  // EditConflict unless label.revision is the label's revision (nobody changed it since).
  void update(const Label& label);
  // Removes the label as last seen (EditConflict when changed or removed since). `annotator`
  // is who removed it, for the journal; "" = the label's own annotator.
  void remove(const LabelRef& label, const std::string& annotator = {});
  std::optional<Label> get(int64_t id) const;
  // Ordered by recording, t0, id.
  std::vector<Label> list(const LabelFilter& filter = {}) const;
  // Labels of one recording; "" = all labels.
  int64_t count(const std::string& recording = {}) const;
  // All or nothing, in one transaction and one journal batch (undone together).
  std::vector<int64_t> add_many(const std::vector<Label>& labels);
  // Removes every label the filter matches, in one transaction; returns how many.
  int64_t remove_where(const LabelFilter& filter, const std::string& annotator = {});
  // The whole edit or nothing, in one transaction and one journal batch whose every row is
  // journalled under `by` (the person or program that made the edit), so that undo(by)
  // reverts exactly this edit, whichever lanes it touched. Removals first, then rejections,
  // updates and insertions; returns the new labels' ids in the order of edit.add. Throws naming the
  // first label that is invalid or no longer exists, leaving the store unchanged; EditConflict
  // when a removed, rejected or updated label's revision is not the one stated (someone else
  // changed or removed it since), leaving the store unchanged too.
  std::vector<int64_t> apply(const LabelEdit& edit, const std::string& by);

  // A number that changes whenever another connection (another process, another LabelStore)
  // has committed to the database since this one last asked; this store's own commits do not
  // change it. PRAGMA data_version (a few microseconds, cheap enough for every frame), plus the
  // other writers' commits this store's own edits found in the journal (which data_version
  // misses when an edit's transaction begins right after them). It may also change without
  // news (then journal_after() has nothing new).
  int64_t change_count() const;
  // The journal rows after `sequence`, oldest first (what the other writers did since a
  // journal row one has seen); damaged rows are left out (in problems()).
  std::vector<JournalEntry> journal_after(int64_t sequence) const;
  // The newest journal row's sequence (0 for an empty journal).
  int64_t last_sequence() const;

  // Rejects a suggestion: removes the segmenter's label and remembers its span, one edit
  // journalled under the annotator (its undo brings the label back and forgets the span).
  // Throws when the label is not a segmenter's. The same as apply() with edit.reject.
  void reject(const LabelRef& suggestion, const std::string& annotator);
  // The rejections of a recording's suggestions (damaged rows left out, in problems()).
  std::vector<Rejection> rejections(const std::string& recording) const;

  // Class vocabulary per skin (the papers' class names), in the given order.
  // Names must be non-empty and distinct.
  void set_classes(const std::string& skin, const std::vector<std::string>& classes);
  // Empty when no vocabulary was set for the skin.
  std::vector<std::string> classes(const std::string& skin) const;

  // undo() reverts the newest edit batch that is not undone (only that
  // annotator's when given) and returns false when there is none; redo()
  // re-applies the most recently undone batch. Both are journalled and each is
  // its own transaction; any new edit clears the redo chain. Throws
  // EditConflict when a label was changed since by another edit (another
  // annotator's, with per-annotator undo), naming the label and who changed it,
  // leaving the store unchanged: an undo never takes back someone else's work.
  bool undo(const std::string& annotator = {});
  bool redo(const std::string& annotator = {});
  // The journal rows of the edit undo(annotator) would revert now, oldest first (empty when
  // there is none): what Ctrl+Z is about to take back, to say so.
  std::vector<JournalEntry> next_undo(const std::string& annotator = {}) const;
  // The newest `limit` journal rows, newest first (a negative limit: all rows).
  std::vector<JournalEntry> journal(int64_t limit = 1000) const;

  // Both write a temporary file beside `path` and rename it into place, so a
  // failed export leaves no partial file. CSV follows RFC 4180 (CRLF line
  // ends, fields with commas, quotes or line breaks quoted).
  void export_csv(const std::string& path, const LabelFilter& filter = {}) const;
  // {"labels": [{"id", "recording", "t0", "t1", "region", "class", "annotator",
  //  "source", "confidence", "note", "created", "modified"}]}
  void export_json(const std::string& path, const LabelFilter& filter = {}) const;

  // Result of PRAGMA integrity_check: "ok" for a sound database.
  std::string integrity_check() const;

  // Every read checks each row it meets against its checksum and its values; a
  // damaged row is left out of what a read returns (get() throws for it) and is
  // never overwritten (update, remove, undo and redo throw naming it). The rows
  // met so far that are damaged, once each:
  const std::vector<StoreProblem>& problems() const { return problems_; }
  // Reads every row of every table and runs SQLite's integrity check: all
  // problems of the store.
  std::vector<StoreProblem> check() const;
  // The schema version the store had when opened (1 = no checksums, upgraded on open).
  int64_t opened_version() const { return opened_version_; }
  const std::string& path() const;

 private:
  void note_problems(const std::vector<StoreProblem>& problems) const;
  // An edit's transaction that begins after another writer's commit makes SQLite's data_version
  // skip that commit: each edit notes, once its transaction holds the lock, whether the journal
  // grew since this connection last wrote (a change for change_count()), and after its writes
  // the journal's end as its own.
  void note_others_commits();
  void note_own_commit();

  sqlite3* database_ = nullptr;
  std::string path_;
  std::string fixed_time_;  // "" = the wall clock
  mutable std::vector<StoreProblem> problems_;
  int64_t opened_version_ = 0;
  int64_t known_sequence_ = 0;  // the journal's newest row as of this connection's last edit
  int64_t others_commits_ = 0;  // commits of other writers noticed by this connection's edits
};

}  // namespace tactile
