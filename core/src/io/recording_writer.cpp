// A recording written while it happens, in HDF5's single-writer/multiple-reader mode.
#include "tactile/io/recording_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "tactile/io/hdf5_file.h"
#include "tactile/io/hdf5_object.h"
#include "tactile/io/minmax_pyramid.h"

namespace tactile {

using hdf5::checked;
using hdf5::fail;
using hdf5::Object;

namespace {

// Overview blocks per chunk: small and uncompressed, so the block being filled is written
// in place at every flush instead of being stored again.
constexpr hsize_t kOverviewChunk = 64;

Object growing_dataset(hid_t group, const char* name, hsize_t channels, hsize_t chunk_columns,
                       bool compress, size_t cache_bytes, const std::string& where) {
  const hsize_t shape[2] = {channels, 0};
  const hsize_t limit[2] = {channels, H5S_UNLIMITED};
  Object space = checked(H5Screate_simple(2, shape, limit), H5Sclose, where, "dataspace");
  Object properties = hdf5::untimed_dataset_properties(where);
  const hsize_t chunk[2] = {1, chunk_columns};
  hdf5::add_chunked_storage(properties.id(), 2, chunk, compress, where);
  // What no flush wrote reads as a gap, never as numbers: after a failed flush the extent may
  // already cover samples whose chunks never reached the disk (`tactile repair` cuts them).
  const float gap = std::numeric_limits<float>::quiet_NaN();
  if (H5Pset_fill_value(properties.id(), H5T_NATIVE_FLOAT, &gap) < 0)
    fail(where, "cannot set the fill value");
  // Every channel's chunk being filled stays in the cache between flushes.
  Object access = checked(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose, where, "property list");
  if (H5Pset_chunk_cache(access.id(), 12421, cache_bytes, 1.0) < 0)
    fail(where, "cannot size the chunk cache");
  return checked(H5Dcreate2(group, name, H5T_IEEE_F32LE, space.id(), H5P_DEFAULT, properties.id(),
                            access.id()),
                 H5Dclose, where, "cannot create dataset");
}

// Writes the [channels][count] block at column `first` of a growing dataset, growing it.
void append_columns(hid_t dataset, hsize_t channels, hsize_t first, hsize_t count,
                    const float* data, const std::string& where) {
  if (count == 0) return;
  const hsize_t extent[2] = {channels, first + count};
  if (H5Dset_extent(dataset, extent) < 0) fail(where, "cannot grow the dataset");
  Object file_space = checked(H5Dget_space(dataset), H5Sclose, where, "dataspace");
  const hsize_t start[2] = {0, first};
  const hsize_t size[2] = {channels, count};
  if (H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, start, nullptr, size, nullptr) < 0)
    fail(where, "cannot select");
  Object memory_space = checked(H5Screate_simple(2, size, nullptr), H5Sclose, where, "dataspace");
  if (H5Dwrite(dataset, H5T_NATIVE_FLOAT, memory_space.id(), file_space.id(), H5P_DEFAULT, data) <
      0)
    fail(where, "cannot write");
}

}  // namespace

struct RecordingWriter::Handles {
  Object file, samples, overview_min, overview_max;
  std::string where;  // FILE:/streams/NAME
};

RecordingWriter::RecordingWriter(const std::string& path, const std::string& recording_id,
                                 const std::string& layout_id, const Metadata& metadata,
                                 const std::string& stream, double rate_hz, double start_time,
                                 const std::vector<std::string>& channels,
                                 const std::vector<std::string>& units,
                                 const RecordingWriterOptions& options)
    : path_(path), channels_(static_cast<int>(channels.size())) {
  hdf5::silence_errors();
  const std::string where = path + ":/streams/" + stream;
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz))
    throw Error(where, "needs a positive sample rate");
  if (!std::isfinite(start_time)) throw Error(where, "start_time is not finite");
  if (channels.empty()) throw Error(where, "has no channels");
  if (!units.empty() && units.size() != channels.size())
    throw Error(where, std::to_string(units.size()) + " units for " +
                           std::to_string(channels.size()) + " channels");
  if (!(options.flush_seconds > 0.0)) throw Error(path, "flush interval must be positive");
  if (stream.empty() || stream.find('/') != std::string::npos)
    throw Error(where, "invalid stream name");
  hdf5::check_unique_names(channels, where + "/channels");
  std::error_code error;
  if (std::filesystem::exists(path, error))
    throw Error(path, "exists already; a recording is never written over a file");
  // About a second per chunk (whole overview blocks), so a chunk is written once or twice.
  chunk_ = std::clamp<int64_t>(
      (std::llround(std::ceil(rate_hz)) + kOverviewBlock - 1) / kOverviewBlock * kOverviewBlock,
      kOverviewBlock, 8192);
  flush_every_ = std::max<int64_t>(1, std::llround(std::floor(options.flush_seconds * rate_hz)));
  handles_ = std::make_unique<Handles>();
  handles_->where = where;
  try {
    handles_->file = hdf5::create_recording_file(path, path);
    const hid_t file = handles_->file.id();
    hdf5::write_recording_attributes(file, path, recording_id, layout_id, metadata);
    Object streams = hdf5::create_group(file, "streams", true, path + ":/streams");
    Object group = hdf5::create_stream_group(streams.id(), stream, rate_hz, start_time, channels,
                                             units, where);
    const auto count = static_cast<hsize_t>(channels_);
    const size_t cache =
        std::min<size_t>(size_t{64} << 20, count * static_cast<size_t>(chunk_) * 4 * 2 + (1 << 20));
    handles_->samples = growing_dataset(group.id(), "samples", count, static_cast<hsize_t>(chunk_),
                                        true, cache, where + "/samples");
    handles_->overview_min =
        growing_dataset(group.id(), "overview_min", count, kOverviewChunk, false,
                        count * kOverviewChunk * 4 * 2, where + "/overview_min");
    handles_->overview_max =
        growing_dataset(group.id(), "overview_max", count, kOverviewChunk, false,
                        count * kOverviewChunk * 4 * 2, where + "/overview_max");
    // From here on the file on disk is whole after every flush, whatever happens to us.
    if (H5Fstart_swmr_write(file) < 0) fail(path, "cannot start single-writer mode");
  } catch (...) {
    handles_.reset();
    std::filesystem::remove(path, error);
    throw;
  }
  block_min_.assign(static_cast<size_t>(channels_), std::numeric_limits<float>::infinity());
  block_max_.assign(static_cast<size_t>(channels_), -std::numeric_limits<float>::infinity());
}

RecordingWriter::~RecordingWriter() {
  hdf5::silence_errors();
  try {
    finish();
  } catch (const std::exception&) {
    // The file holds what was flushed before; finish() is where errors are reported.
  }
}

bool RecordingWriter::finished() const { return !handles_; }

void RecordingWriter::append(const SampleMatrix& rows) {
  hdf5::silence_errors();  // appends may come from a thread of their own (a live recorder's)
  if (!handles_) throw Error(path_, "the recording is finished");
  if (rows.cols() != channels_)
    throw Error(handles_->where, std::to_string(rows.cols()) + " values per sample for " +
                                     std::to_string(channels_) + " channels");
  for (Eigen::Index row = 0; row < rows.rows(); ++row)
    for (Eigen::Index column = 0; column < rows.cols(); ++column)
      pending_.push_back(rows(row, column));
  pending_count_ += rows.rows();
  appended_ += rows.rows();
  if (pending_count_ >= flush_every_) flush();
}

void RecordingWriter::flush() {
  if (!handles_) return;
  hdf5::silence_errors();
  const std::string& where = handles_->where;
  const auto channels = static_cast<hsize_t>(channels_);
  if (pending_count_ > 0) {
    // [samples][channels] as gathered -> [channels][samples] as stored.
    std::vector<float> columns(pending_.size());
    for (int64_t sample = 0; sample < pending_count_; ++sample)
      for (int channel = 0; channel < channels_; ++channel)
        columns[static_cast<size_t>(channel * pending_count_ + sample)] =
            pending_[static_cast<size_t>(sample * channels_ + channel)];
    append_columns(handles_->samples.id(), channels, static_cast<hsize_t>(written_),
                   static_cast<hsize_t>(pending_count_), columns.data(), where + "/samples");
    // The samples reach the disk before their overview does: when a write fails (a full
    // disk), the overview on disk summarises only samples that are there, and a reader ends
    // the recording where the two agree.
    if (H5Dflush(handles_->samples.id()) < 0) fail(where + "/samples", "cannot flush");
    // The overview blocks these samples touch: the one being filled goes on from before.
    const int64_t first_block = written_ / kOverviewBlock;
    const int64_t end_block = (written_ + pending_count_ + kOverviewBlock - 1) / kOverviewBlock;
    const int64_t blocks = end_block - first_block;
    std::vector<float> minima(static_cast<size_t>(channels_ * blocks)), maxima(minima.size());
    for (int channel = 0; channel < channels_; ++channel) {
      MinMax range{block_min_[static_cast<size_t>(channel)],
                   block_max_[static_cast<size_t>(channel)]};
      for (int64_t sample = 0; sample < pending_count_; ++sample) {
        const int64_t index = written_ + sample;
        if (index % kOverviewBlock == 0) range = MinMax{};
        range.add(columns[static_cast<size_t>(channel * pending_count_ + sample)]);
        const size_t slot =
            static_cast<size_t>(channel * blocks + index / kOverviewBlock - first_block);
        // A block of nothing but gaps is NaN, as write_recording stores it.
        minima[slot] = range.empty() ? std::numeric_limits<float>::quiet_NaN() : range.min;
        maxima[slot] = range.empty() ? std::numeric_limits<float>::quiet_NaN() : range.max;
      }
      // Carried into the next flush unless the block is complete.
      const bool complete = (written_ + pending_count_) % kOverviewBlock == 0;
      block_min_[static_cast<size_t>(channel)] =
          complete ? std::numeric_limits<float>::infinity() : range.min;
      block_max_[static_cast<size_t>(channel)] =
          complete ? -std::numeric_limits<float>::infinity() : range.max;
    }
    append_columns(handles_->overview_min.id(), channels, static_cast<hsize_t>(first_block),
                   static_cast<hsize_t>(blocks), minima.data(), where + "/overview_min");
    append_columns(handles_->overview_max.id(), channels, static_cast<hsize_t>(first_block),
                   static_cast<hsize_t>(blocks), maxima.data(), where + "/overview_max");
    written_ += pending_count_;
    pending_.clear();
    pending_count_ = 0;
  }
  if (H5Fflush(handles_->file.id(), H5F_SCOPE_GLOBAL) < 0) fail(path_, "cannot flush");
  hsize_t size = 0;
  if (H5Fget_filesize(handles_->file.id(), &size) >= 0) file_bytes_ = static_cast<int64_t>(size);
}

void RecordingWriter::finish() {
  if (!handles_) return;
  hdf5::silence_errors();
  std::unique_ptr<Handles> handles;
  try {
    flush();
  } catch (...) {
    handles_.reset();
    // The allocations whose writes failed are past the end of the file: without them HDF5
    // would not open it at all.
    hdf5::pad_to_declared_end(path_);
    throw;
  }
  handles = std::move(handles_);
  handles->samples.close(path_);
  handles->overview_min.close(path_);
  handles->overview_max.close(path_);
  handles->file.close(path_);
}

}  // namespace tactile
