// Dataset CSV: write with exact round trip, read back ours or any CSV with a class column.
#include "tactile/features/dataset.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>

#include "dataset_files.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/io/csv_text.h"
#include "tactile/text.h"

namespace tactile {

//---- Shared by both writers

namespace dataset_files {

void check_dataset(const std::string& path, const Dataset& dataset) {
  const auto rows = static_cast<size_t>(dataset.rows());
  if (rows == 0) throw Error(path, "the dataset has no rows");
  if (dataset.columns.empty()) throw Error(path, "the dataset has no feature columns");
  if (dataset.features.cols() != static_cast<int64_t>(dataset.columns.size()))
    throw Error(path, "the dataset has " + std::to_string(dataset.columns.size()) +
                          " feature columns but " + std::to_string(dataset.features.cols()) +
                          " values per row");
  if (dataset.classes.size() != rows || dataset.subjects.size() != rows ||
      dataset.recordings.size() != rows || dataset.segment_ids.size() != rows ||
      dataset.metadata.size() != rows)
    throw Error(path,
                "the dataset's classes, subjects, recordings, segment ids and metadata "
                "must have one entry per row (" +
                    std::to_string(rows) + ")");
  std::set<std::string> names = {kClassColumn, kSubjectColumn, kRecordingColumn, kSegmentIdColumn};
  for (const FeatureColumn& column : dataset.columns) {
    if (column.name.empty()) throw Error(path, "a feature column has an empty name");
    if (!names.insert(column.name).second)
      throw Error(path, "column name '" + column.name + "' is used twice");
  }
  for (size_t row = 0; row < rows; ++row)
    if (dataset.classes[row].empty())
      throw Error(path, "row " + std::to_string(row + 1) + " has an empty class");
  for (int64_t column = 0; column < dataset.features.cols(); ++column)
    for (int64_t row = 0; row < dataset.features.rows(); ++row)
      if (!std::isfinite(dataset.features(row, column)))
        throw Error(path, "row " + std::to_string(row + 1) + " feature '" +
                              dataset.columns[column].name + "' is not finite");
}

}  // namespace dataset_files

std::string Dataset::shared_metadata(const std::string& key) const {
  std::string shared;
  for (size_t row = 0; row < metadata.size(); ++row) {
    const auto found = metadata[row].find(key);
    if (found == metadata[row].end()) return "";
    if (row == 0) shared = found->second;
    if (found->second != shared) return "";
  }
  return shared;
}

std::vector<std::string> Dataset::class_names() const {
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (const std::string& name : classes)
    if (seen.insert(name).second) names.push_back(name);
  return names;
}

//---- CSV writer

namespace {

using namespace dataset_files;

// RFC 4180 quoting; also cells with blanks at either end, which the reader would trim.
std::string csv_cell(const std::string& text) {
  const bool edge_blank = !text.empty() && (text.front() == ' ' || text.front() == '\t' ||
                                            text.back() == ' ' || text.back() == '\t');
  if (!edge_blank && text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char character : text) {
    if (character == '"') quoted += '"';
    quoted += character;
  }
  return quoted + '"';
}

// The reader reads one line per row, so text cells may not hold line breaks.
void check_one_line(const std::string& path, const std::string& text, const std::string& what) {
  if (text.find_first_of("\r\n") != std::string::npos)
    throw Error(path, what + " holds a line break, which a dataset CSV cannot keep");
}

}  // namespace

void write_dataset_csv(const std::string& path, const Dataset& dataset) {
  check_dataset(path, dataset);
  std::set<std::string> taken = {kClassColumn, kSubjectColumn, kRecordingColumn, kSegmentIdColumn};
  for (const FeatureColumn& column : dataset.columns) taken.insert(column.name);
  std::set<std::string> keys;
  for (const Metadata& metadata : dataset.metadata)
    for (const auto& [key, value] : metadata) keys.insert(key);
  for (const std::string& key : keys) {
    if (taken.count(key))
      throw Error(path, "metadata key '" + key + "' collides with a column of the same name");
    check_one_line(path, key, "metadata key '" + key + "'");
  }

  std::string text;
  for (const FeatureColumn& column : dataset.columns) {
    check_one_line(path, column.name, "column name '" + column.name + "'");
    text += csv_cell(column.name) + ",";
  }
  text += std::string(kClassColumn) + "," + kSubjectColumn + "," + kRecordingColumn + "," +
          kSegmentIdColumn;
  for (const std::string& key : keys) {
    text += ',';
    text += csv_cell(key);
  }
  text += "\n";
  for (int64_t row = 0; row < dataset.rows(); ++row) {
    for (int64_t column = 0; column < dataset.features.cols(); ++column)
      text += shortest_text(dataset.features(row, column)) + ",";
    const std::string where = "row " + std::to_string(row + 1);
    check_one_line(path, dataset.classes[row], where + " class");
    check_one_line(path, dataset.subjects[row], where + " subject");
    check_one_line(path, dataset.recordings[row], where + " recording");
    text += csv_cell(dataset.classes[row]) + "," + csv_cell(dataset.subjects[row]) + "," +
            csv_cell(dataset.recordings[row]) + "," + std::to_string(dataset.segment_ids[row]);
    const Metadata& metadata = dataset.metadata[row];
    for (const std::string& key : keys) {
      const auto found = metadata.find(key);
      text += ",";
      if (found == metadata.end()) continue;
      check_one_line(path, found->second, where + " metadata '" + key + "'");
      text += csv_cell(found->second);
    }
    text += "\n";
  }
  write_file_atomically(path, text);
}

//---- CSV reader

namespace {

enum class ColumnRole { kFeature, kClass, kSubject, kRecording, kSegmentId, kMetadata };

struct HeaderColumn {
  std::string name;
  ColumnRole role = ColumnRole::kMetadata;
};

ColumnRole known_role(const std::string& name) {
  if (name == kClassColumn) return ColumnRole::kClass;
  if (name == kSubjectColumn) return ColumnRole::kSubject;
  if (name == kRecordingColumn) return ColumnRole::kRecording;
  if (name == kSegmentIdColumn) return ColumnRole::kSegmentId;
  return ColumnRole::kMetadata;
}

// Our own files: features, then class, subject, recording, segment_id, then metadata.
// Any other file: a column is a feature when its first row holds a number there.
void assign_roles(std::vector<HeaderColumn>& header,
                  const std::vector<std::string_view>& first_row) {
  size_t class_index = header.size();
  for (size_t index = 0; index < header.size(); ++index) {
    header[index].role = known_role(header[index].name);
    if (header[index].role == ColumnRole::kClass) class_index = index;
  }
  const bool ours = class_index + 3 < header.size() &&
                    header[class_index + 1].role == ColumnRole::kSubject &&
                    header[class_index + 2].role == ColumnRole::kRecording &&
                    header[class_index + 3].role == ColumnRole::kSegmentId;
  for (size_t index = 0; index < header.size(); ++index) {
    if (header[index].role != ColumnRole::kMetadata) continue;
    const bool numeric = !first_row[index].empty() && csv::looks_numeric(first_row[index]);
    if (ours ? index < class_index : numeric) header[index].role = ColumnRole::kFeature;
  }
}

int64_t parse_segment_id(std::string_view cell, const std::string& where) {
  int64_t value = 0;
  const auto [end, status] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || status != std::errc() || end != cell.data() + cell.size())
    throw Error(where, "segment_id '" + std::string(cell) + "' is not a whole number");
  return value;
}

}  // namespace

Dataset read_dataset_csv(const std::string& path) {
  csv::LineReader reader(path);
  std::vector<std::string_view> cells;
  std::vector<HeaderColumn> header;
  while (reader.next()) {
    if (csv::is_blank(reader.line())) continue;
    if (!csv::split_cells(reader.line(), cells))
      throw Error(csv::location(path, reader.number()), "unterminated quote in the header");
    std::set<std::string> seen;
    for (size_t index = 0; index < cells.size(); ++index) {
      HeaderColumn column{csv::unquote(cells[index])};
      if (column.name.empty())
        throw Error(csv::location(path, reader.number(), index + 1), "empty column name");
      if (!seen.insert(column.name).second)
        throw Error(csv::location(path, reader.number(), index + 1),
                    "column '" + column.name + "' appears twice");
      header.push_back(std::move(column));
    }
    break;
  }
  if (header.empty()) throw Error(path, "empty file: no header row");
  const int64_t header_line = reader.number();
  if (std::none_of(header.begin(), header.end(),
                   [](const HeaderColumn& column) { return column.name == kClassColumn; }))
    throw Error(csv::location(path, header_line), "no 'class' column in the header");

  Dataset dataset;
  std::vector<double> values;  // row-major while reading
  bool roles_assigned = false;
  while (reader.next()) {
    if (csv::is_blank(reader.line())) continue;
    const int64_t line = reader.number();
    if (!csv::split_cells(reader.line(), cells))
      throw Error(csv::location(path, line), "unterminated quote");
    if (cells.size() != header.size())
      throw Error(csv::location(path, line), "ragged row: " + std::to_string(cells.size()) +
                                                 " cells, the header has " +
                                                 std::to_string(header.size()));
    if (!roles_assigned) {
      assign_roles(header, cells);
      for (const HeaderColumn& column : header)
        if (column.role == ColumnRole::kFeature) dataset.columns.push_back({column.name, ""});
      if (dataset.columns.empty())
        throw Error(csv::location(path, header_line), "no numeric feature columns");
      roles_assigned = true;
    }
    std::string subject, recording;
    int64_t segment_id = 0;
    Metadata metadata;
    for (size_t index = 0; index < cells.size(); ++index) {
      const auto column = static_cast<int64_t>(index + 1);
      switch (header[index].role) {
        case ColumnRole::kFeature:
          values.push_back(csv::parse_double(cells[index], path, line, column));
          break;
        case ColumnRole::kClass:
          dataset.classes.push_back(csv::unquote(cells[index]));
          if (dataset.classes.back().empty())
            throw Error(csv::location(path, line, column), "empty class");
          break;
        case ColumnRole::kSubject:
          subject = csv::unquote(cells[index]);
          break;
        case ColumnRole::kRecording:
          recording = csv::unquote(cells[index]);
          break;
        case ColumnRole::kSegmentId:
          segment_id = parse_segment_id(cells[index], csv::location(path, line, column));
          break;
        case ColumnRole::kMetadata:
          // An empty cell is a key this row does not have (the writer leaves it empty).
          if (!cells[index].empty()) metadata[header[index].name] = csv::unquote(cells[index]);
          break;
      }
    }
    dataset.subjects.push_back(std::move(subject));
    dataset.recordings.push_back(std::move(recording));
    dataset.segment_ids.push_back(segment_id);
    dataset.metadata.push_back(std::move(metadata));
  }
  if (dataset.classes.empty()) throw Error(path, "no data rows");
  const auto columns = static_cast<int64_t>(dataset.columns.size());
  const auto rows = static_cast<int64_t>(dataset.classes.size());
  dataset.features =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          values.data(), rows, columns);
  return dataset;
}

}  // namespace tactile
