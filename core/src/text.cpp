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

std::string printable_text(const std::string& bytes) {
  const auto byte = [&](size_t at) { return static_cast<unsigned char>(bytes[at]); };
  // The length of the well-formed UTF-8 character at `at` (RFC 3629: no overlong forms, no
  // surrogates, nothing past U+10FFFF); 0 when there is none.
  const auto utf8_length = [&](size_t at) -> size_t {
    const unsigned char lead = byte(at);
    size_t length = 0;
    unsigned char low = 0x80, high = 0xbf;  // the range of the byte after the lead
    if (lead >= 0xc2 && lead <= 0xdf)
      length = 2;
    else if (lead >= 0xe0 && lead <= 0xef) {
      length = 3;
      if (lead == 0xe0) low = 0xa0;
      if (lead == 0xed) high = 0x9f;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
      length = 4;
      if (lead == 0xf0) low = 0x90;
      if (lead == 0xf4) high = 0x8f;
    } else {
      return 0;
    }
    if (at + length > bytes.size()) return 0;
    if (byte(at + 1) < low || byte(at + 1) > high) return 0;
    for (size_t k = 2; k < length; ++k)
      if (byte(at + k) < 0x80 || byte(at + k) > 0xbf) return 0;
    return length;
  };
  std::string text;
  for (size_t at = 0; at < bytes.size();) {
    const unsigned char value = byte(at);
    if (value >= 0x20 && value < 0x7f) {
      text.push_back(static_cast<char>(value));
      ++at;
      continue;
    }
    const size_t length = value >= 0x80 ? utf8_length(at) : 0;
    if (length > 0) {
      text.append(bytes, at, length);
      at += length;
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02X", value);
    text += escaped;
    ++at;
  }
  return text;
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

}  // namespace tactile
