#include "label_rows.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "tactile/error.h"

namespace tactile::label_rows {

namespace {

// Shortest text that reads back as the same double, for error messages.
std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace

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
    throw Error(where, "t0 (" + number_text(label.t0) + " s) must be before t1 (" +
                           number_text(label.t1) + " s)");
  if (label.region.empty()) throw Error(where, "region is empty (use \"all\" for the whole skin)");
  if (label.class_name.empty()) throw Error(where, "class is empty");
  // Written this way round so that NaN fails too.
  if (!(label.confidence >= 0.0 && label.confidence <= 1.0))
    throw Error(where, "confidence " + number_text(label.confidence) + " is outside [0, 1]");
}

Label read_label(const sqlite::Statement& statement, const std::string& path) {
  Label label;
  label.id = statement.integer(0);
  label.recording = statement.text(1);
  label.t0 = statement.real(2);
  label.t1 = statement.real(3);
  label.region = statement.text(4);
  label.class_name = statement.text(5);
  label.annotator = statement.text(6);
  const std::string source = statement.text(7);
  try {
    label.source = parse_label_source(source);
  } catch (const Error& error) {
    throw Error(where_label(path, label.id), error.message());
  }
  label.confidence = statement.real(8);
  label.note = statement.text(9);
  label.created = statement.text(10);
  label.modified = statement.text(11);
  return label;
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
  return read_label(select, path);
}

void store(sqlite3* database, const std::string& path, const Label& label) {
  sqlite::Statement upsert(database, where_label(path, label.id),
                           std::string("INSERT OR REPLACE INTO labels (") + kColumns +
                               ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  // Id 0 means "new": a NULL id lets AUTOINCREMENT pick one that was never used,
  // so an id freed by a delete stays free for that label's undo.
  if (label.id == 0)
    upsert.bind_null(1);
  else
    upsert.bind(1, label.id);
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
      .bind(12, label.modified);
  upsert.run();
}

void erase(sqlite3* database, const std::string& path, int64_t id) {
  sqlite::Statement remove(database, where_label(path, id), "DELETE FROM labels WHERE id = ?");
  remove.bind(1, id);
  remove.run();
}

//---- Journal

std::string state_json(const std::optional<Label>& label) {
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

void write_journal(sqlite3* database, const std::string& path, int64_t batch,
                   const std::string& annotator, const std::string& action, int64_t label_id,
                   const std::string& before_json, const std::string& after_json,
                   const std::string& time) {
  sqlite::Statement insert(database, where_label(path, label_id),
                           "INSERT INTO journal (batch, time, annotator, action, label_id, "
                           "before_json, after_json) VALUES (?, ?, ?, ?, ?, ?, ?)");
  insert.bind(1, batch)
      .bind(2, time.empty() ? now_utc() : time)
      .bind(3, annotator)
      .bind(4, action)
      .bind(5, label_id)
      .bind(6, before_json)
      .bind(7, after_json);
  insert.run();
}

void clear_redo_chain(sqlite3* database, const std::string& path) {
  sqlite::execute(database, path,
                  "UPDATE journal SET undone_by = NULL WHERE undone_by IS NOT NULL");
}

}  // namespace tactile::label_rows
