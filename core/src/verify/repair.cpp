// tactile repair: see tactile/verify/repair.h.
#include "tactile/verify/repair.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/hdf5_object.h"
#include "tactile/io/recording_writer.h"
#include "tactile/verify/verify.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f s", seconds);
  return text;
}

std::string span_text(const StreamInfo& stream, int64_t first, int64_t end) {
  return "samples [" + std::to_string(first) + ", " + std::to_string(end) + ") (" +
         seconds_text(static_cast<double>(first) / stream.rate_hz) + " to " +
         seconds_text(static_cast<double>(end) / stream.rate_hz) + ")";
}

// Reads a stream's samples in whole steps of chunks; a channel's chunk that cannot be read
// becomes a gap and one line of `lost`.
class StreamReader {
 public:
  StreamReader(const RecordingFile& file, const StreamInfo& stream, std::vector<std::string>& lost)
      : file_(file), stream_(stream), lost_(lost) {
    chunk_ = std::max<int64_t>(1, file.chunk_samples(stream.name));
    step_ = std::max<int64_t>(1, 8192 / chunk_) * chunk_;
  }
  int64_t step() const { return step_; }

  SampleMatrix read(int64_t first, int64_t count) const {
    try {
      return file_.read(stream_.name, first, count);
    } catch (const Error&) {
    }
    const int channels = static_cast<int>(stream_.channels.size());
    SampleMatrix samples(count, channels);
    for (int channel = 0; channel < channels; ++channel)
      for (int64_t from = first; from < first + count;) {
        const int64_t end = std::min(first + count, (from / chunk_ + 1) * chunk_);
        try {
          const std::vector<float> values =
              file_.read_channel(stream_.name, channel, from, end - from);
          for (int64_t k = from; k < end; ++k)
            samples(k - first, channel) = values[static_cast<size_t>(k - from)];
        } catch (const Error& error) {
          samples.col(channel)
              .segment(from - first, end - from)
              .setConstant(std::numeric_limits<float>::quiet_NaN());
          lost_.push_back("/streams/" + stream_.name + " channel " +
                          stream_.channels[static_cast<size_t>(channel)] + ", " +
                          span_text(stream_, from, end) + ": unreadable (" + error.message() +
                          "), now a gap");
        }
        from = end;
      }
    return samples;
  }

  // The samples a flush completed: the rows after the last one holding any value are what a
  // failed flush claimed but never wrote (they read as the datasets' fill, a gap).
  int64_t written_end() const {
    const int64_t count = stream_.sample_count;
    std::vector<std::string> ignored;
    StreamReader quiet(file_, stream_, ignored);
    for (int64_t end = count; end > 0;) {
      const int64_t first = std::max<int64_t>(0, (end - 1) / step_ * step_);
      const SampleMatrix samples = quiet.read(first, end - first);
      for (int64_t row = samples.rows() - 1; row >= 0; --row)
        if (samples.row(row).unaryExpr([](float v) { return std::isnan(v) ? 0.0f : 1.0f; }).sum() >
            0)
          return first + row + 1;
      end = first;
    }
    return 0;
  }

 private:
  const RecordingFile& file_;
  const StreamInfo& stream_;
  std::vector<std::string>& lost_;
  int64_t chunk_ = 1, step_ = 1;
};

std::string beside(const std::string& path, const std::string& suffix) {
  std::string candidate = path + suffix;
  for (int k = 2; fs::exists(candidate); ++k) candidate = path + suffix + "-" + std::to_string(k);
  return candidate;
}

// The end of a stream that holds nothing, cut; named in `lost`.
int64_t kept_count(const StreamInfo& stream, const StreamReader& reader,
                   std::vector<std::string>& lost) {
  const int64_t end = reader.written_end();
  if (end < stream.sample_count)
    lost.push_back("/streams/" + stream.name + " " + span_text(stream, end, stream.sample_count) +
                   ": never written (the flush that held them failed) or a gap at the end: cut");
  return end;
}

// One regular stream (every live recording): copied chunk step by chunk step, so a recording
// of hours is repaired in bounded memory.
void copy_streaming(const RecordingFile& file, const std::string& target, RepairReport& report) {
  const StreamInfo& stream = file.streams().front();
  StreamReader reader(file, stream, report.lost);
  const int64_t count = kept_count(stream, reader, report.lost);
  RecordingWriterOptions options;
  options.flush_seconds = std::max(1.0, 65536.0 / stream.rate_hz);
  RecordingWriter writer(target, file.recording_id(), file.layout_id(), file.metadata(),
                         stream.name, stream.rate_hz, stream.start_time, stream.channels,
                         stream.units, options);
  for (int64_t first = 0; first < count; first += reader.step())
    writer.append(reader.read(first, std::min(reader.step(), count - first)));
  writer.finish();
  report.rebuilt.push_back("/streams/" + stream.name +
                           ": the overview and the sample count, from " + std::to_string(count) +
                           " samples (" +
                           seconds_text(static_cast<double>(count) / stream.rate_hz) + ")");
}

// Several streams or time stamps: the recording read whole, each stream cut where its data
// (and its time stamps) end.
void copy_whole(const RecordingFile& file, const std::string& target, RepairReport& report) {
  Recording recording;
  recording.id = file.recording_id();
  recording.layout_id = file.layout_id();
  recording.metadata = file.metadata();
  for (const StreamInfo& info : file.streams()) {
    StreamReader reader(file, info, report.lost);
    int64_t count = kept_count(info, reader, report.lost);
    Stream stream = info.empty_stream();
    if (info.has_timestamps) {
      try {
        stream.timestamps = file.read_timestamps(info.name);
      } catch (const Error& error) {
        throw Error(file.path(), "cannot be repaired: the time stamps of /streams/" + info.name +
                                     " are unreadable (" + error.message() + ")");
      }
      int64_t good = 0;
      while (good < count && std::isfinite(stream.timestamps[static_cast<size_t>(good)]) &&
             (good == 0 || stream.timestamps[static_cast<size_t>(good)] >
                               stream.timestamps[static_cast<size_t>(good - 1)]))
        ++good;
      if (good < count)
        report.lost.push_back("/streams/" + info.name + " " + span_text(info, good, count) +
                              ": their time stamps are not in order: cut");
      count = good;
      stream.timestamps.resize(static_cast<size_t>(count));
    }
    stream.samples = SampleMatrix(count, static_cast<Eigen::Index>(info.channels.size()));
    for (int64_t first = 0; first < count; first += reader.step()) {
      const int64_t length = std::min(reader.step(), count - first);
      stream.samples.middleRows(first, length) = reader.read(first, length);
    }
    report.rebuilt.push_back("/streams/" + info.name +
                             ": the overview and the sample count, from " + std::to_string(count) +
                             " samples");
    recording.streams.push_back(std::move(stream));
  }
  write_recording(target, recording);
}

}  // namespace

RepairReport repair_recording(const std::string& path) {
  RepairReport report;
  std::unique_ptr<RecordingFile> file;
  try {
    // A writer that could not even pad its file (a file system without sparse files).
    if (hdf5::pad_to_declared_end(path))
      report.rebuilt.push_back("the file's end, which its writer could not write (read as zeros)");
    file = std::make_unique<RecordingFile>(path);
  } catch (const Error& error) {
    throw Error(path,
                std::string("cannot be repaired: it does not open (") + error.message() + ")");
  }
  // A cut-off file verifies as far as it goes, but claims samples it never wrote.
  if (!file->cut_off() && verify_recording(path).empty()) return report;
  const std::string target = beside(path, ".repairing");
  std::error_code ignored;
  try {
    const auto& streams = file->streams();
    if (streams.size() == 1 && !streams.front().has_timestamps)
      copy_streaming(*file, target, report);
    else
      copy_whole(*file, target, report);
    const std::vector<FileProblem> problems = verify_recording(target);
    if (!problems.empty())
      throw Error(path, "the repaired copy does not verify (" + problems.front().message + ")");
  } catch (const Error& error) {
    fs::remove(target, ignored);
    throw Error(path, std::string("not repaired, the file is as it was: ") + error.what());
  }
  file.reset();
  report.kept_original = beside(path, ".damaged");
  fs::rename(path, report.kept_original);
  fs::rename(target, path);
  report.repaired = true;
  return report;
}

std::vector<std::string> repair_lines(const std::string& path, const RepairReport& report) {
  if (!report.repaired) return {path + ": whole, nothing to repair"};
  std::vector<std::string> lines{path + ": repaired; the damaged original is kept as " +
                                 report.kept_original};
  for (const std::string& line : report.rebuilt) lines.push_back("  rebuilt: " + line);
  if (report.lost.empty()) lines.push_back("  lost: nothing");
  for (const std::string& line : report.lost) lines.push_back("  lost: " + line);
  return lines;
}

}  // namespace tactile
