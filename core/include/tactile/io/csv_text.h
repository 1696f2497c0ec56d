#pragma once
// Core's own (not for app/): the text side of CSV files, shared by the recordings' CSV
// (formats/csv_files.h) and the label store's (labelstore/label_csv_json.h). A line reader that
// streams the file, a cell splitter that understands double quotes, and number parsing with
// std::from_chars that reports "file.csv:LINE column COLUMN" on any bad cell.

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace tactile::csv {

// "file.csv:12 column 3" (line and column 1-based; column 0 leaves it out).
std::string location(const std::string& path, int64_t line, int64_t column = 0);

// Reads a file one line at a time, without the line break ("\n" or "\r\n").
class LineReader {
 public:
  explicit LineReader(const std::string& path);  // throws tactile::Error
  // False at the end of the file; throws tactile::Error on a read failure.
  bool next();
  std::string_view line() const { return line_; }
  int64_t number() const { return number_; }  // 1-based
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::unique_ptr<char[]> buffer_;  // not zeroed: the stream fills it
  std::string line_;
  int64_t number_ = 0;
};

// Lines holding anything but spaces, tabs and line breaks, counted in one fast pass
// so the sample matrix can be allocated once at its final size.
int64_t count_content_lines(const std::string& path);

bool is_blank(std::string_view line);

// Splits at commas. A cell in double quotes may hold commas and "" for a quote; its
// view excludes the outer quotes (use unquote() for the text). Spaces and tabs around
// cells are trimmed. Returns false on an unterminated quote.
bool split_cells(std::string_view line, std::vector<std::string_view>& cells);
// The text of a cell returned by split_cells: "" replaced by ".
std::string unquote(std::string_view cell);

// A cell as a finite number; throws tactile::Error at `path:line column column`
// naming the cell for empty, non-numeric, NaN, infinite or out-of-range values.
float parse_float(std::string_view cell, const std::string& path, int64_t line, int64_t column);
double parse_double(std::string_view cell, const std::string& path, int64_t line, int64_t column);
// True when the whole cell is a number (any value, NaN included): tells a header row
// from a data row.
bool looks_numeric(std::string_view cell);

}  // namespace tactile::csv
