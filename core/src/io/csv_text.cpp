#include "tactile/io/csv_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "tactile/error.h"

namespace tactile::csv {

namespace {

constexpr size_t kReadBuffer = size_t(1) << 20;

// A read buffer of up to 1 MiB, no larger than the file (a small file costs no megabyte).
size_t buffer_size(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error) return kReadBuffer;
  return static_cast<size_t>(std::clamp<uintmax_t>(size + 1, 4096, kReadBuffer));
}

std::string_view trim(std::string_view text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const size_t last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// Cells are short; quote them in messages, cut to keep one line readable.
std::string shown(std::string_view cell) {
  constexpr size_t kLongest = 40;
  return "'" + std::string(cell.substr(0, kLongest)) + (cell.size() > kLongest ? "...'" : "'");
}

template <typename Number>
Number parse_number(std::string_view cell, const std::string& path, int64_t line, int64_t column) {
  std::string_view text = cell;
  if (text.empty()) throw Error(location(path, line, column), "empty cell");
  // from_chars takes no leading '+', which spreadsheets write.
  if (text.front() == '+' && text.size() > 1 && text[1] != '-') text.remove_prefix(1);
  Number value{};
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status == std::errc::result_out_of_range)
    throw Error(location(path, line, column), "value " + shown(cell) + " is out of range");
  if (status != std::errc() || end != text.data() + text.size())
    throw Error(location(path, line, column), "not a number: " + shown(cell));
  if (!std::isfinite(value))
    throw Error(location(path, line, column),
                "NaN and infinite values are not accepted: " + shown(cell));
  return value;
}

}  // namespace

std::string location(const std::string& path, int64_t line, int64_t column) {
  std::string text = path + ":" + std::to_string(line);
  if (column > 0) text += " column " + std::to_string(column);
  return text;
}

LineReader::LineReader(const std::string& path) : path_(path) {
  const size_t size = buffer_size(path);
  buffer_.reset(new char[size]);
  in_.rdbuf()->pubsetbuf(buffer_.get(), static_cast<std::streamsize>(size));
  in_.open(path, std::ios::binary);
  if (!in_) throw Error(path, "cannot open file");
}

bool LineReader::next() {
  if (!std::getline(in_, line_)) {
    if (in_.bad()) throw Error(location(path_, number_ + 1), "read error");
    return false;
  }
  ++number_;
  if (!line_.empty() && line_.back() == '\r') line_.pop_back();
  // Spreadsheet programs start UTF-8 files with a byte order mark; it is not text.
  if (number_ == 1 && line_.starts_with("\xEF\xBB\xBF")) line_.erase(0, 3);
  return true;
}

int64_t count_content_lines(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw Error(path, "cannot open file");
  const size_t capacity = buffer_size(path);
  const std::unique_ptr<char[]> buffer(new char[capacity]);
  int64_t count = 0;
  bool has_content = false;
  size_t size = 0;
  while ((size = std::fread(buffer.get(), 1, capacity, file.get())) > 0) {
    for (size_t index = 0; index < size; ++index) {
      const char character = buffer[index];
      if (character == '\n') {
        count += has_content;
        has_content = false;
      } else if (character != ' ' && character != '\t' && character != '\r') {
        has_content = true;
      }
    }
  }
  if (std::ferror(file.get())) throw Error(path, "read error");
  return count + has_content;
}

bool is_blank(std::string_view line) { return trim(line).empty(); }

bool split_cells(std::string_view line, std::vector<std::string_view>& cells) {
  cells.clear();
  size_t position = 0;
  while (true) {
    // Skip spaces before the cell, so ` "a b"` is still a quoted cell.
    while (position < line.size() && (line[position] == ' ' || line[position] == '\t')) ++position;
    if (position < line.size() && line[position] == '"') {
      const size_t begin = position + 1;
      size_t cursor = begin;
      while (true) {
        cursor = line.find('"', cursor);
        if (cursor == std::string_view::npos) return false;
        if (cursor + 1 < line.size() && line[cursor + 1] == '"') {
          cursor += 2;
          continue;
        }
        break;
      }
      cells.push_back(line.substr(begin, cursor - begin));
      position = line.find(',', cursor + 1);
    } else {
      const size_t comma = line.find(',', position);
      const size_t end = comma == std::string_view::npos ? line.size() : comma;
      cells.push_back(trim(line.substr(position, end - position)));
      position = comma;
    }
    if (position == std::string_view::npos) return true;
    ++position;  // past the comma: another cell follows, even an empty last one
  }
}

std::string unquote(std::string_view cell) {
  std::string text;
  text.reserve(cell.size());
  for (size_t index = 0; index < cell.size(); ++index) {
    text += cell[index];
    if (cell[index] == '"' && index + 1 < cell.size() && cell[index + 1] == '"') ++index;
  }
  return text;
}

float parse_float(std::string_view cell, const std::string& path, int64_t line, int64_t column) {
  return parse_number<float>(cell, path, line, column);
}

double parse_double(std::string_view cell, const std::string& path, int64_t line, int64_t column) {
  return parse_number<double>(cell, path, line, column);
}

bool looks_numeric(std::string_view cell) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  double value = 0.0;
  const auto [end, status] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  return !cell.empty() && end == cell.data() + cell.size() &&
         (status == std::errc() || status == std::errc::result_out_of_range);
}

}  // namespace tactile::csv
