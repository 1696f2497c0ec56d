#include "tactile/parameters.h"

#include <charconv>
#include <cmath>

#include "tactile/error.h"

namespace tactile {

namespace {

std::string trim(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const size_t last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

}  // namespace

Parameters Parameters::parse(const std::string& text, const std::string& where) {
  Parameters parameters;
  parameters.where_ = where;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    const std::string item = trim(text.substr(start, end - start));
    start = end + 1;
    if (item.empty()) {
      if (end >= text.size()) break;
      continue;
    }
    const size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0)
      throw Error(where, "expected key=value, got '" + item + "'");
    const std::string key = trim(item.substr(0, equals));
    if (parameters.has(key)) throw Error(where, "'" + key + "' given twice");
    parameters.values_[key] = trim(item.substr(equals + 1));
  }
  return parameters;
}

std::string Parameters::answer(const std::string& key, std::string value) const {
  answered_[key] = value;
  return value;
}

std::string Parameters::answered_text() const {
  std::string text;
  for (const auto& [key, value] : answered_) text += (text.empty() ? "" : ",") + key + "=" + value;
  return text;
}

double Parameters::number(const std::string& key, double fallback) const {
  const auto found = values_.find(key);
  if (found == values_.end()) {
    char text[64];
    const auto written = std::to_chars(text, text + sizeof(text), fallback);  // shortest exact
    answer(key, std::string(text, written.ptr));
    return fallback;
  }
  const std::string& value = found->second;
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (error != std::errc() || end != value.data() + value.size() || !std::isfinite(parsed))
    throw Error(where_, key + "=" + value + ": not a finite number");
  answer(key, value);
  return parsed;
}

int64_t Parameters::integer(const std::string& key, int64_t fallback) const {
  const auto found = values_.find(key);
  if (found == values_.end()) {
    answer(key, std::to_string(fallback));
    return fallback;
  }
  const std::string& value = found->second;
  int64_t parsed = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (error != std::errc() || end != value.data() + value.size())
    throw Error(where_, key + "=" + value + ": not a whole number");
  answer(key, value);
  return parsed;
}

bool Parameters::flag(const std::string& key, bool fallback) const {
  const auto found = values_.find(key);
  if (found == values_.end()) {
    answer(key, fallback ? "true" : "false");
    return fallback;
  }
  const std::string& value = found->second;
  if (value == "1" || value == "true" || value == "yes" || value == "on") {
    answer(key, "true");
    return true;
  }
  if (value == "0" || value == "false" || value == "no" || value == "off") {
    answer(key, "false");
    return false;
  }
  throw Error(where_, key + "=" + value + ": expected true or false");
}

std::string Parameters::text(const std::string& key, const std::string& fallback) const {
  const auto found = values_.find(key);
  return answer(key, found == values_.end() ? fallback : found->second);
}

void Parameters::expect_only(const std::vector<std::string>& known) const {
  for (const auto& [key, value] : values_) {
    bool listed = false;
    for (const std::string& name : known) listed |= name == key;
    if (listed) continue;
    std::string names;
    for (const std::string& name : known) names += (names.empty() ? "" : ", ") + name;
    throw Error(where_, "unknown parameter '" + key + "'" +
                            (names.empty() ? "" : " (known: " + names + ")"));
  }
}

}  // namespace tactile
