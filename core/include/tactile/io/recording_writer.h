#pragma once
// RecordingWriter: a recording written as it happens. The file is the same format 2 as
// write_recording's (docs/FILE_FORMAT.md: checksummed HDF5 1.10, Fletcher32 on every chunk,
// min/max overview), written in HDF5's single-writer/multiple-reader mode, which keeps the
// file whole on disk at every moment: killed at any instant, it opens (RecordingFile sees it
// as cut_off()) with every sample up to the last flush. Samples are flushed whenever a
// second of them (`flush_seconds`) has gathered, so a crash loses at most that much.
//
// One regular stream; appends come from one thread at a time.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile {

struct RecordingWriterOptions {
  double flush_seconds = 1.0;  // of samples gathered before they go to disk
};

class RecordingWriter {
 public:
  // Creates `path`, which must not exist (a recording is never written over another file),
  // with the recording's attributes and an empty stream of `channels` (units alike, or
  // empty). Throws tactile::Error naming the file.
  RecordingWriter(const std::string& path, const std::string& recording_id,
                  const std::string& layout_id, const Metadata& metadata, const std::string& stream,
                  double rate_hz, double start_time, const std::vector<std::string>& channels,
                  const std::vector<std::string>& units,
                  const RecordingWriterOptions& options = {});
  ~RecordingWriter();  // finish(), errors swallowed (call finish() to see them)
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // Appends samples: rows = samples, one column per channel (NaN: a gap). Writes to disk
  // when a flush is due. Throws tactile::Error on a wrong column count or an I/O failure.
  void append(const SampleMatrix& rows);
  // Writes what is gathered now and flushes the file.
  void flush();
  // Writes the rest and closes the file: an ordinary recording from then on. Idempotent.
  void finish();

  const std::string& path() const { return path_; }
  int64_t samples() const { return appended_; }         // appended so far
  int64_t samples_on_disk() const { return written_; }  // as of the last flush
  int64_t chunk_samples() const { return chunk_; }
  // The file's size as of the last flush (what the recording has taken of its disk so far).
  int64_t file_bytes() const { return file_bytes_; }
  bool finished() const;

 private:
  struct Handles;
  std::string path_;
  int channels_;
  int64_t chunk_;
  int64_t flush_every_;
  std::unique_ptr<Handles> handles_;
  std::vector<float> pending_;  // [channels][pending samples], channel after channel
  int64_t pending_count_ = 0;
  int64_t appended_ = 0;
  int64_t written_ = 0;
  int64_t file_bytes_ = 0;
  // The overview block being filled (per channel) and the first block not yet final on disk.
  std::vector<float> block_min_, block_max_;
};

}  // namespace tactile
