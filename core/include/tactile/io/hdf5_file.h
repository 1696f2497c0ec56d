#pragma once
// Recordings on disk: the native HDF5 file (layout described in docs/FILE_FORMAT.md).
// RecordingFile opens a file and reads only its attributes and dataset shapes, so a
// viewer can show an hour of data from the min/max overview and read the few chunks
// of a time range on demand.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile {

// Current value of the root attribute `format_version`. Format 2 (HDF5 1.10 file
// format, Fletcher32 on every chunk, fixed-length strings) lets every damaged byte
// be caught; files of format 1 are still read (`tactile upgrade` rewrites them).
inline constexpr int kRecordingFormatVersion = 2;
// Samples per block of the min/max overview written by write_recording.
inline constexpr int64_t kOverviewBlock = 256;

// Writes the whole recording to a temporary file beside `path`, then renames it over
// `path`: readers see the old file or the new one, never half of one. Throws
// tactile::Error (naming the file and the stream) on invalid content or I/O failure,
// and leaves no temporary file behind.
void write_recording(const std::string& path, const Recording& recording);

// Reads everything. Throws tactile::Error naming the file and the dataset. With `step`, each
// stream is read in blocks of about a million values and step(share read) is called after
// each (a job's progress and cancel: the callback throws).
Recording read_recording(const std::string& path, const std::function<void(double)>& step = {});

struct StreamInfo {
  std::string name;
  double rate_hz = 0.0;
  double start_time = 0.0;
  std::vector<std::string> channels;
  std::vector<std::string> units;
  int64_t sample_count = 0;
  bool has_timestamps = false;
  // Irregular streams need their time stamps for the duration; the first and last
  // are read when the file is opened. Meaningful only when has_timestamps.
  double first_timestamp = 0.0;
  double last_timestamp = 0.0;
  // Seconds covered, as Stream::duration() of the same stream.
  double duration() const;
  // A Stream of this name, rate, start, channels and units, without samples (to be read in).
  Stream empty_stream() const;
};

class RecordingFile {
 public:
  // Opens the file and checks its format, attributes and every dataset shape.
  // Throws tactile::Error naming the file and the offending dataset.
  explicit RecordingFile(const std::string& path);
  // The same for a file held in memory (an HDF5 file image, e.g. received or fuzzed); `name`
  // stands for the path in messages. The bytes are copied.
  static RecordingFile from_image(std::span<const uint8_t> image, const std::string& name);
  ~RecordingFile();
  RecordingFile(RecordingFile&&) noexcept;
  RecordingFile& operator=(RecordingFile&&) noexcept;
  RecordingFile(const RecordingFile&) = delete;
  RecordingFile& operator=(const RecordingFile&) = delete;

  const std::string& path() const { return path_; }
  // The file's format_version: 1 (no checksums) or 2.
  int format_version() const { return format_version_; }
  // The file was not closed by its writer (a live recording still being written, or one whose
  // writer was killed), or its writer failed mid-flush (a full disk) and claimed samples it
  // never wrote. Its streams hold the samples written up to the last flush; `tactile repair`
  // makes it a whole file again.
  bool cut_off() const { return cut_off_; }
  const std::string& layout_id() const { return layout_id_; }
  const std::string& recording_id() const { return recording_id_; }
  const Metadata& metadata() const { return metadata_; }
  const std::vector<StreamInfo>& streams() const { return streams_; }
  // Throws tactile::Error when the file has no such stream.
  const StreamInfo& stream(const std::string& name) const;

  // Samples [first, first + count) of every channel: rows = samples, cols = channels.
  SampleMatrix read(const std::string& stream, int64_t first, int64_t count) const;
  std::vector<float> read_channel(const std::string& stream, int channel, int64_t first,
                                  int64_t count) const;
  // Samples [first, first + count) of channels [channel_first, channel_first +
  // channel_count): rows = samples, cols = channels.
  SampleMatrix read_channels(const std::string& stream, int channel_first, int channel_count,
                             int64_t first, int64_t count) const;
  // Samples per stored chunk along time (the unit a reader decompresses); 0 when the
  // samples are not chunked.
  int64_t chunk_samples(const std::string& stream) const;
  // Empty for a regularly sampled stream (as Stream::timestamps).
  std::vector<double> read_timestamps(const std::string& stream) const;
  // Per-block {min, max}: rows = blocks of overview_block() samples, cols = channels.
  std::pair<SampleMatrix, SampleMatrix> read_overview(const std::string& stream) const;
  int64_t overview_block() const { return overview_block_; }
  Recording read_all(const std::function<void(double)>& step = {}) const;

 private:
  RecordingFile() = default;
  void load();    // reads the structure of the open file_ (format, metadata, streams)
  struct Handle;  // the open HDF5 file
  std::string path_;
  std::unique_ptr<Handle> file_;
  std::string layout_id_;
  std::string recording_id_;
  Metadata metadata_;
  std::vector<StreamInfo> streams_;
  int64_t overview_block_ = kOverviewBlock;
  int format_version_ = kRecordingFormatVersion;
  bool cut_off_ = false;
};

}  // namespace tactile
