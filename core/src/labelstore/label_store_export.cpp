// The LabelStore's CSV and JSON exports. Both are written atomically (io/atomic_file.h), so a
// failed export never leaves a partial file.
#include <charconv>
#include <nlohmann/json.hpp>

#include "label_rows.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/labelstore/label_csv_json.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// RFC 4180: a field holding a comma, a quote or a line break is quoted, and
// its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char character : text) {
    if (character == '"') quoted += '"';
    quoted += character;
  }
  return quoted + '"';
}

}  // namespace

std::string labels_csv(const std::vector<Label>& labels) {
  std::string text =
      "id,recording,t0,t1,region,class,annotator,source,confidence,note,created,modified\r\n";
  for (const Label& label : labels) {
    std::string line = std::to_string(label.id);
    for (const std::string& field :
         {csv_field(label.recording), shortest_text(label.t0), shortest_text(label.t1),
          csv_field(label.region), csv_field(label.class_name), csv_field(label.annotator),
          std::string(to_string(label.source)), shortest_text(label.confidence),
          csv_field(label.note), csv_field(label.created), csv_field(label.modified)})
      line += "," + field;
    text += line + "\r\n";
  }
  return text;
}

void LabelStore::export_csv(const std::string& path, const LabelFilter& filter) const {
  write_file_atomically(path, labels_csv(list(filter)), "label export");
}

std::string labels_json(const std::vector<Label>& labels) {
  nlohmann::json array = nlohmann::json::array();
  for (const Label& label : labels) array.push_back(label_rows::to_json(label));
  const nlohmann::json document{{"labels", std::move(array)}};
  return document.dump(2) + "\n";
}

nlohmann::json label_json(const Label& label) {
  nlohmann::json object = label_rows::to_json(label);
  if (label.revision != 0) object["revision"] = label.revision;
  return object;
}

Label label_from_json(const nlohmann::json& object, const std::string& where) {
  return label_rows::from_json(object, where);
}

void LabelStore::export_json(const std::string& path, const LabelFilter& filter) const {
  write_file_atomically(path, labels_json(list(filter)), "label export");
}

}  // namespace tactile
