#include "tactile/text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace tactile {

std::string shortest_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string fixed_text(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string significant_text(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return text;
}

std::string seconds_text(double seconds) {
  if (!std::isfinite(seconds)) return shortest_text(seconds);
  const double microseconds = std::round(seconds * 1e6);
  return shortest_text(microseconds == 0.0 ? 0.0 : microseconds / 1e6);
}

std::string in_quotes(const std::string& text) { return "\"" + text + "\""; }

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

}  // namespace tactile
