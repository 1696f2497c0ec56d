// CSV import: the long (one sample per row) and wide (one capture per row) shapes.
#include "tactile/formats/csv_files.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>

#include "tactile/error.h"
#include "tactile/formats/array_files.h"
#include "tactile/io/csv_text.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

using csv::location;

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::string file_name_of(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
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

//---- long: one table, or several split by grouping columns, with a class column or not

namespace {

// The header row: where it is, its names, and which columns hold what.
struct TableHeader {
  int64_t line = 0;
  std::vector<std::string> names;
  std::optional<size_t> class_column;
  std::vector<size_t> group_columns;
  std::vector<size_t> sample_columns;  // the time column first when there is one
  bool has_time = false;
};

TableHeader read_header(csv::LineReader& reader, const SkinLayout& layout,
                        const CsvTableOptions& options) {
  const std::string& path = reader.path();
  while (reader.next() && csv::is_blank(reader.line())) {
  }
  TableHeader header;
  header.line = reader.number();
  std::vector<std::string_view> cells;
  if (!csv::split_cells(reader.line(), cells))
    throw Error(location(path, header.line), "unterminated quote in the header");
  if (std::all_of(cells.begin(), cells.end(), csv::looks_numeric))
    throw Error(location(path, header.line), "expected a header row, found numbers");
  for (std::string_view cell : cells) header.names.push_back(csv::unquote(cell));
  const auto column_of = [&](const std::string& name, const char* option) {
    const auto found = std::find(header.names.begin(), header.names.end(), name);
    if (found == header.names.end())
      throw Error(std::string(option), "no column '" + name + "' in " + path +
                                           " (columns: " + joined(header.names) + ")");
    return static_cast<size_t>(found - header.names.begin());
  };
  if (!options.class_column.empty())
    header.class_column = column_of(options.class_column, "--class-column");
  for (const std::string& name : options.group_columns)
    header.group_columns.push_back(column_of(name, "--group-columns"));
  // The sample columns: the rest, in order; a time column first when named so or when
  // there is one more than the layout's channels.
  for (size_t column = 0; column < header.names.size(); ++column)
    if (column != header.class_column &&
        std::find(header.group_columns.begin(), header.group_columns.end(), column) ==
            header.group_columns.end())
      header.sample_columns.push_back(column);
  const std::vector<size_t>& data = header.sample_columns;
  const size_t channel_count = layout.channels.size();
  header.has_time =
      options.has_time_column.value_or(!data.empty() && (data.size() == channel_count + 1 ||
                                                         is_time_name(header.names[data.front()])));
  const bool only_samples = data.size() == header.names.size();
  if (data.size() != channel_count + (header.has_time ? 1 : 0))
    throw Error(location(path, header.line),
                std::to_string(data.size()) + (only_samples ? " columns" : " sample columns") +
                    ", but layout '" + layout.id + "' has " + std::to_string(channel_count) +
                    " channels" + (header.has_time ? " (plus the time column)" : ""));
  if (!header.has_time && !options.rate_hz)
    throw Error(location(path, header.line), "no time column and no rate given");
  return header;
}

// The rows of one group (of the whole table when there are no grouping columns).
struct TableGroup {
  std::vector<std::string> values;
  std::vector<double> times;
  SampleMatrix samples;  // grown by doubling; rows past `rows` are unused
  int64_t rows = 0;
  std::vector<std::string> classes;
  int64_t first_line = 0;
};

// Rate, start and (when irregular) time stamps of a stream from its rows' times; the rate
// is the one given when there is one.
void set_time_base(Stream& stream, std::vector<double> times, int64_t rows, bool grouped,
                   const CsvTableOptions& options, const std::string& where) {
  if (options.rate_hz) {
    stream.rate_hz = *options.rate_hz;
  } else if (rows < 2) {
    throw Error(where, std::string(grouped ? "a group of one sample" : "one sample") +
                           " gives no time step: give the rate");
  }
  if (times.empty()) return;
  std::vector<double> steps(times.size() - 1);
  for (size_t k = 1; k < times.size(); ++k) steps[k - 1] = times[k] - times[k - 1];
  if (!options.rate_hz) stream.rate_hz = rate_from_steps(steps);
  stream.start_time = times.front();
  const double step = 1.0 / stream.rate_hz;
  if (std::any_of(steps.begin(), steps.end(), [&](double value) {
        return std::abs(value - step) > kIrregularStepTolerance * step;
      }))
    stream.timestamps = std::move(times);
}

}  // namespace

std::vector<ImportedRecording> import_csv_table(const std::string& path, const SkinLayout& layout,
                                                const CsvTableOptions& options) {
  if (options.rate_hz) check_rate(*options.rate_hz, "rate_hz");
  const int64_t content_lines = csv::count_content_lines(path);
  if (content_lines == 0) throw Error(path, "empty file");
  const auto channel_count = static_cast<Eigen::Index>(layout.channels.size());
  csv::LineReader reader(path);
  const TableHeader header = read_header(reader, layout, options);
  const int64_t rows = content_lines - 1;
  if (rows == 0) throw Error(path, "a header but no data rows");
  const bool grouped = !header.group_columns.empty();

  std::vector<TableGroup> groups;
  std::map<std::string, size_t> index;
  int64_t row_count = 0;
  for_each_row(reader, [&](const std::vector<std::string_view>& row, int64_t line) {
    check_cell_count(row.size(), header.names.size(), path, line, "header has");
    if (row_count++ == rows) throw Error(path, "file grew while it was read");
    std::string key;
    std::vector<std::string> values;
    for (size_t column : header.group_columns) {
      values.push_back(csv::unquote(row[column]));
      key += values.back() + '\x1f';
    }
    auto [found, added] = index.emplace(key, groups.size());
    if (added) {
      groups.emplace_back();
      groups.back().values = std::move(values);
      groups.back().first_line = line;
    }
    TableGroup& group = groups[found->second];
    size_t at = 0;
    if (header.has_time) {
      const size_t time_column = header.sample_columns[at++];
      const auto column_number = static_cast<int64_t>(time_column) + 1;
      const double time = csv::parse_double(row[time_column], path, line, column_number);
      if (!group.times.empty() && !(time > group.times.back()))
        throw Error(location(path, line, column_number),
                    "time " + std::string(row[time_column]) + " does not increase on the " +
                        (grouped ? "group's " : "") + "previous row");
      group.times.push_back(time);
    }
    // One table fills a matrix of its counted rows; a group grows its own by doubling.
    if (group.rows == group.samples.rows())
      group.samples.conservativeResize(
          grouped ? std::min<int64_t>(rows, std::max<int64_t>(1024, 2 * group.rows)) : rows,
          channel_count);
    for (Eigen::Index channel = 0; at < header.sample_columns.size(); ++at, ++channel) {
      const size_t column = header.sample_columns[at];
      group.samples(group.rows, channel) =
          csv::parse_float(row[column], path, line, static_cast<int64_t>(column) + 1);
    }
    ++group.rows;
    if (header.class_column) group.classes.push_back(csv::unquote(row[*header.class_column]));
  });
  if (row_count != rows) throw Error(path, "file shrank while it was read");

  std::vector<ImportedRecording> recordings;
  for (TableGroup& group : groups) {
    Stream stream = empty_stream(options.stream_name, layout);
    if (group.samples.rows() != group.rows)
      group.samples.conservativeResize(group.rows, channel_count);
    stream.samples = std::move(group.samples);
    // The class runs below still need the times; without classes the stream takes them.
    set_time_base(stream, header.class_column ? group.times : std::move(group.times), group.rows,
                  grouped, options, grouped ? location(path, group.first_line) : path);
    ImportedRecording imported;
    Recording& recording = imported.recording;
    recording.id = stem_of(path);
    for (size_t k = 0; k < group.values.size(); ++k) {
      recording.id += "-" + group.values[k];
      recording.metadata[options.group_columns[k]] = group.values[k];
    }
    recording.layout_id = layout.id;
    recording.metadata["imported_from"] = file_name_of(path);
    if (header.class_column) {
      // Each run of one class: from its first sample's time to one step past its last.
      const double step = 1.0 / stream.rate_hz;
      std::vector<double> times = group.times;
      if (times.empty())
        for (int64_t row = 0; row < group.rows; ++row)
          times.push_back(static_cast<double>(row) * step);
      for (Label& label : labels_from_frame_classes(group.classes, 0.0, 1.0)) {
        const auto first = static_cast<size_t>(std::llround(label.t0));
        const auto last = static_cast<size_t>(std::llround(label.t1)) - 1;
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

Recording import_csv_long(const std::string& path, const SkinLayout& layout,
                          const CsvLongOptions& options) {
  CsvTableOptions table;
  static_cast<CsvLongOptions&>(table) = options;
  return std::move(import_csv_table(path, layout, table).front().recording);
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
