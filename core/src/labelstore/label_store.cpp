#include "tactile/labelstore/label_store.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <utility>

#include "label_rows.h"
#include "row_checksum.h"
#include "sqlite_statement.h"
#include "tactile/error.h"

namespace tactile {

namespace {

// Version 1: tables store_schema, labels, classes, journal.
// Version 2: a checksum column in labels and journal (row_checksum.h), tables
// digests and label_classes (label_rows::add_checksums). A store of version 1 is
// upgraded when opened; a new store is made the same way (version 1, then the
// upgrade), so every store of version 2 has the very same schema text, which
// check() compares.
// Version 3: table rejections (suggestions an annotator rejected, so that a rerun of
// the segmenter does not bring them back).
// Version 4: a revision column in labels (covered by the row's checksum, label_rows::
// add_revisions): every edit states the revision its editor saw, so that an edit of a label
// someone else changed meanwhile is refused instead of overwriting it.
constexpr int64_t kSchemaVersion = 4;

constexpr const char* kAddRejections = R"sql(
CREATE TABLE rejections (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  recording TEXT NOT NULL,
  method TEXT NOT NULL,
  t0 REAL NOT NULL,
  t1 REAL NOT NULL,
  annotator TEXT NOT NULL,
  time TEXT NOT NULL,
  checksum TEXT NOT NULL);
CREATE INDEX rejections_by_recording ON rejections (recording, method);
)sql";

// How long a writer waits for another process's transaction before failing.
constexpr std::chrono::milliseconds kBusyTimeout(5000);

constexpr const char* kCreateSchemaVersion1 = R"sql(
CREATE TABLE store_schema (version INTEGER NOT NULL);
CREATE TABLE labels (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  recording TEXT NOT NULL,
  t0 REAL NOT NULL,
  t1 REAL NOT NULL,
  region TEXT NOT NULL,
  class TEXT NOT NULL,
  annotator TEXT NOT NULL,
  source TEXT NOT NULL,
  confidence REAL NOT NULL,
  note TEXT NOT NULL,
  created TEXT NOT NULL,
  modified TEXT NOT NULL,
  CHECK (t0 < t1 AND confidence BETWEEN 0 AND 1));
CREATE INDEX labels_by_time ON labels (recording, t0, id);
CREATE TABLE classes (
  skin TEXT NOT NULL,
  position INTEGER NOT NULL,
  name TEXT NOT NULL,
  PRIMARY KEY (skin, position),
  UNIQUE (skin, name));
CREATE TABLE journal (
  sequence INTEGER PRIMARY KEY AUTOINCREMENT,
  batch INTEGER NOT NULL,
  time TEXT NOT NULL,
  annotator TEXT NOT NULL,
  action TEXT NOT NULL,
  label_id INTEGER NOT NULL,
  before_json TEXT NOT NULL,
  after_json TEXT NOT NULL,
  undone INTEGER NOT NULL DEFAULT 0,
  undone_by INTEGER);
CREATE INDEX journal_by_batch ON journal (batch);
CREATE INDEX journal_by_undo ON journal (undone_by);
)sql";

// Creates the current schema in an empty database, inside the caller's transaction.
void create_schema(sqlite3* database, const std::string& path) {
  sqlite::execute(database, path, kCreateSchemaVersion1);
  label_rows::add_checksums(database, path);
  sqlite::execute(database, path, kAddRejections);
  label_rows::add_revisions(database, path);
  sqlite::execute(database, path, "INSERT INTO store_schema (version) VALUES (4)");
}

// The schema every store of the current version has: (type, name, table, sql).
using SchemaRows = std::vector<std::array<std::string, 4>>;

SchemaRows read_schema(sqlite3* database, const std::string& path) {
  sqlite::Statement select(database, path,
                           "SELECT type, name, tbl_name, COALESCE(sql, '') FROM sqlite_master "
                           "ORDER BY type, name");
  SchemaRows rows;
  while (select.step())
    rows.push_back({select.text(0), select.text(1), select.text(2), select.text(3)});
  return rows;
}

const SchemaRows& expected_schema() {
  static const SchemaRows rows = [] {
    sqlite3* database = nullptr;
    sqlite3_open(":memory:", &database);
    create_schema(database, ":memory:");
    SchemaRows schema = read_schema(database, ":memory:");
    sqlite3_close(database);
    return schema;
  }();
  return rows;
}

int64_t single_integer(sqlite3* database, const std::string& where, const std::string& sql) {
  sqlite::Statement select(database, where, sql);
  select.step();
  return select.integer(0);
}

// SQLite's own busy timeout sleeps in growing steps up to 100 ms: a writer waiting for another
// that commits often sleeps past one commit after another (label_writers_bench saw its commits
// wait and its view lag by up to ~0.5 s). Retries every millisecond, for at least kBusyTimeout.
int wait_for_lock(void*, int attempts) {
  if (attempts >= static_cast<int>(kBusyTimeout.count())) return 0;
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return 1;
}

// Switching a new database to WAL takes an exclusive lock without calling the
// busy handler, so a second process opening the same new file at that moment
// gets SQLITE_BUSY at once. Retry for as long as the busy timeout would wait.
void enable_wal(sqlite3* database, const std::string& path) {
  const auto deadline = std::chrono::steady_clock::now() + kBusyTimeout;
  for (;;) {
    const int code = sqlite3_exec(database, "PRAGMA journal_mode = WAL", nullptr, nullptr, nullptr);
    if (code == SQLITE_OK) return;
    if ((code & 0xff) != SQLITE_BUSY || std::chrono::steady_clock::now() > deadline)
      sqlite::fail(database, path, "cannot switch to the WAL journal", code);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// A path as the path part of a file: URI (RFC 3986): reserved bytes percent-encoded.
std::string uri_path(const std::string& path) {
  std::string text;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') {
      text += static_cast<char>(c);
    } else {
      char escaped[4];
      std::snprintf(escaped, sizeof(escaped), "%%%02X", c);
      text += escaped;
    }
  }
  return text;
}

// Creates the schema in an empty database, or checks the version of ours and
// upgrades version 1. Returns the version found (the current one for a new store).
int64_t prepare_schema(sqlite3* database, const std::string& path, bool read_only) {
  int64_t found = kSchemaVersion;
  if (read_only) {
    if (single_integer(database, path,
                       "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND "
                       "name = 'store_schema'") == 0)
      throw Error(path, "not a label store (no store_schema table)");
    found = single_integer(database, path, "SELECT MAX(version) FROM store_schema");
    if (found != kSchemaVersion)
      throw Error(path, "label store schema version " + std::to_string(found) +
                            (found == 1 ? " carries no checksums; `tactile upgrade` adds them"
                             : found < kSchemaVersion
                                 ? " is older than this program's; `tactile upgrade` brings it up"
                                 : " is not supported by this program"));
    return found;
  }
  sqlite::Transaction transaction(database, path);
  const bool ours = single_integer(database, path,
                                   "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' "
                                   "AND name = 'store_schema'") > 0;
  if (!ours) {
    if (single_integer(database, path, "SELECT COUNT(*) FROM sqlite_master") > 0)
      throw Error(path, "a SQLite database, but not a label store (no store_schema table)");
    create_schema(database, path);
  } else {
    const int64_t version = single_integer(database, path, "SELECT MAX(version) FROM store_schema");
    found = version;
    if (version > kSchemaVersion)
      throw Error(path, "label store schema version " + std::to_string(version) +
                            " is newer than this program reads (" + std::to_string(kSchemaVersion) +
                            "); update tactile");
    if (version < 1)
      throw Error(path, "label store schema version " + std::to_string(version) + " is invalid");
    if (version == 1) label_rows::add_checksums(database, path);
    if (version <= 2) sqlite::execute(database, path, kAddRejections);
    if (version <= 3) label_rows::add_revisions(database, path);
    if (version < kSchemaVersion)
      sqlite::execute(database, path, "UPDATE store_schema SET version = 4");
  }
  transaction.commit();
  return found;
}

// Inserts a new label (id and times assigned here) and journals it under `by` ("" = the
// label's annotator). `time` "" = now.
int64_t insert_new(sqlite3* database, const std::string& path, Label label, int64_t batch,
                   const std::string& time, const std::string& by = {}) {
  label.id = 0;
  label.revision = 1;
  label.created = label.modified = time.empty() ? label_rows::now_utc() : time;
  label.id = label_rows::store(database, path, label);
  label_rows::write_journal(database, path, batch, by.empty() ? label.annotator : by, "insert",
                            label.id, "", label_rows::state_json(label), label.created);
  return label.id;
}

// Replaces an existing label's values (its creation time kept) and journals it under `by`
// ("" = the label's annotator).
void update_existing(sqlite3* database, const std::string& path, const Label& before,
                     const Label& label, int64_t batch, const std::string& by = {}) {
  Label after = label;
  after.created = before.created;
  after.modified = label_rows::now_utc();
  after.revision = before.revision + 1;
  label_rows::store(database, path, after);
  label_rows::write_journal(database, path, batch, by.empty() ? after.annotator : by, "update",
                            after.id, label_rows::state_json(before),
                            label_rows::state_json(after));
}

// Deletes an existing label and journals it.
void delete_existing(sqlite3* database, const std::string& path, const Label& label,
                     const std::string& annotator, int64_t batch) {
  label_rows::erase(database, path, label.id);
  label_rows::write_journal(database, path, batch, annotator.empty() ? label.annotator : annotator,
                            "delete", label.id, label_rows::state_json(label), "");
}

}  // namespace

//---- Opening

LabelStore::LabelStore(const std::string& path, OpenMode mode) : path_(path) {
  if (mode != OpenMode::kCreate && !std::filesystem::exists(path))
    throw Error(path, "no such label database");
  const bool read_only = mode == OpenMode::kReadOnly;
  int flags = (read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE) | SQLITE_OPEN_FULLMUTEX;
  if (mode == OpenMode::kCreate) flags |= SQLITE_OPEN_CREATE;
  // Read-only and no write-ahead log beside the file: the file is the whole store,
  // so SQLite may treat it as immutable and create no -wal or -shm file beside it.
  std::string name = path;
  if (read_only && !std::filesystem::exists(path + "-wal")) {
    flags |= SQLITE_OPEN_URI;
    name = "file:" + uri_path(std::filesystem::absolute(path).string()) + "?immutable=1";
  }
  const int code = sqlite3_open_v2(name.c_str(), &database_, flags, nullptr);
  try {
    if (code != SQLITE_OK) sqlite::fail(database_, path_, "cannot open", code);
    sqlite3_extended_result_codes(database_, 1);
    // Another process writing waits up to 5 s for us, and we for it.
    sqlite3_busy_handler(database_, wait_for_lock, nullptr);
    if (!read_only) {
      // The first read of the file: a file that is not a database fails here.
      enable_wal(database_, path_);
      // WAL with synchronous=NORMAL survives a killed process but may lose the last
      // commits on power loss; FULL syncs the WAL at every commit, so an edit that
      // returned is on disk.
      sqlite::execute(database_, path_, "PRAGMA synchronous = FULL");
    }
    opened_version_ = prepare_schema(database_, path_, read_only);
    known_sequence_ = last_sequence();
  } catch (...) {
    sqlite3_close_v2(database_);
    database_ = nullptr;
    throw;
  }
}

LabelStore::~LabelStore() { sqlite3_close_v2(database_); }

LabelStore::LabelStore(LabelStore&& other) noexcept
    : database_(std::exchange(other.database_, nullptr)),
      path_(std::move(other.path_)),
      fixed_time_(std::move(other.fixed_time_)),
      problems_(std::move(other.problems_)),
      opened_version_(other.opened_version_),
      known_sequence_(other.known_sequence_),
      others_commits_(other.others_commits_) {}

LabelStore& LabelStore::operator=(LabelStore&& other) noexcept {
  if (this != &other) {
    sqlite3_close_v2(database_);
    database_ = std::exchange(other.database_, nullptr);
    path_ = std::move(other.path_);
    fixed_time_ = std::move(other.fixed_time_);
    problems_ = std::move(other.problems_);
    opened_version_ = other.opened_version_;
    known_sequence_ = other.known_sequence_;
    others_commits_ = other.others_commits_;
  }
  return *this;
}

std::string StoreProblem::where(const std::string& path) const {
  std::string text = path + ": " + table;
  if (row != 0) text += " row " + std::to_string(row);
  if (!field.empty())
    text += (table == "digests" ? " of " : table == "schema" ? ", " : " field ") + field;
  return text;
}

std::vector<StoreProblem> LabelStore::check() const {
  const std::string integrity = integrity_check();
  if (integrity != "ok") note_problems({StoreProblem{"database", 0, "", integrity}});
  // Reads parse only what they use of the schema: compare it whole with the one
  // every store of this version has (a damaged constraint would fail only writes).
  const SchemaRows& expected = expected_schema();
  const SchemaRows actual = read_schema(database_, path_);
  for (const auto& row : expected)
    if (std::find(actual.begin(), actual.end(), row) == actual.end())
      note_problems({StoreProblem{"schema", 0, row[0] + " " + row[1], "missing or damaged"}});
  for (const auto& row : actual)
    if (std::find(expected.begin(), expected.end(), row) == expected.end())
      note_problems(
          {StoreProblem{"schema", 0, row[0] + " " + row[1], "not part of a label store"}});
  list();
  journal(-1);
  std::vector<std::string> recordings;
  {
    sqlite::Statement select(database_, path_, "SELECT DISTINCT recording FROM rejections");
    while (select.step()) recordings.push_back(select.text(0));
  }
  for (const std::string& recording : recordings) rejections(recording);
  return problems_;
}

const std::string& LabelStore::path() const { return path_; }

std::string LabelStore::integrity_check() const {
  sqlite::Statement check(database_, path_, "PRAGMA integrity_check");
  std::string report;
  while (check.step()) {
    if (!report.empty()) report += '\n';
    report += check.text(0);
  }
  return report;
}

//---- Edits

int64_t LabelStore::add(const Label& label) {
  label_rows::validate(label, path_ + " new label");
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const int64_t id =
      insert_new(database_, path_, label, label_rows::next_batch(database_, path_), fixed_time_);
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
  return id;
}

std::vector<int64_t> LabelStore::add_many(const std::vector<Label>& labels) {
  // Validate everything first: one bad label rejects the whole batch.
  for (size_t i = 0; i < labels.size(); ++i)
    label_rows::validate(labels[i], path_ + " new label " + std::to_string(i + 1) + " of " +
                                        std::to_string(labels.size()));
  std::vector<int64_t> ids;
  if (labels.empty()) return ids;
  ids.reserve(labels.size());
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const int64_t batch = label_rows::next_batch(database_, path_);
  for (const Label& label : labels)
    ids.push_back(insert_new(database_, path_, label, batch, fixed_time_));
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
  return ids;
}

void LabelStore::update(const Label& label) {
  const std::string where = label_rows::where_label(path_, label.id);
  label_rows::validate(label, where);
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const Label before = label_rows::require_seen(database_, path_, ref_of(label), "update");
  update_existing(database_, path_, before, label, label_rows::next_batch(database_, path_));
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
}

void LabelStore::remove(const LabelRef& label, const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const Label before = label_rows::require_seen(database_, path_, label, "remove");
  delete_existing(database_, path_, before, annotator, label_rows::next_batch(database_, path_));
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
}

int64_t LabelStore::remove_where(const LabelFilter& filter, const std::string& annotator) {
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const label_rows::FilterClause clause = label_rows::filter_clause(filter);
  std::vector<Label> doomed;
  {
    sqlite::Statement select(database_, path_,
                             std::string("SELECT ") + label_rows::kColumns + " FROM labels" +
                                 clause.sql + " ORDER BY recording, t0, id");
    clause.bind(select);
    const label_rows::KnownClasses classes = label_rows::known_classes(database_, path_);
    while (select.step())
      doomed.push_back(label_rows::require(label_rows::read_label(select, classes), path_));
  }
  if (doomed.empty()) return 0;
  const int64_t batch = label_rows::next_batch(database_, path_);
  for (const Label& label : doomed) delete_existing(database_, path_, label, annotator, batch);
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
  return static_cast<int64_t>(doomed.size());
}

std::vector<int64_t> LabelStore::apply(const LabelEdit& edit, const std::string& by) {
  const std::string what = path_ + " edit by " + (by.empty() ? std::string("(nobody)") : by);
  for (size_t i = 0; i < edit.add.size(); ++i)
    label_rows::validate(edit.add[i], what + ", new label " + std::to_string(i + 1) + " of " +
                                          std::to_string(edit.add.size()));
  for (const Label& label : edit.update)
    label_rows::validate(label, label_rows::where_label(path_, label.id));
  std::vector<int64_t> ids;
  if (edit.empty()) return ids;
  sqlite::Transaction transaction(database_, path_);
  note_others_commits();
  const int64_t batch = label_rows::next_batch(database_, path_);
  // Any refusal below throws before the commit: the whole edit or nothing.
  for (const LabelRef& seen : edit.remove) {
    const Label before = label_rows::require_seen(database_, path_, seen, "remove");
    delete_existing(database_, path_, before, by, batch);
  }
  for (const LabelRef& seen : edit.reject) {
    // The suggestion goes and its span is remembered, journalled as a "reject": its undo
    // brings the suggestion back and forgets the rejection.
    const int64_t id = seen.id;
    const std::optional<Label> suggestion =
        label_rows::require_seen(database_, path_, seen, "reject");
    const std::string where = label_rows::where_label(path_, id);
    if (suggestion->source != LabelSource::kSegmenter)
      throw Error(where, "only a segmenter's suggestion can be rejected");
    label_rows::remember_rejection(database_, path_, *suggestion, by);
    label_rows::erase(database_, path_, id);
    label_rows::write_journal(database_, path_, batch, by, "reject", id,
                              label_rows::state_json(suggestion), "");
  }
  for (const Label& label : edit.update) {
    const Label before = label_rows::require_seen(database_, path_, ref_of(label), "update");
    update_existing(database_, path_, before, label, batch, by);
  }
  ids.reserve(edit.add.size());
  for (const Label& label : edit.add)
    ids.push_back(insert_new(database_, path_, label, batch, fixed_time_, by));
  label_rows::clear_redo_chain(database_, path_);
  note_own_commit();
  transaction.commit();
  return ids;
}

//---- Queries

std::optional<Label> LabelStore::get(int64_t id) const {
  return label_rows::load(database_, path_, id);
}

std::vector<Label> LabelStore::list(const LabelFilter& filter) const {
  const label_rows::FilterClause clause = label_rows::filter_clause(filter);
  sqlite::Statement select(database_, path_,
                           std::string("SELECT ") + label_rows::kColumns + " FROM labels" +
                               clause.sql + " ORDER BY recording, t0, id");
  clause.bind(select);
  const label_rows::KnownClasses classes = label_rows::known_classes(database_, path_);
  // A read of whole recordings can be checked against their digests.
  const bool whole = !filter.region && !filter.class_name && !filter.source && !filter.annotator &&
                     !filter.overlapping_t0 && !filter.overlapping_t1;
  std::map<std::string, label_rows::Digest> found;
  if (whole && filter.recording) found[label_rows::label_scope(*filter.recording)];
  std::vector<StoreProblem> problems;
  std::vector<Label> labels;
  while (select.step()) {
    label_rows::CheckedLabel row = label_rows::read_label(select, classes);
    label_rows::Digest& digest = found[label_rows::label_scope(row.recording)];
    ++digest.rows;
    digest.sum += row_checksum::row_hash(row.id, row.checksum);
    if (row.problem)
      problems.push_back(*row.problem);
    else
      labels.push_back(std::move(*row.label));
  }
  if (whole) {
    const std::string prefix =
        filter.recording ? label_rows::label_scope(*filter.recording) : "labels:";
    std::map<std::string, label_rows::Digest> stored =
        label_rows::read_digests(database_, prefix, problems);
    // A prefix also matches longer recording names: keep the one asked for.
    if (filter.recording)
      std::erase_if(stored, [&](const auto& entry) { return entry.first != prefix; });
    label_rows::compare_digests(found, stored, true, problems);
  }
  note_problems(problems);
  return labels;
}

void LabelStore::note_problems(const std::vector<StoreProblem>& problems) const {
  for (const StoreProblem& problem : problems) {
    const bool known =
        std::any_of(problems_.begin(), problems_.end(), [&](const StoreProblem& seen) {
          return seen.table == problem.table && seen.row == problem.row &&
                 seen.field == problem.field;
        });
    if (!known) problems_.push_back(problem);
  }
}

int64_t LabelStore::count(const std::string& recording) const {
  if (recording.empty()) return single_integer(database_, path_, "SELECT COUNT(*) FROM labels");
  sqlite::Statement select(database_, path_, "SELECT COUNT(*) FROM labels WHERE recording = ?");
  select.bind(1, recording);
  select.step();
  return select.integer(0);
}

//---- Suggestions

void LabelStore::reject(const LabelRef& suggestion, const std::string& annotator) {
  LabelEdit edit;
  edit.reject = {suggestion};
  apply(edit, annotator);
}

std::vector<Rejection> LabelStore::rejections(const std::string& recording) const {
  sqlite::Statement select(database_, path_,
                           "SELECT id, recording, method, t0, t1, annotator, time, checksum FROM "
                           "rejections WHERE recording = ? ORDER BY t0, id");
  select.bind(1, recording);
  std::vector<Rejection> found;
  std::vector<StoreProblem> problems;
  while (select.step()) {
    Rejection rejection{select.integer(0), select.text(1), select.text(2), select.real(3),
                        select.real(4),    select.text(5), select.text(6)};
    const auto wrong = row_checksum::mismatches(
        "rejections", rejection.id, label_rows::rejection_fields(rejection), select.text(7));
    if (!wrong.empty()) {
      problems.push_back(
          {"rejections", rejection.id, wrong.front(), "value does not match its checksum"});
      continue;
    }
    found.push_back(std::move(rejection));
  }
  note_problems(problems);
  return found;
}

//---- Class vocabulary

void LabelStore::set_classes(const std::string& skin, const std::vector<std::string>& classes) {
  const std::string where = path_ + " classes of skin '" + skin + "'";
  if (skin.empty()) throw Error(path_ + " classes", "skin name is empty");
  std::set<std::string> seen;
  for (const std::string& name : classes) {
    if (name.empty()) throw Error(where, "a class name is empty");
    if (!seen.insert(name).second) throw Error(where, "class '" + name + "' is listed twice");
  }
  sqlite::Transaction transaction(database_, where);
  sqlite::Statement clear(database_, where, "DELETE FROM classes WHERE skin = ?");
  clear.bind(1, skin);
  clear.run();
  sqlite::Statement insert(database_, where,
                           "INSERT INTO classes (skin, position, name) VALUES (?, ?, ?)");
  for (size_t position = 0; position < classes.size(); ++position) {
    insert.reset();
    insert.bind(1, skin).bind(2, static_cast<int64_t>(position)).bind(3, classes[position]);
    insert.run();
  }
  transaction.commit();
}

std::vector<std::string> LabelStore::classes(const std::string& skin) const {
  sqlite::Statement select(database_, path_,
                           "SELECT name FROM classes WHERE skin = ? ORDER BY position");
  select.bind(1, skin);
  std::vector<std::string> names;
  while (select.step()) names.push_back(select.text(0));
  return names;
}

}  // namespace tactile
