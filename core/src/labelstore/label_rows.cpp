#include "label_rows.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "row_checksum.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::label_rows {

namespace {

using row_checksum::Field;

// The fields a labels row's checksum covers: schema 4 added the revision at the end (a row
// of schema 2 or 3 is checked without it, by add_checksums and add_revisions).
std::vector<Field> label_fields(const Label& label, const std::string& source,
                                bool with_revision = true) {
  std::vector<Field> fields = {{"recording", label.recording},
                               {"t0", label.t0},
                               {"t1", label.t1},
                               {"region", label.region},
                               {"class", label.class_name},
                               {"annotator", label.annotator},
                               {"source", source},
                               {"confidence", label.confidence},
                               {"note", label.note},
                               {"created", label.created},
                               {"modified", label.modified}};
  if (with_revision) fields.push_back({"revision", label.revision});
  return fields;
}

std::string label_checksum(const Label& label) {
  return row_checksum::compute("labels", label.id,
                               label_fields(label, std::string(to_string(label.source))));
}

}  // namespace

StoreProblem row_problem(const char* table, int64_t row, std::string field, std::string what) {
  return StoreProblem{table, row, std::move(field), std::move(what)};
}

std::optional<StoreProblem> checksum_problem(const char* table, int64_t row,
                                             const std::vector<Field>& fields,
                                             const std::string& stored) {
  const std::vector<std::string> fields_wrong =
      row_checksum::mismatches(table, row, fields, stored);
  if (fields_wrong.empty()) return std::nullopt;
  if (fields_wrong.size() == fields.size())
    return row_problem(table, row, "",
                       "no field matches the row's checksum (row id or checksum damaged)");
  std::string names;
  for (const std::string& name : fields_wrong) names += (names.empty() ? "" : ", ") + name;
  return row_problem(table, row, fields_wrong.front(),
                     "value does not match its checksum (damaged: " + names + ")");
}

std::string now_utc() {
  const auto now = std::chrono::system_clock::now();
  const auto milliseconds =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[40];
  const size_t length = std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &utc);
  char fraction[8];
  std::snprintf(fraction, sizeof(fraction), ".%03dZ", static_cast<int>(milliseconds));
  return std::string(text, length) + fraction;
}

std::string where_label(const std::string& path, int64_t id) {
  return path + " label " + std::to_string(id);
}

void validate(const Label& label, const std::string& where) {
  if (label.recording.empty()) throw Error(where, "recording is empty");
  if (!std::isfinite(label.t0)) throw Error(where, "t0 is not a finite number");
  if (!std::isfinite(label.t1)) throw Error(where, "t1 is not a finite number");
  if (!(label.t0 < label.t1))
    throw Error(where, "t0 (" + shortest_text(label.t0) + " s) must be before t1 (" +
                           shortest_text(label.t1) + " s)");
  if (label.region.empty()) throw Error(where, "region is empty (use \"all\" for the whole skin)");
  if (label.class_name.empty()) throw Error(where, "class is empty");
  // Written this way round so that NaN fails too.
  if (!(label.confidence >= 0.0 && label.confidence <= 1.0))
    throw Error(where, "confidence " + shortest_text(label.confidence) + " is outside [0, 1]");
}

bool is_iso_time(const std::string& text) {
  // YYYY-MM-DDTHH:MM:SS[.fff]Z
  if (text.size() < 20 || text.back() != 'Z') return false;
  const char* pattern = "dddd-dd-ddTdd:dd:dd";
  for (size_t index = 0; pattern[index] != '\0'; ++index) {
    const char expected = pattern[index];
    const char actual = text[index];
    if (expected == 'd' ? (actual < '0' || actual > '9') : actual != expected) return false;
  }
  const size_t rest = 19;
  if (text.size() > rest + 1) {
    if (text[rest] != '.' || text.size() < rest + 3) return false;
    for (size_t index = rest + 1; index + 1 < text.size(); ++index)
      if (text[index] < '0' || text[index] > '9') return false;
  }
  auto number = [&text](size_t first, size_t count) {
    return std::stoi(text.substr(first, count));
  };
  const int month = number(5, 2), day = number(8, 2), hour = number(11, 2), minute = number(14, 2),
            second = number(17, 2);
  return month >= 1 && month <= 12 && day >= 1 && day <= 31 && hour < 24 && minute < 60 &&
         second <= 60;
}

KnownClasses known_classes(sqlite3* database, const std::string& path) {
  sqlite::Statement select(database, path,
                           "SELECT name FROM classes UNION SELECT name FROM label_classes");
  KnownClasses names;
  while (select.step()) names.insert(select.text(0));
  return names;
}

namespace {

// The kColumns of the current row as stored; the source stays text until checked.
Label label_from_row(const sqlite::Statement& statement, std::string& source) {
  Label label;
  label.id = statement.integer(0);
  label.recording = statement.text(1);
  label.t0 = statement.real(2);
  label.t1 = statement.real(3);
  label.region = statement.text(4);
  label.class_name = statement.text(5);
  label.annotator = statement.text(6);
  source = statement.text(7);
  label.confidence = statement.real(8);
  label.note = statement.text(9);
  label.created = statement.text(10);
  label.modified = statement.text(11);
  return label;
}

}  // namespace

CheckedLabel read_label(const sqlite::Statement& statement, const KnownClasses& classes) {
  CheckedLabel row;
  std::string source;
  Label label = label_from_row(statement, source);
  row.id = label.id;
  row.recording = label.recording;
  row.checksum = statement.text(12);
  label.revision = statement.integer(13);
  row.problem = checksum_problem("labels", label.id, label_fields(label, source), row.checksum);
  if (row.problem) return row;
  // Intact as written; still, only valid values pass as labels.
  try {
    label.source = parse_label_source(source);
  } catch (const Error& error) {
    row.problem = row_problem("labels", label.id, "source", error.message());
    return row;
  }
  try {
    validate(label, "");
  } catch (const Error& error) {
    row.problem = row_problem("labels", label.id, "", error.message());
    return row;
  }
  if (label.revision < 1)
    row.problem = row_problem("labels", label.id, "revision",
                              std::to_string(label.revision) + " is not a revision (1 or more)");
  else if (classes.count(label.class_name) == 0)
    row.problem = row_problem("labels", label.id, "class",
                              "'" + label.class_name + "' is in no vocabulary of the store");
  else if (!is_iso_time(label.created))
    row.problem =
        row_problem("labels", label.id, "created", "'" + label.created + "' is not a time");
  else if (!is_iso_time(label.modified))
    row.problem =
        row_problem("labels", label.id, "modified", "'" + label.modified + "' is not a time");
  else
    row.label = std::move(label);
  return row;
}

Error problem_error(const StoreProblem& problem, const std::string& path) {
  return Error(problem.where(path), problem.what + "; the row is left as it is");
}

Label require(const CheckedLabel& row, const std::string& path) {
  if (row.problem) throw problem_error(*row.problem, path);
  return *row.label;
}

nlohmann::json to_json(const Label& label) {
  return nlohmann::json{{"id", label.id},
                        {"recording", label.recording},
                        {"t0", label.t0},
                        {"t1", label.t1},
                        {"region", label.region},
                        {"class", label.class_name},
                        {"annotator", label.annotator},
                        {"source", to_string(label.source)},
                        {"confidence", label.confidence},
                        {"note", label.note},
                        {"created", label.created},
                        {"modified", label.modified}};
}

Label from_json(const nlohmann::json& object, const std::string& where) {
  try {
    Label label;
    label.id = object.at("id").get<int64_t>();
    label.recording = object.at("recording").get<std::string>();
    label.t0 = object.at("t0").get<double>();
    label.t1 = object.at("t1").get<double>();
    label.region = object.at("region").get<std::string>();
    label.class_name = object.at("class").get<std::string>();
    label.annotator = object.at("annotator").get<std::string>();
    label.source = parse_label_source(object.at("source").get<std::string>());
    label.confidence = object.at("confidence").get<double>();
    label.note = object.at("note").get<std::string>();
    label.created = object.at("created").get<std::string>();
    label.modified = object.at("modified").get<std::string>();
    // Journal rows of schema 4 carry the revision; the export and older rows do not.
    label.revision = object.value("revision", int64_t{0});
    return label;
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, std::string("malformed label JSON: ") + error.what());
  } catch (const Error& error) {
    throw Error(where, error.message());
  }
}

//---- Filters

void FilterClause::bind(sqlite::Statement& statement) const {
  int index = 1;
  for (const auto& parameter : parameters) {
    if (const auto* text = std::get_if<std::string>(&parameter))
      statement.bind(index++, *text);
    else
      statement.bind(index++, std::get<double>(parameter));
  }
}

FilterClause filter_clause(const LabelFilter& filter) {
  FilterClause clause;
  std::vector<std::string> conditions;
  auto add = [&](const char* condition, std::variant<std::string, double> value) {
    conditions.emplace_back(condition);
    clause.parameters.push_back(std::move(value));
  };
  if (filter.recording) add("recording = ?", *filter.recording);
  if (filter.region) add("region = ?", *filter.region);
  if (filter.class_name) add("class = ?", *filter.class_name);
  if (filter.annotator) add("annotator = ?", *filter.annotator);
  if (filter.source) add("source = ?", std::string(to_string(*filter.source)));
  // [t0, t1) meets [a, b) when t0 < b and t1 > a.
  if (filter.overlapping_t0) add("t1 > ?", *filter.overlapping_t0);
  if (filter.overlapping_t1) add("t0 < ?", *filter.overlapping_t1);
  for (size_t i = 0; i < conditions.size(); ++i)
    clause.sql += (i == 0 ? " WHERE " : " AND ") + conditions[i];
  return clause;
}

//---- Rows

std::optional<Label> load(sqlite3* database, const std::string& path, int64_t id) {
  sqlite::Statement select(database, where_label(path, id),
                           std::string("SELECT ") + kColumns + " FROM labels WHERE id = ?");
  select.bind(1, id);
  if (!select.step()) return std::nullopt;
  return require(read_label(select, known_classes(database, path)), path);
}

namespace {

// Takes a row out of its recording's digest; refuses a row that is damaged.
void forget_row(sqlite3* database, const std::string& path, int64_t id) {
  sqlite::Statement select(database, where_label(path, id),
                           std::string("SELECT ") + kColumns + " FROM labels WHERE id = ?");
  select.bind(1, id);
  if (!select.step()) return;
  const CheckedLabel row = read_label(select, known_classes(database, path));
  require(row, path);
  adjust_digest(database, path, label_scope(row.recording), -1,
                0 - row_checksum::row_hash(row.id, row.checksum));
}

}  // namespace

int64_t store(sqlite3* database, const std::string& path, const Label& label) {
  if (label.id != 0) forget_row(database, path, label.id);
  sqlite::Statement upsert(database, where_label(path, label.id),
                           std::string("INSERT OR REPLACE INTO labels (") + kColumns +
                               ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  // Id 0 means "new": a NULL id lets AUTOINCREMENT pick one that was never used,
  // so an id freed by a delete stays free for that label's undo. The checksum
  // covers the id, so a new row gets its checksum once the id is known.
  if (label.id == 0)
    upsert.bind_null(1).bind(13, std::string());
  else
    upsert.bind(1, label.id).bind(13, label_checksum(label));
  upsert.bind(2, label.recording)
      .bind(3, label.t0)
      .bind(4, label.t1)
      .bind(5, label.region)
      .bind(6, label.class_name)
      .bind(7, label.annotator)
      .bind(8, std::string(to_string(label.source)))
      .bind(9, label.confidence)
      .bind(10, label.note)
      .bind(11, label.created)
      .bind(12, label.modified)
      .bind(14, label.revision);
  upsert.run();
  Label stored = label;
  if (stored.id == 0) {
    stored.id = sqlite3_last_insert_rowid(database);
    sqlite::Statement update(database, where_label(path, stored.id),
                             "UPDATE labels SET checksum = ? WHERE id = ?");
    update.bind(1, label_checksum(stored)).bind(2, stored.id);
    update.run();
  }
  adjust_digest(database, path, label_scope(stored.recording), 1,
                row_checksum::row_hash(stored.id, label_checksum(stored)));
  sqlite::Statement known(database, path, "INSERT OR IGNORE INTO label_classes (name) VALUES (?)");
  known.bind(1, stored.class_name);
  known.run();
  return stored.id;
}

void erase(sqlite3* database, const std::string& path, int64_t id) {
  forget_row(database, path, id);
  sqlite::Statement remove(database, where_label(path, id), "DELETE FROM labels WHERE id = ?");
  remove.bind(1, id);
  remove.run();
}

void add_checksums(sqlite3* database, const std::string& path) {
  sqlite::execute(database, path, R"sql(
ALTER TABLE labels ADD COLUMN checksum TEXT NOT NULL DEFAULT '';
ALTER TABLE journal ADD COLUMN checksum TEXT NOT NULL DEFAULT '';
CREATE TABLE digests (scope TEXT PRIMARY KEY, rows INTEGER NOT NULL, sum INTEGER NOT NULL,
                      checksum TEXT NOT NULL);
CREATE TABLE label_classes (name TEXT PRIMARY KEY);
INSERT OR IGNORE INTO label_classes (name) SELECT DISTINCT class FROM labels;
)sql");
  std::vector<std::pair<Label, std::string>> labels;
  {
    // The columns of schema 1 (no revision yet; add_revisions adds it).
    sqlite::Statement select(database, path,
                             "SELECT id, recording, t0, t1, region, class, annotator, source, "
                             "confidence, note, created, modified FROM labels ORDER BY id");
    while (select.step()) {
      std::string source;
      Label label = label_from_row(select, source);
      labels.emplace_back(std::move(label), source);
    }
  }
  sqlite::Statement update(database, path, "UPDATE labels SET checksum = ? WHERE id = ?");
  for (const auto& [label, source] : labels) {
    const std::string checksum =
        row_checksum::compute("labels", label.id, label_fields(label, source, false));
    update.reset();
    update.bind(1, checksum).bind(2, label.id);
    update.run();
    adjust_digest(database, path, label_scope(label.recording), 1,
                  row_checksum::row_hash(label.id, checksum));
  }
  std::vector<std::pair<JournalEntry, std::optional<int64_t>>> entries;
  {
    sqlite::Statement select(database, path,
                             std::string("SELECT ") + kJournalColumns + " FROM journal");
    while (select.step()) {
      std::optional<int64_t> undone_by;
      JournalEntry entry = journal_from_row(select, undone_by);
      entries.emplace_back(std::move(entry), undone_by);
    }
  }
  for (const auto& [entry, undone_by] : entries) seal_journal_row(database, path, entry, undone_by);
}

void add_revisions(sqlite3* database, const std::string& path) {
  sqlite::execute(database, path,
                  "ALTER TABLE labels ADD COLUMN revision INTEGER NOT NULL DEFAULT 1");
  // Every row's checksum gains the revision's CRC, and its recording's digest the new row
  // hash. A row that is damaged already stays as it is (its checksum still names the field).
  struct Row {
    Label label;
    std::string source, checksum;
  };
  std::vector<Row> rows;
  {
    sqlite::Statement select(database, path,
                             std::string("SELECT ") + kColumns + " FROM labels ORDER BY id");
    while (select.step()) {
      Row row;
      row.label = label_from_row(select, row.source);
      row.label.revision = select.integer(13);
      row.checksum = select.text(12);
      rows.push_back(std::move(row));
    }
  }
  sqlite::Statement update(database, path, "UPDATE labels SET checksum = ? WHERE id = ?");
  for (const Row& row : rows) {
    const std::vector<Field> old_fields = label_fields(row.label, row.source, false);
    if (!row_checksum::mismatches("labels", row.label.id, old_fields, row.checksum).empty())
      continue;
    const std::string checksum =
        row_checksum::compute("labels", row.label.id, label_fields(row.label, row.source));
    update.reset();
    update.bind(1, checksum).bind(2, row.label.id);
    update.run();
    adjust_digest(database, path, label_scope(row.label.recording), 0,
                  row_checksum::row_hash(row.label.id, checksum) -
                      row_checksum::row_hash(row.label.id, row.checksum));
  }
}

}  // namespace tactile::label_rows
