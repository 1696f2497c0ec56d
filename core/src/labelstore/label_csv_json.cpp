#include "tactile/labelstore/label_csv_json.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "label_rows.h"
#include "tactile/error.h"
#include "tactile/io/csv_text.h"

namespace tactile {

namespace {

constexpr const char* kHeader[] = {"id",         "recording", "t0",        "t1",
                                   "region",     "class",     "annotator", "source",
                                   "confidence", "note",      "created",   "modified"};
constexpr size_t kFields = std::size(kHeader);

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot read the file");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// One RFC 4180 record: its fields and the line it starts on.
struct Record {
  std::vector<std::string> fields;
  int64_t line = 0;
};

std::vector<Record> csv_records(const std::string& text, const std::string& path) {
  std::vector<Record> records;
  Record record;
  std::string field;
  bool quoted = false, in_quotes = false, field_started = false;
  int64_t line = 1;
  record.line = 1;
  auto end_field = [&] {
    record.fields.push_back(field);
    field.clear();
    quoted = in_quotes = field_started = false;
  };
  auto end_record = [&] {
    end_field();
    if (!(record.fields.size() == 1 && record.fields[0].empty())) records.push_back(record);
    record = Record{};
    record.line = line;
  };
  for (size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (in_quotes) {
      if (c == '"' && at + 1 < text.size() && text[at + 1] == '"') {
        field += '"';
        ++at;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"') {
      if (field_started || quoted)
        throw Error(path + ":" + std::to_string(line), "a quote inside an unquoted field");
      quoted = in_quotes = field_started = true;
    } else if (c == ',') {
      end_field();
    } else if (c == '\r' && at + 1 < text.size() && text[at + 1] == '\n') {
      continue;  // CRLF: the \n ends the record
    } else if (c == '\n') {
      ++line;
      end_record();
    } else {
      if (quoted) throw Error(path + ":" + std::to_string(line), "text after a closing quote");
      field += c;
      field_started = true;
    }
  }
  if (in_quotes) throw Error(path + ":" + std::to_string(record.line), "a quote is never closed");
  if (field_started || quoted || !record.fields.empty()) end_record();
  return records;
}

}  // namespace

std::vector<Label> read_labels_csv(const std::string& path) {
  const std::vector<Record> records = csv_records(read_all(path), path);
  if (records.empty()) throw Error(path, "empty file: expected the header of `labels export`");
  const Record& header = records.front();
  if (header.fields.size() != kFields ||
      !std::equal(header.fields.begin(), header.fields.end(), std::begin(kHeader)))
    throw Error(path + ":1",
                "expected the header id,recording,t0,t1,region,class,annotator,"
                "source,confidence,note,created,modified");
  std::vector<Label> labels;
  for (size_t k = 1; k < records.size(); ++k) {
    const Record& record = records[k];
    const std::string where = path + ":" + std::to_string(record.line);
    if (record.fields.size() != kFields)
      throw Error(where, std::to_string(record.fields.size()) + " fields, expected " +
                             std::to_string(kFields));
    const auto& f = record.fields;
    Label label;
    label.recording = f[1];
    label.t0 = csv::parse_double(f[2], path, record.line, 3);
    label.t1 = csv::parse_double(f[3], path, record.line, 4);
    label.region = f[4];
    label.class_name = f[5];
    label.annotator = f[6];
    try {
      label.source = parse_label_source(f[7]);
    } catch (const Error& error) {
      throw Error(where, error.message());
    }
    label.confidence = csv::parse_double(f[8], path, record.line, 9);
    label.note = f[9];
    label_rows::validate(label, where);
    labels.push_back(std::move(label));
  }
  return labels;
}

std::vector<Label> read_labels_json(const std::string& path) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(read_all(path));
  } catch (const nlohmann::json::exception& error) {
    throw Error(path, std::string("not JSON: ") + error.what());
  }
  if (!document.is_object() || !document.contains("labels") || !document["labels"].is_array())
    throw Error(path, "expected {\"labels\": [...]} as `labels export --json` writes");
  std::vector<Label> labels;
  const nlohmann::json& items = document["labels"];
  for (size_t k = 0; k < items.size(); ++k) {
    const std::string where = path + " label " + std::to_string(k + 1);
    nlohmann::json item = items[k];
    // Ids and times are the store's to assign; accept what export wrote or nothing.
    if (item.is_object()) {
      for (const char* field : {"id", "created", "modified"})
        if (!item.contains(field)) item[field] = field[0] == 'i' ? nlohmann::json(0) : "";
      if (!item.contains("note")) item["note"] = "";
      if (!item.contains("confidence")) item["confidence"] = 1.0;
    }
    Label label = label_rows::from_json(item, where);
    label_rows::validate(label, where);
    labels.push_back(std::move(label));
  }
  return labels;
}

}  // namespace tactile
