// Reading a SkinLayout from JSON (schema in docs/LAYOUTS.md). Structure errors are reported
// while reading; everything else is left to validate_layout, so a layout built in code and one
// read from a file obey the same rules.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile {

namespace {

using Json = nlohmann::json;

// Reads JSON values of one file, naming the file and the entry in every error.
class Reader {
 public:
  explicit Reader(std::string where) : where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& entry, const std::string& message) const {
    throw Error(where_, entry.empty() ? message : entry + ": " + message);
  }

  void check_object(const Json& value, const std::string& entry) const {
    if (!value.is_object())
      fail(entry, std::string("expected an object, got ") + value.type_name());
  }

  // Unknown keys are typos more often than extensions; reject them so no value is ignored.
  void check_keys(const Json& object, const std::string& entry,
                  std::initializer_list<const char*> allowed) const {
    for (const auto& item : object.items()) {
      bool known = false;
      for (const char* key : allowed) known = known || item.key() == key;
      if (!known) fail(entry, "unknown key " + in_quotes(item.key()));
    }
  }

  const Json& require(const Json& object, const char* key, const std::string& entry) const {
    const auto found = object.find(key);
    if (found == object.end()) fail(entry, std::string("missing required key \"") + key + "\"");
    return *found;
  }

  const Json* optional(const Json& object, const char* key) const {
    const auto found = object.find(key);
    return found == object.end() ? nullptr : &*found;
  }

  std::string text(const Json& value, const std::string& entry, const char* key) const {
    if (!value.is_string()) {
      fail(entry, std::string(key) + " must be a string, got " + value.type_name());
    }
    return value.get<std::string>();
  }

  std::string text_or(const Json& object, const char* key, const std::string& entry,
                      const std::string& fallback) const {
    const Json* value = optional(object, key);
    return value == nullptr ? fallback : text(*value, entry, key);
  }

  // JSON has no NaN: files written by other tools carry it as null or "NaN". Both become NaN
  // here so validate_layout reports it at the entry ("taxel 12: position is NaN").
  double number(const Json& value, const std::string& entry, const std::string& key) const {
    if (value.is_number()) return value.get<double>();
    if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (value.is_string()) {
      const std::string spelled = value.get<std::string>();
      if (spelled == "NaN" || spelled == "nan" || spelled == "NAN") {
        return std::numeric_limits<double>::quiet_NaN();
      }
      if (spelled == "Infinity" || spelled == "inf") return std::numeric_limits<double>::infinity();
      if (spelled == "-Infinity" || spelled == "-inf") {
        return -std::numeric_limits<double>::infinity();
      }
      fail(entry, key + " must be a number, got " + in_quotes(spelled));
    }
    fail(entry, key + " must be a number, got " + value.type_name());
  }

  int64_t whole_number(const Json& value, const std::string& entry, const std::string& key) const {
    if (value.is_number_unsigned()) {
      const uint64_t unsigned_value = value.get<uint64_t>();
      if (unsigned_value > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
        fail(entry, key + " is too large");
      }
      return static_cast<int64_t>(unsigned_value);
    }
    if (value.is_number_integer()) return value.get<int64_t>();
    fail(entry, key + " must be a whole number, got " +
                    (value.is_string() ? in_quotes(value.get<std::string>()) : value.dump()));
  }

  const Json& array(const Json& value, const std::string& entry, const char* key) const {
    if (!value.is_array()) {
      fail(entry, std::string(key) + " must be an array, got " + value.type_name());
    }
    return value;
  }

  // A list of [x, y] pairs: an outline.
  std::vector<Point2> points(const Json& value, const std::string& entry,
                             const std::string& key) const {
    array(value, entry, key.c_str());
    std::vector<Point2> result;
    for (size_t point = 0; point < value.size(); ++point) {
      const Json& pair = value[point];
      const std::string place = key + "[" + std::to_string(point) + "]";
      if (!pair.is_array() || pair.size() != 2) fail(entry, place + " must be a pair [x, y]");
      result.push_back(
          {number(pair[0], entry, place + "[0]"), number(pair[1], entry, place + "[1]")});
    }
    return result;
  }

  std::vector<std::string> strings(const Json& value, const char* key) const {
    array(value, "", key);
    std::vector<std::string> result;
    for (size_t index = 0; index < value.size(); ++index) {
      result.push_back(
          text(value[index], std::string(key) + "[" + std::to_string(index) + "]", "entry"));
    }
    return result;
  }

 private:
  std::string where_;
};

TaxelShape parse_shape(const Reader& reader, const std::string& name, const std::string& entry) {
  for (TaxelShape shape : {TaxelShape::kRectangle, TaxelShape::kHexagon, TaxelShape::kStripe,
                           TaxelShape::kPolygon, TaxelShape::kCircle}) {
    if (name == taxel_shape_name(shape)) return shape;
  }
  reader.fail(entry, "unknown shape " + in_quotes(name) + " (rect, hex, stripe, polygon, circle)");
}

std::string describe_taxel(int64_t id, const std::string& name) {
  std::string text = "taxel " + std::to_string(id);
  if (!name.empty() && name != std::to_string(id)) text.append(" ").append(in_quotes(name));
  return text;
}

Taxel parse_taxel(const Reader& reader, const Json& value, size_t index, const SkinLayout& layout,
                  const std::unordered_map<std::string, int>& channel_by_name) {
  std::string entry = "taxels[" + std::to_string(index) + "]";
  reader.check_object(value, entry);
  Taxel taxel;
  taxel.id = reader.whole_number(reader.require(value, "id", entry), entry, "id");
  taxel.name = reader.text_or(value, "name", entry, std::to_string(taxel.id));
  entry = describe_taxel(taxel.id, taxel.name);
  reader.check_keys(
      value, entry,
      {"id", "name", "body_part", "x", "y", "w", "h", "area", "shape", "outline", "channels"});
  taxel.body_part = reader.text_or(value, "body_part", entry, "");
  taxel.position.x = reader.number(reader.require(value, "x", entry), entry, "x");
  taxel.position.y = reader.number(reader.require(value, "y", entry), entry, "y");
  taxel.size.x = reader.number(reader.require(value, "w", entry), entry, "w");
  taxel.size.y = reader.number(reader.require(value, "h", entry), entry, "h");
  taxel.area = reader.number(reader.require(value, "area", entry), entry, "area");
  taxel.shape = parse_shape(reader, reader.text_or(value, "shape", entry, "rect"), entry);
  if (const Json* outline = reader.optional(value, "outline")) {
    taxel.outline = reader.points(*outline, entry, "outline");
  }
  const Json& channels = reader.require(value, "channels", entry);
  if (!channels.is_object()) {
    reader.fail(entry, std::string("channels must be an object {modality: channel name}, got ") +
                           channels.type_name());
  }
  taxel.channels.assign(layout.modalities.size(), -1);
  for (const auto& item : channels.items()) {
    const int slot = layout.modality_index(item.key());
    if (slot < 0) reader.fail(entry, "unknown modality " + in_quotes(item.key()));
    const std::string channel_name = reader.text(item.value(), entry, "channel name");
    const auto found = channel_by_name.find(channel_name);
    if (found == channel_by_name.end()) {
      reader.fail(entry, "unknown channel " + in_quotes(channel_name));
    }
    taxel.channels[static_cast<size_t>(slot)] = found->second;
  }
  return taxel;
}

Group parse_group(const Reader& reader, const Json& value, size_t index) {
  std::string entry = "groups[" + std::to_string(index) + "]";
  reader.check_object(value, entry);
  Group group;
  group.id = reader.text(reader.require(value, "id", entry), entry, "id");
  entry = "group " + in_quotes(group.id);
  reader.check_keys(value, entry, {"id", "kind", "name", "taxels"});
  group.kind = reader.text(reader.require(value, "kind", entry), entry, "kind");
  group.name = reader.text_or(value, "name", entry, group.id);
  const Json& taxels = reader.array(reader.require(value, "taxels", entry), entry, "taxels");
  for (size_t member = 0; member < taxels.size(); ++member) {
    group.taxels.push_back(
        reader.whole_number(taxels[member], entry, "taxels[" + std::to_string(member) + "]"));
  }
  return group;
}

// Line and column (1-based) of a byte offset, for syntax errors.
std::pair<size_t, size_t> line_and_column(const std::string& text, size_t byte) {
  size_t line = 1;
  size_t column = 1;
  for (size_t index = 0; index < byte && index < text.size(); ++index) {
    if (text[index] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

Json parse_text(const std::string& text, const std::string& where) {
  // nlohmann keeps the last of two equal keys; a duplicated key would silently drop a value.
  std::vector<std::set<std::string>> open_objects;
  const auto reject_duplicate_keys = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) open_objects.emplace_back();
    if (event == Json::parse_event_t::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == Json::parse_event_t::key && !open_objects.empty() &&
        !open_objects.back().insert(parsed.get<std::string>()).second) {
      throw Error(where, "duplicate key " + in_quotes(parsed.get<std::string>()));
    }
    return true;
  };
  try {
    return Json::parse(text, reject_duplicate_keys);
  } catch (const Json::parse_error& error) {
    // error.byte is 1-based and points just past the offending character.
    const auto [line, column] = line_and_column(text, error.byte == 0 ? 0 : error.byte - 1);
    std::string message = error.what();
    const size_t detail = message.find(": ", message.find("parse error"));
    if (detail != std::string::npos) message = message.substr(detail + 2);
    throw Error(where + ":" + std::to_string(line) + " column " + std::to_string(column),
                "JSON syntax error: " + message);
  } catch (const Json::exception& error) {
    // A number too large for a double (1e400) is an out_of_range, not a parse_error (the
    // same escape the fuzzer found in the JSON frames reader).
    throw Error(where, std::string("unreadable JSON: ") + error.what());
  }
}

}  // namespace

SkinLayout parse_layout_json(const std::string& text, const std::string& where) {
  const Json root = parse_text(text, where);
  const Reader reader(where);
  reader.check_object(root, "");
  reader.check_keys(
      root, "",
      {"id", "name", "description", "map_unit", "sample_rate_hz", "modalities", "display",
       "channels", "taxels", "groups", "disjoint_kinds", "classes", "outline"});
  SkinLayout layout;
  layout.id = reader.text(reader.require(root, "id", ""), "", "id");
  layout.name = reader.text(reader.require(root, "name", ""), "", "name");
  layout.description = reader.text_or(root, "description", "", "");
  layout.map_unit = reader.text_or(root, "map_unit", "", "mm");
  if (layout.map_unit != "mm") {
    reader.fail("", "map_unit must be \"mm\" (areas are mm^2), got " + in_quotes(layout.map_unit));
  }
  if (const Json* rate = reader.optional(root, "sample_rate_hz")) {
    layout.sample_rate_hz = reader.number(*rate, "", "sample_rate_hz");
  }
  layout.modalities = reader.strings(reader.require(root, "modalities", ""), "modalities");
  layout.display_modality = layout.modalities.empty() ? "" : layout.modalities.front();
  if (const Json* display = reader.optional(root, "display")) {
    reader.check_object(*display, "display");
    reader.check_keys(*display, "display", {"modality", "min", "max"});
    layout.display_modality =
        reader.text_or(*display, "modality", "display", layout.display_modality);
    if (const Json* low = reader.optional(*display, "min")) {
      layout.display_min = reader.number(*low, "display", "min");
    }
    if (const Json* high = reader.optional(*display, "max")) {
      layout.display_max = reader.number(*high, "display", "max");
    }
  }

  const Json& channels = reader.array(reader.require(root, "channels", ""), "", "channels");
  std::unordered_map<std::string, int> channel_by_name;
  for (size_t index = 0; index < channels.size(); ++index) {
    const std::string entry = "channels[" + std::to_string(index) + "]";
    const Json& value = channels[index];
    reader.check_object(value, entry);
    reader.check_keys(value, entry, {"name", "unit", "modality"});
    Channel channel;
    channel.name = reader.text(reader.require(value, "name", entry), entry, "name");
    channel.unit = reader.text_or(value, "unit", entry, "");
    channel.modality = reader.text(reader.require(value, "modality", entry), entry, "modality");
    // Checked here already: taxels look channels up by name.
    const auto [previous, inserted] =
        channel_by_name.emplace(channel.name, static_cast<int>(index));
    if (!inserted) {
      reader.fail("channel " + in_quotes(channel.name), "duplicate channel name (columns " +
                                                            std::to_string(previous->second) +
                                                            " and " + std::to_string(index) + ")");
    }
    layout.channels.push_back(std::move(channel));
  }

  const Json& taxels = reader.array(reader.require(root, "taxels", ""), "", "taxels");
  layout.taxels.reserve(taxels.size());
  for (size_t index = 0; index < taxels.size(); ++index) {
    layout.taxels.push_back(parse_taxel(reader, taxels[index], index, layout, channel_by_name));
  }
  if (const Json* groups = reader.optional(root, "groups")) {
    reader.array(*groups, "", "groups");
    for (size_t index = 0; index < groups->size(); ++index) {
      layout.groups.push_back(parse_group(reader, (*groups)[index], index));
    }
  }
  if (const Json* kinds = reader.optional(root, "disjoint_kinds")) {
    layout.disjoint_kinds = reader.strings(*kinds, "disjoint_kinds");
  }
  if (const Json* classes = reader.optional(root, "classes")) {
    layout.classes = reader.strings(*classes, "classes");
  }
  if (const Json* outline = reader.optional(root, "outline")) {
    reader.array(*outline, "", "outline");
    for (size_t index = 0; index < outline->size(); ++index) {
      const std::string entry = "outline[" + std::to_string(index) + "]";
      layout.body_outline.push_back(reader.points((*outline)[index], entry, "points"));
    }
  }
  validate_layout(layout, where);
  return layout;
}

SkinLayout load_layout_file(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw Error(path, "cannot open layout file");
  std::ostringstream content;
  content << stream.rdbuf();
  if (stream.bad()) throw Error(path, "cannot read layout file");
  return parse_layout_json(content.str(), path);
}

}  // namespace tactile
