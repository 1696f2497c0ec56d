// CSV export in the long shape, written so that import gives back the same bits.
#include <algorithm>
#include <charconv>
#include <fstream>

#include "tactile/error.h"
#include "tactile/formats/csv_files.h"
#include "tactile/io/atomic_file.h"

namespace tactile {

namespace {

// Samples converted to text per step: bounds memory when exporting from a file.
constexpr int64_t kExportBlock = 65536;

// Quotes a header name only when a reader would otherwise split or trim it.
std::string header_cell(const std::string& name) {
  const bool plain = !name.empty() && name.find_first_of(",\"\r\n") == std::string::npos &&
                     name.front() != ' ' && name.back() != ' ';
  if (plain) return name;
  std::string text = "\"";
  for (char character : name)
    text += character == '"' ? std::string("\"\"") : std::string(1, character);
  return text + "\"";
}

// Shortest text that reads back as the same float or double.
template <typename Number>
void append_number(std::string& line, Number value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  line.append(text, result.ptr);
}

size_t find_stream_index(const std::vector<std::string>& names, const std::string& wanted,
                         const std::string& where) {
  if (names.empty()) throw Error(where, "the recording has no streams");
  if (wanted.empty()) return 0;
  const auto found = std::find(names.begin(), names.end(), wanted);
  if (found != names.end()) return static_cast<size_t>(found - names.begin());
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  throw Error(where, "no stream '" + wanted + "' (streams: " + known + ")");
}

// Written atomically (io/atomic_file.h). `read_block(first, count)` gives samples
// [first, first + count) as a SampleMatrix; `time_of(index)` the time of a sample.
template <typename ReadBlock, typename TimeOf>
void write_long_csv(const std::string& path, const std::vector<std::string>& channels,
                    int64_t sample_count, ReadBlock read_block, TimeOf time_of) {
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(path, "cannot create file");
        std::string line = "time_s";
        for (const std::string& channel : channels) {
          line += ',';
          line += header_cell(channel);
        }
        line += '\n';
        out << line;
        for (int64_t first = 0; first < sample_count; first += kExportBlock) {
          const int64_t count = std::min(kExportBlock, sample_count - first);
          const SampleMatrix block = read_block(first, count);
          for (int64_t row = 0; row < count; ++row) {
            line.clear();
            append_number(line, time_of(first + row));
            for (Eigen::Index channel = 0; channel < block.cols(); ++channel) {
              line += ',';
              append_number(line, block(row, channel));
            }
            line += '\n';
            out.write(line.data(), static_cast<std::streamsize>(line.size()));
          }
          if (!out) throw Error(path, "write failed");
        }
        out.close();
        if (!out) throw Error(path, "write failed");
      },
      "CSV file");
}

void check_time_base(double rate_hz, bool has_timestamps, const std::string& where) {
  if (rate_hz <= 0.0 && !has_timestamps)
    throw Error(where, "stream has neither a rate nor time stamps: no time column to write");
}

}  // namespace

void export_csv_long(const std::string& path, const Recording& recording,
                     const std::string& stream_name) {
  std::vector<std::string> names;
  for (const Stream& stream : recording.streams) names.push_back(stream.name);
  const Stream& stream =
      recording.streams[find_stream_index(names, stream_name, "recording " + recording.id)];
  check_time_base(stream.rate_hz, !stream.timestamps.empty(), "stream " + stream.name);
  write_long_csv(
      path, stream.channels, stream.sample_count(),
      [&](int64_t first, int64_t count) -> SampleMatrix {
        return stream.samples.middleRows(first, count);
      },
      [&](int64_t index) { return stream.time_of(index); });
}

void export_csv_long(const std::string& path, const RecordingFile& file,
                     const std::string& stream_name) {
  std::vector<std::string> names;
  for (const StreamInfo& info : file.streams()) names.push_back(info.name);
  const StreamInfo& info = file.streams()[find_stream_index(names, stream_name, file.path())];
  check_time_base(info.rate_hz, info.has_timestamps, file.path() + ":/streams/" + info.name);
  const std::vector<double> timestamps = file.read_timestamps(info.name);
  // The same time base as Stream::time_of, so both exports write identical text.
  Stream time_base;
  time_base.rate_hz = info.rate_hz;
  time_base.start_time = info.start_time;
  write_long_csv(
      path, info.channels, info.sample_count,
      [&](int64_t first, int64_t count) { return file.read(info.name, first, count); },
      [&](int64_t index) {
        return timestamps.empty() ? time_base.time_of(index) : timestamps[size_t(index)];
      });
}

}  // namespace tactile
