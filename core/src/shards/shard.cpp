#include "tactile/shards/shard.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"

namespace tactile {

namespace {

constexpr int kPartFormat = 1;

std::string crc_text(const std::string& text) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (size_t at = 0; at < text.size();) {  // crc32 takes a uInt length
    const size_t block = std::min<size_t>(text.size() - at, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(text.data() + at), static_cast<uInt>(block));
    at += block;
  }
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08lx", static_cast<unsigned long>(crc));
  return hex;
}

// What the checksum covers: every field but the checksum, in the file's own key order.
nlohmann::json checked_body(const Part& part) {
  return {
      {"tactile_part", kPartFormat}, {"command", part.command}, {"shard", part.shard.to_string()},
      {"inputs", part.inputs},       {"result", part.result},   {"items", part.items},
      {"plan", part.plan},           {"shared", part.shared},   {"done", part.done}};
}

template <typename Value>
Value part_field(const nlohmann::json& document, const char* key, const std::string& path) {
  if (!document.contains(key)) throw Error(path, std::string("not a part file: no '") + key + "'");
  try {
    return document.at(key).get<Value>();
  } catch (const nlohmann::json::exception&) {
    throw Error(path, std::string("part field '") + key + "' is malformed");
  }
}

std::string short_json(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return text;
}

// The first field two parts of one job must share and do not: "FIELD: 'A' here, 'B' there".
std::string first_difference(const Part& a, const Part& b) {
  if (a.command != b.command)
    return "made by `tactile " + b.command + "`, " + a.path + " by `tactile " + a.command + "`";
  if (a.inputs != b.inputs) {
    for (auto it = a.inputs.begin(); a.inputs.is_object() && it != a.inputs.end(); ++it) {
      const nlohmann::json other = b.inputs.is_object() && b.inputs.contains(it.key())
                                       ? b.inputs.at(it.key())
                                       : nlohmann::json();
      if (other != it.value())
        return "made with " + it.key() + " " + short_json(other) + ", " + a.path + " with " +
               short_json(it.value());
    }
    for (auto it = b.inputs.begin(); b.inputs.is_object() && it != b.inputs.end(); ++it)
      if (!a.inputs.is_object() || !a.inputs.contains(it.key()))
        return "made with " + it.key() + " " + short_json(it.value()) + ", " + a.path +
               " without it";
    return "made with other inputs than " + a.path;
  }
  if (a.shard.count != b.shard.count)
    return "is one of " + std::to_string(b.shard.count) + " shards, " + a.path + " one of " +
           std::to_string(a.shard.count);
  if (a.result != b.result) return "is for " + b.result + ", " + a.path + " for " + a.result;
  if (a.items != b.items || a.plan != b.plan)
    return "saw other work than " + a.path + " (" + std::to_string(b.items) + " items, not " +
           std::to_string(a.items) + "; did the inputs change between the shards?)";
  return "";
}

}  // namespace

//---- Shard ----------------------------------------------------------------------------------

bool Shard::owns(size_t item) const {
  return !active() || static_cast<int>(item % static_cast<size_t>(count)) == index - 1;
}

std::vector<size_t> Shard::items_of(size_t total) const {
  std::vector<size_t> items;
  for (size_t item = 0; item < total; ++item)
    if (owns(item)) items.push_back(item);
  return items;
}

std::string Shard::to_string() const {
  return active() ? std::to_string(index) + "/" + std::to_string(count) : "";
}

Shard Shard::parse(const std::string& text, const std::string& where) {
  Shard shard;
  if (text.empty()) return shard;
  const size_t slash = text.find('/');
  const auto number = [&](const std::string& digits) {
    if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      throw Error(where, "'" + text + "' is not I/N (shard I of N, 1 <= I <= N), e.g. 2/4");
    return std::stoi(digits);
  };
  if (slash == std::string::npos)
    throw Error(where, "'" + text + "' is not I/N (shard I of N, 1 <= I <= N), e.g. 2/4");
  shard.index = number(text.substr(0, slash));
  shard.count = number(text.substr(slash + 1));
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count)
    throw Error(where, "'" + text + "': the shard must be 1 to N of N >= 1");
  return shard;
}

std::string default_part_path(const std::string& result, const Shard& shard) {
  return result + ".part-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
}

std::string plan_digest(const std::vector<std::string>& keys) {
  std::string joined;
  for (const std::string& key : keys) joined += key + '\n';
  return std::to_string(keys.size()) + ":" + crc_text(joined);
}

std::string file_digest(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path, "cannot read the file");
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<char> block(1 << 20);
  int64_t size = 0;
  while (file) {
    file.read(block.data(), static_cast<std::streamsize>(block.size()));
    const auto got = file.gcount();
    crc = crc32(crc, reinterpret_cast<const Bytef*>(block.data()), static_cast<uInt>(got));
    size += got;
  }
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08lx", static_cast<unsigned long>(crc));
  return std::to_string(size) + ":" + hex;
}

//---- Part files -----------------------------------------------------------------------------

void write_part(const std::string& path, const Part& part) {
  if (!part.shard.active()) throw Error(path, "a part needs its shard");
  nlohmann::json document = checked_body(part);
  document["checksum"] = crc_text(document.dump());
  write_file_atomically(path, document.dump() + "\n", "part");
}

Part read_part(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(path, "no such part file");
  std::ostringstream text;
  text << file.rdbuf();
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& error) {
    throw Error(path, std::string("not a part file (cut short or damaged?): ") + error.what());
  }
  if (!document.is_object() || !document.contains("tactile_part"))
    throw Error(path, "not a part file of `tactile ... --shard I/N`");
  if (part_field<int>(document, "tactile_part", path) != kPartFormat)
    throw Error(path, "a part file of another version (" + document.at("tactile_part").dump() +
                          "); make it again");
  Part part;
  part.path = path;
  part.command = part_field<std::string>(document, "command", path);
  part.shard = Shard::parse(part_field<std::string>(document, "shard", path), path + ": shard");
  if (!part.shard.active()) throw Error(path, "part field 'shard' is empty");
  part.inputs = document.contains("inputs") ? document.at("inputs") : nlohmann::json();
  part.result = part_field<std::string>(document, "result", path);
  part.items = part_field<int64_t>(document, "items", path);
  part.plan = part_field<std::string>(document, "plan", path);
  part.shared = document.contains("shared") ? document.at("shared") : nlohmann::json();
  part.done = document.contains("done") ? document.at("done") : nlohmann::json();
  const std::string checksum = part_field<std::string>(document, "checksum", path);
  if (crc_text(checked_body(part).dump()) != checksum)
    throw Error(path, "checksum failed: the part was changed or damaged; run its shard again");
  if (part.items < 0) throw Error(path, "part field 'items' is negative");
  if (!part.done.is_array()) throw Error(path, "part field 'done' is not a list");
  int64_t previous = -1;
  for (const nlohmann::json& entry : part.done) {
    if (!entry.is_object() || !entry.contains("index") || !entry.at("index").is_number_integer())
      throw Error(path, "an item without its index");
    const auto index = entry.at("index").get<int64_t>();
    if (index <= previous || index >= part.items || !part.shard.owns(static_cast<size_t>(index)))
      throw Error(path, "item " + std::to_string(index) + " is not one of shard " +
                            part.shard.to_string() + "'s, in order");
    previous = index;
  }
  const size_t owned = part.shard.items_of(static_cast<size_t>(part.items)).size();
  if (part.done.size() != owned)
    throw Error(path, "holds " + std::to_string(part.done.size()) + " of shard " +
                          part.shard.to_string() + "'s " + std::to_string(owned) +
                          " items; run it again");
  return part;
}

namespace {

// Where a missing shard's part would be: named as the first part given is (a command's
// default may be "DB.segment.part-I-of-N", a cluster's "DIR/parts/part-I-of-N"), else beside
// the result.
std::string missing_part_hint(const Part& first, const Shard& missing) {
  const std::string suffix = default_part_path("", first.shard).substr(1);  // "part-I-of-N"
  if (first.path.size() > suffix.size() &&
      first.path.compare(first.path.size() - suffix.size(), suffix.size(), suffix) == 0)
    return first.path.substr(0, first.path.size() - suffix.size()) +
           default_part_path("", missing).substr(1);
  return default_part_path(first.result, missing);
}

}  // namespace

std::vector<Part> gather_parts(const std::vector<std::string>& paths, const std::string& command) {
  if (paths.empty()) throw Error("merge", "no part files given");
  std::map<int, Part> by_shard;
  const Part* first = nullptr;
  std::vector<Part> read;
  read.reserve(paths.size());
  for (const std::string& path : paths) read.push_back(read_part(path));
  for (const Part& part : read) {
    if (!command.empty() && part.command != command)
      throw Error(part.path,
                  "a part of `tactile " + part.command + "`, not of `tactile " + command + "`");
    if (first) {
      const std::string difference = first_difference(*first, part);
      if (!difference.empty())
        throw Error(part.path, "does not belong with " + first->path + ": it is " + difference);
    } else {
      first = &part;
    }
    const auto [at, inserted] = by_shard.emplace(part.shard.index, part);
    if (!inserted)
      throw Error(part.path,
                  "shard " + part.shard.to_string() + " is given twice: also " + at->second.path);
  }
  std::vector<std::string> missing;
  for (int index = 1; index <= first->shard.count; ++index)
    if (!by_shard.count(index))
      missing.push_back(std::to_string(index) + "/" + std::to_string(first->shard.count) + " (" +
                        missing_part_hint(*first, Shard{index, first->shard.count}) + ")");
  if (!missing.empty()) {
    std::string list;
    for (const std::string& name : missing) list += (list.empty() ? "" : ", ") + name;
    throw Error("merge", std::string(missing.size() == 1 ? "shard " : "shards ") + list +
                             (missing.size() == 1 ? " is" : " are") +
                             " missing; run it with --shard and merge again");
  }
  std::vector<Part> parts;
  for (auto& [index, part] : by_shard) parts.push_back(std::move(part));
  return parts;
}

std::vector<nlohmann::json> items_in_order(const std::vector<Part>& parts) {
  if (parts.empty()) return {};
  std::vector<nlohmann::json> items(static_cast<size_t>(parts.front().items));
  std::vector<bool> seen(items.size(), false);
  for (const Part& part : parts)
    for (const nlohmann::json& entry : part.done) {
      const auto index = static_cast<size_t>(entry.at("index").get<int64_t>());
      items[index] = entry;
      seen[index] = true;
    }
  for (size_t index = 0; index < items.size(); ++index)
    if (!seen[index])
      throw Error(parts[index % parts.size()].path,
                  "item " + std::to_string(index) + " of shard " +
                      parts[index % parts.size()].shard.to_string() + " is not in it");
  return items;
}

}  // namespace tactile
