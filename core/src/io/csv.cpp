// CSV import: the long (one sample per row) and wide (one capture per row) shapes.
#include "tactile/io/csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>

#include "csv_text.h"
#include "tactile/error.h"
#include "tactile/io/array_import.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

using csv::location;

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::string file_name_of(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

bool is_time_name(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char character) { return std::tolower(character); });
  return name == "t" || name == "time" || name == "time_s" || name == "timestamp";
}

void check_rate(double rate_hz, const std::string& option) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0)
    throw Error(option, "rate must be a positive number of Hz, not " + std::to_string(rate_hz));
}

Stream empty_stream(const std::string& name, const SkinLayout& layout) {
  Stream stream;
  stream.name = name;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  return stream;
}

// Reads the rows after the header (or all rows) of a file whose content lines were
// counted beforehand. Blank lines may end the file but not interrupt the data, where
// they would hide a lost row. Calls `row(cells, line)` for every data row.
template <typename Row>
void for_each_row(csv::LineReader& reader, Row row) {
  std::vector<std::string_view> cells;
  int64_t blank_line = 0;
  while (reader.next()) {
    if (csv::is_blank(reader.line())) {
      if (blank_line == 0) blank_line = reader.number();
      continue;
    }
    if (blank_line != 0)
      throw Error(location(reader.path(), blank_line), "blank line inside the data");
    if (!csv::split_cells(reader.line(), cells))
      throw Error(location(reader.path(), reader.number()), "unterminated quote");
    row(cells, reader.number());
  }
}

// A cell count other than `expected` names the first missing or the first extra column.
void check_cell_count(size_t count, size_t expected, const std::string& path, int64_t line,
                      const std::string& what) {
  if (count == expected) return;
  const int64_t column = static_cast<int64_t>(std::min(count, expected)) + 1;
  throw Error(location(path, line, column), "row has " + std::to_string(count) + " cells, " + what +
                                                " " + std::to_string(expected));
}

// 1 / median time step, snapped to 10 significant digits when that is within 1e-9:
// time columns printed in decimal make 250 Hz read as 249.99999999999997.
double rate_from_steps(std::vector<double> steps) {
  const double rate = 1.0 / stats::median(std::move(steps));
  const double scale = std::pow(10.0, 9.0 - std::floor(std::log10(rate)));
  const double snapped = std::round(rate * scale) / scale;
  return std::abs(snapped - rate) <= 1e-9 * rate ? snapped : rate;
}

}  // namespace

//---- long

Recording import_csv_long(const std::string& path, const SkinLayout& layout,
                          const CsvLongOptions& options) {
  if (options.rate_hz) check_rate(*options.rate_hz, "rate_hz");
  const int64_t content_lines = csv::count_content_lines(path);
  if (content_lines == 0) throw Error(path, "empty file");
  const size_t channel_count = layout.channels.size();

  csv::LineReader reader(path);
  while (reader.next() && csv::is_blank(reader.line())) {
  }
  const int64_t header_line = reader.number();
  std::vector<std::string_view> header;
  if (!csv::split_cells(reader.line(), header))
    throw Error(location(path, header_line), "unterminated quote in the header");
  if (std::all_of(header.begin(), header.end(), csv::looks_numeric))
    throw Error(location(path, header_line), "expected a header row, found numbers");

  const bool first_is_time_name = is_time_name(csv::unquote(header.front()));
  // One more column than channels, or a first column named as time: a time column.
  const bool has_time =
      options.has_time_column.value_or(header.size() == channel_count + 1 || first_is_time_name);
  const size_t columns = channel_count + (has_time ? 1 : 0);
  if (header.size() != columns)
    throw Error(location(path, header_line), std::to_string(header.size()) +
                                                 " columns, but layout '" + layout.id + "' has " +
                                                 std::to_string(channel_count) + " channels" +
                                                 (has_time ? " (plus the time column)" : ""));
  if (!has_time && !options.rate_hz)
    throw Error(location(path, header_line), "no time column and no rate given");

  const int64_t rows = content_lines - 1;
  if (rows == 0) throw Error(path, "a header but no data rows");
  Stream stream = empty_stream(options.stream_name, layout);
  stream.samples.resize(rows, static_cast<Eigen::Index>(channel_count));
  std::vector<double> times;
  if (has_time) times.reserve(static_cast<size_t>(rows));
  const int64_t first_channel_cell = has_time ? 1 : 0;

  int64_t row = 0;
  for_each_row(reader, [&](const std::vector<std::string_view>& cells, int64_t line) {
    check_cell_count(cells.size(), columns, path, line, "header has");
    if (row == rows) throw Error(path, "file grew while it was read");
    if (has_time) {
      const double time = csv::parse_double(cells[0], path, line, 1);
      if (!times.empty() && !(time > times.back()))
        throw Error(location(path, line, 1),
                    "time " + std::string(cells[0]) + " does not increase on the previous row");
      times.push_back(time);
    }
    for (size_t channel = 0; channel < channel_count; ++channel) {
      const int64_t column = first_channel_cell + static_cast<int64_t>(channel);
      stream.samples(row, static_cast<Eigen::Index>(channel)) =
          csv::parse_float(cells[size_t(column)], path, line, column + 1);
    }
    ++row;
  });
  if (row != rows) throw Error(path, "file shrank while it was read");

  if (options.rate_hz) {
    stream.rate_hz = *options.rate_hz;
  } else if (rows < 2) {
    throw Error(path, "one sample gives no time step: give the rate");
  }
  if (has_time) {
    std::vector<double> steps(times.size() - 1);
    for (size_t index = 1; index < times.size(); ++index)
      steps[index - 1] = times[index] - times[index - 1];
    if (!options.rate_hz) stream.rate_hz = rate_from_steps(steps);
    stream.start_time = times.front();
    const double step = 1.0 / stream.rate_hz;
    const bool irregular = std::any_of(steps.begin(), steps.end(), [&](double value) {
      return std::abs(value - step) > kIrregularStepTolerance * step;
    });
    if (irregular) stream.timestamps = std::move(times);
  }

  Recording recording;
  recording.id = stem_of(path);
  recording.layout_id = layout.id;
  recording.metadata["imported_from"] = file_name_of(path);
  recording.streams.push_back(std::move(stream));
  return recording;
}


//---- long, with a class column and grouping columns

std::vector<ImportedRecording> import_csv_table(const std::string& path, const SkinLayout& layout,
                                                const CsvTableOptions& options) {
  if (options.rate_hz) check_rate(*options.rate_hz, "rate_hz");
  const int64_t content_lines = csv::count_content_lines(path);
  if (content_lines == 0) throw Error(path, "empty file");
  const size_t channel_count = layout.channels.size();
  csv::LineReader reader(path);
  while (reader.next() && csv::is_blank(reader.line())) {
  }
  const int64_t header_line = reader.number();
  std::vector<std::string_view> cells;
  if (!csv::split_cells(reader.line(), cells))
    throw Error(location(path, header_line), "unterminated quote in the header");
  std::vector<std::string> header;
  for (std::string_view cell : cells) header.push_back(csv::unquote(cell));
  const auto column_of = [&](const std::string& name, const char* option) {
    const auto found = std::find(header.begin(), header.end(), name);
    if (found == header.end()) {
      std::string names;
      for (const std::string& column : header) names += (names.empty() ? "" : ", ") + column;
      throw Error(std::string(option), "no column '" + name + "' in " + path + " (columns: " + names + ")");
    }
    return static_cast<size_t>(found - header.begin());
  };
  const std::optional<size_t> class_column =
      options.class_column.empty() ? std::nullopt : std::optional<size_t>(column_of(options.class_column, "--class-column"));
  std::vector<size_t> group_columns;
  for (const std::string& name : options.group_columns) group_columns.push_back(column_of(name, "--group-columns"));
  // The sample columns: the rest, in order; a time column first when named so or when
  // there is one more than the layout's channels.
  std::vector<size_t> data;
  for (size_t column = 0; column < header.size(); ++column)
    if (column != class_column && std::find(group_columns.begin(), group_columns.end(), column) == group_columns.end())
      data.push_back(column);
  const bool has_time = !data.empty() && (data.size() == channel_count + 1 || is_time_name(header[data.front()]));
  if (data.size() != channel_count + (has_time ? 1 : 0))
    throw Error(location(path, header_line),
                std::to_string(data.size()) + " sample columns, but layout '" + layout.id + "' has " +
                    std::to_string(channel_count) + " channels" + (has_time ? " (plus the time column)" : ""));
  if (!has_time && !options.rate_hz) throw Error(location(path, header_line), "no time column and no rate given");

  struct Group {
    std::vector<std::string> values;
    std::vector<double> times;
    std::vector<float> samples;  // row after row
    std::vector<std::string> classes;
    int64_t first_line = 0;
  };
  std::vector<Group> groups;
  std::map<std::string, size_t> index;
  for_each_row(reader, [&](const std::vector<std::string_view>& row, int64_t line) {
    check_cell_count(row.size(), header.size(), path, line, "header has");
    std::string key;
    std::vector<std::string> values;
    for (size_t column : group_columns) {
      values.push_back(csv::unquote(row[column]));
      key += values.back() + '\x1f';
    }
    auto [found, added] = index.emplace(key, groups.size());
    if (added) {
      groups.emplace_back();
      groups.back().values = values;
      groups.back().first_line = line;
    }
    Group& group = groups[found->second];
    size_t at = 0;
    if (has_time) {
      const auto time_column = static_cast<int64_t>(data[at++]);
      const double time = csv::parse_double(row[static_cast<size_t>(time_column)], path, line, time_column + 1);
      if (!group.times.empty() && !(time > group.times.back()))
        throw Error(location(path, line, time_column + 1),
                    "time " + std::string(row[static_cast<size_t>(time_column)]) + " does not increase on the group's previous row");
      group.times.push_back(time);
    }
    for (; at < data.size(); ++at)
      group.samples.push_back(csv::parse_float(row[data[at]], path, line, static_cast<int64_t>(data[at]) + 1));
    if (class_column) group.classes.push_back(csv::unquote(row[*class_column]));
  });
  if (groups.empty()) throw Error(path, "a header but no data rows");

  std::vector<ImportedRecording> recordings;
  for (Group& group : groups) {
    const auto rows = static_cast<int64_t>(group.samples.size() / channel_count);
    Stream stream = empty_stream(options.stream_name, layout);
    stream.samples.resize(rows, static_cast<Eigen::Index>(channel_count));
    for (int64_t row = 0; row < rows; ++row)
      for (size_t channel = 0; channel < channel_count; ++channel)
        stream.samples(row, static_cast<Eigen::Index>(channel)) = group.samples[static_cast<size_t>(row) * channel_count + channel];
    if (options.rate_hz) {
      stream.rate_hz = *options.rate_hz;
    } else if (rows < 2) {
      throw Error(location(path, group.first_line), "a group of one sample gives no time step: give the rate");
    }
    if (has_time) {
      std::vector<double> steps(group.times.size() - 1);
      for (size_t k = 1; k < group.times.size(); ++k) steps[k - 1] = group.times[k] - group.times[k - 1];
      if (!options.rate_hz) stream.rate_hz = rate_from_steps(steps);
      stream.start_time = group.times.front();
      const double step = 1.0 / stream.rate_hz;
      if (std::any_of(steps.begin(), steps.end(), [&](double value) { return std::abs(value - step) > kIrregularStepTolerance * step; }))
        stream.timestamps = group.times;
    }
    ImportedRecording imported;
    Recording& recording = imported.recording;
    recording.id = stem_of(path);
    for (size_t k = 0; k < group.values.size(); ++k) {
      recording.id += "-" + group.values[k];
      recording.metadata[options.group_columns[k]] = group.values[k];
    }
    recording.layout_id = layout.id;
    recording.metadata["imported_from"] = file_name_of(path);
    if (class_column) {
      // Each run of one class: from its first sample's time to one step past its last.
      const double step = 1.0 / stream.rate_hz;
      std::vector<double> times = group.times;
      if (times.empty())
        for (int64_t row = 0; row < rows; ++row) times.push_back(static_cast<double>(row) * step);
      for (Label& label : labels_from_frame_classes(group.classes, 0.0, 1.0)) {
        const auto first = static_cast<size_t>(std::llround(label.t0)), last = static_cast<size_t>(std::llround(label.t1)) - 1;
        label.t0 = times[first];
        label.t1 = times[last] + step;
        label.recording = recording.id;
        imported.labels.push_back(std::move(label));
      }
    }
    recording.streams.push_back(std::move(stream));
    recordings.push_back(std::move(imported));
  }
  return recordings;
}

//---- wide

namespace {

// The class of one line of a labels file, or "" when it names none.
std::string resolve_class(const std::string& token, const std::vector<std::string>& vocabulary) {
  if (vocabulary.empty()) return token;
  if (std::find(vocabulary.begin(), vocabulary.end(), token) != vocabulary.end()) return token;
  int64_t index = -1;
  const auto [end, status] = std::from_chars(token.data(), token.data() + token.size(), index);
  if (status == std::errc() && end == token.data() + token.size() && index >= 0 &&
      index < static_cast<int64_t>(vocabulary.size()))
    return vocabulary[size_t(index)];
  return {};
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::vector<std::string> read_label_classes(const std::string& path,
                                            const std::vector<std::string>& vocabulary) {
  csv::LineReader reader(path);
  std::vector<std::string> classes;
  bool first = true;
  std::vector<std::string_view> cells;
  int64_t blank_line = 0;
  while (reader.next()) {
    if (csv::is_blank(reader.line())) {
      if (blank_line == 0) blank_line = reader.number();
      continue;
    }
    if (blank_line != 0) throw Error(location(path, blank_line), "blank line inside the labels");
    if (!csv::split_cells(reader.line(), cells) || cells.size() != 1)
      throw Error(location(path, reader.number()), "expected one class per line");
    const std::string token = csv::unquote(cells[0]);
    std::string name = resolve_class(token, vocabulary);
    // A first line that is neither a class nor a number is a header.
    if (name.empty() && first && !csv::looks_numeric(token)) {
      first = false;
      continue;
    }
    first = false;
    if (name.empty())
      throw Error(location(path, reader.number(), 1), "unknown class '" + token +
                                                          "' (classes: " + joined(vocabulary) +
                                                          "; or a 0-based index)");
    classes.push_back(std::move(name));
  }
  if (classes.empty()) throw Error(path, "no labels");
  return classes;
}

}  // namespace

ImportedRecording import_csv_wide(const std::string& path, const SkinLayout& layout,
                                  const CsvWideOptions& options) {
  if (options.samples_per_capture <= 0)
    throw Error("samples_per_capture", "must be a positive number of samples");
  check_rate(options.rate_hz, "rate_hz");
  if (options.labels_path.empty()) throw Error("labels_path", "a labels file is required");
  const int64_t captures = csv::count_content_lines(path);
  if (captures == 0) throw Error(path, "empty file");
  const int64_t per_capture = options.samples_per_capture;
  const size_t channel_count = layout.channels.size();
  const size_t row_length = channel_count * static_cast<size_t>(per_capture);

  Stream stream = empty_stream(options.stream_name, layout);
  stream.rate_hz = options.rate_hz;
  stream.samples.resize(captures * per_capture, static_cast<Eigen::Index>(channel_count));
  csv::LineReader reader(path);
  int64_t capture = 0;
  for_each_row(reader, [&](const std::vector<std::string_view>& cells, int64_t line) {
    if (capture == 0 && cells.size() != row_length) {
      if (cells.size() % size_t(per_capture) != 0)
        throw Error(location(path, line), "row has " + std::to_string(cells.size()) +
                                              " values, not a multiple of samples_per_capture " +
                                              std::to_string(per_capture));
      throw Error(location(path, line),
                  "row has " + std::to_string(cells.size() / size_t(per_capture)) +
                      " channels of " + std::to_string(per_capture) + " samples, layout '" +
                      layout.id + "' has " + std::to_string(channel_count));
    }
    check_cell_count(cells.size(), row_length, path, line, "earlier rows have");
    if (capture == captures) throw Error(path, "file grew while it was read");
    // Channel-major: cell j holds channel j / N, sample j % N of this capture.
    for (size_t cell = 0; cell < cells.size(); ++cell) {
      const auto channel = static_cast<Eigen::Index>(cell / size_t(per_capture));
      const int64_t sample = capture * per_capture + int64_t(cell % size_t(per_capture));
      stream.samples(sample, channel) =
          csv::parse_float(cells[cell], path, line, static_cast<int64_t>(cell) + 1);
    }
    ++capture;
  });
  if (capture != captures) throw Error(path, "file shrank while it was read");

  const std::vector<std::string>& vocabulary =
      options.class_names.empty() ? layout.classes : options.class_names;
  const std::vector<std::string> classes = read_label_classes(options.labels_path, vocabulary);
  if (static_cast<int64_t>(classes.size()) != captures)
    throw Error(options.labels_path, std::to_string(classes.size()) + " labels for " +
                                         std::to_string(captures) + " captures in " + path);

  ImportedRecording imported;
  Recording& recording = imported.recording;
  recording.id = stem_of(path);
  recording.layout_id = layout.id;
  recording.metadata["imported_from"] = file_name_of(path);
  recording.metadata["labels_from"] = file_name_of(options.labels_path);
  recording.metadata["samples_per_capture"] = std::to_string(per_capture);
  recording.streams.push_back(std::move(stream));
  for (int64_t index = 0; index < captures; ++index) {
    Label label;
    label.recording = recording.id;
    label.t0 = static_cast<double>(index * per_capture) / options.rate_hz;
    label.t1 = static_cast<double>((index + 1) * per_capture) / options.rate_hz;
    label.region = "all";
    label.class_name = classes[size_t(index)];
    label.annotator = "import";
    label.source = LabelSource::kGroundTruth;
    imported.labels.push_back(std::move(label));
  }
  return imported;
}

}  // namespace tactile
