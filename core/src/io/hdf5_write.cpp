// Writing the native HDF5 file; the layout is documented in docs/FILE_FORMAT.md.
#include <algorithm>
#include <cmath>
#include <set>

#include "tactile/io/atomic_file.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/hdf5_object.h"

namespace tactile {

namespace {

using hdf5::checked;
using hdf5::fail;
using hdf5::Object;

// Samples per chunk along time: 8192 float32 = 32 KiB. A reader decompresses whole
// chunks, so the skin at one instant (one chunk of every channel) costs about the
// same for a minute or a day of data, and a zoomed-in plot reads little beyond
// what it shows.
constexpr hsize_t kSampleChunk = 8192;
// Overview and time stamps are read whole or in long runs: bigger chunks.
constexpr hsize_t kChunkSamples = 65536;

void check_recording(const std::string& path, const Recording& recording) {
  std::set<std::string> names;
  for (const auto& [key, value] : recording.metadata)
    if (key.empty()) throw Error(path, "metadata has an empty key");
  for (const Stream& stream : recording.streams) {
    const std::string where = path + ":/streams/" + stream.name;
    // A stream name is one HDF5 link name: no separator, not a relative path.
    if (stream.name.empty() || stream.name == "." || stream.name.find('/') != std::string::npos)
      throw Error(where, "invalid stream name '" + stream.name + "'");
    if (!names.insert(stream.name).second) throw Error(where, "duplicate stream name");
    hdf5::check_unique_names(stream.channels, where + "/channels");
    if (static_cast<int64_t>(stream.channels.size()) != stream.channel_count())
      throw Error(where, std::to_string(stream.channels.size()) + " channel names for " +
                             std::to_string(stream.channel_count()) + " sample columns");
    if (!stream.units.empty() && stream.units.size() != stream.channels.size())
      throw Error(where, std::to_string(stream.units.size()) + " units for " +
                             std::to_string(stream.channels.size()) + " channels");
    if (!stream.timestamps.empty() &&
        static_cast<int64_t>(stream.timestamps.size()) != stream.sample_count())
      throw Error(where, std::to_string(stream.timestamps.size()) + " time stamps for " +
                             std::to_string(stream.sample_count()) + " samples");
    if (!std::isfinite(stream.rate_hz) || stream.rate_hz < 0.0)
      throw Error(where, "invalid rate_hz " + std::to_string(stream.rate_hz));
    if (!std::isfinite(stream.start_time)) throw Error(where, "start_time is not finite");
  }
}

// A [rows][columns] dataset written from contiguous memory (row after row), chunked
// along the second dimension, shuffled, deflated and checksummed.
void write_chunked(hid_t location, const std::string& name, hid_t file_type, hid_t memory_type,
                   const void* data, hsize_t rows, hsize_t columns, hsize_t chunk_columns,
                   const std::string& where, bool compress = true) {
  const hsize_t shape[2] = {rows, columns};
  Object space = checked(H5Screate_simple(2, shape, nullptr), H5Sclose, where, "dataspace");
  Object properties = hdf5::untimed_dataset_properties(where);
  const hsize_t chunk[2] = {1, std::min(columns, chunk_columns)};
  hdf5::add_checked_storage(properties.id(), 2, shape, chunk, compress, where);
  Object dataset = checked(H5Dcreate2(location, name.c_str(), file_type, space.id(), H5P_DEFAULT,
                                      properties.id(), H5P_DEFAULT),
                           H5Dclose, where, "cannot create dataset");
  if (rows > 0 && columns > 0 &&
      H5Dwrite(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(where, "cannot write dataset");
}

void write_timestamps(hid_t location, const std::vector<double>& timestamps,
                      const std::string& where) {
  const hsize_t count = timestamps.size();
  Object space = checked(H5Screate_simple(1, &count, nullptr), H5Sclose, where, "dataspace");
  Object properties = hdf5::untimed_dataset_properties(where);
  const hsize_t chunk = std::min<hsize_t>(count, kChunkSamples / 2);
  hdf5::add_checked_storage(properties.id(), 1, &count, &chunk, true, where);
  Object dataset = checked(H5Dcreate2(location, "timestamps", H5T_IEEE_F64LE, space.id(),
                                      H5P_DEFAULT, properties.id(), H5P_DEFAULT),
                           H5Dclose, where, "cannot create dataset");
  if (count > 0 && H5Dwrite(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                            timestamps.data()) < 0)
    fail(where, "cannot write dataset");
}

// Min and max of each block of kOverviewBlock samples, per channel, laid out as
// [channels][blocks] (each channel's blocks contiguous, like the samples).
void write_overview(hid_t group, const Stream& stream, const std::string& where) {
  const int64_t samples = stream.sample_count();
  const int64_t channels = stream.channel_count();
  const int64_t blocks = (samples + kOverviewBlock - 1) / kOverviewBlock;
  std::vector<float> minima(static_cast<size_t>(channels * blocks));
  std::vector<float> maxima(minima.size());
  for (int64_t channel = 0; channel < channels; ++channel) {
    for (int64_t block = 0; block < blocks; ++block) {
      const int64_t first = block * kOverviewBlock;
      const auto values =
          stream.samples.col(channel).segment(first, std::min(kOverviewBlock, samples - first));
      const size_t index = static_cast<size_t>(channel * blocks + block);
      // NaN gaps (a dropped packet) must not hide the values around them.
      minima[index] = values.minCoeff<Eigen::PropagateNumbers>();
      maxima[index] = values.maxCoeff<Eigen::PropagateNumbers>();
    }
  }
  const auto rows = static_cast<hsize_t>(channels);
  const auto columns = static_cast<hsize_t>(blocks);
  write_chunked(group, "overview_min", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, minima.data(), rows,
                columns, kChunkSamples, where + "/overview_min", false);
  write_chunked(group, "overview_max", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, maxima.data(), rows,
                columns, kChunkSamples, where + "/overview_max", false);
}

void write_stream(hid_t streams, const Stream& stream, const std::string& file_where) {
  const std::string where = file_where + ":/streams/" + stream.name;
  Object group = hdf5::create_stream_group(streams, stream.name, stream.rate_hz, stream.start_time,
                                           stream.channels, stream.units, where);
  // Eigen's column-major matrix is channel after channel: exactly [channels][samples].
  write_chunked(group.id(), "samples", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, stream.samples.data(),
                static_cast<hsize_t>(stream.channel_count()),
                static_cast<hsize_t>(stream.sample_count()), kSampleChunk, where + "/samples");
  if (!stream.timestamps.empty())
    write_timestamps(group.id(), stream.timestamps, where + "/timestamps");
  write_overview(group.id(), stream, where);
}

void write_contents(hid_t file, const std::string& path, const Recording& recording) {
  hdf5::write_recording_attributes(file, path, recording.id, recording.layout_id,
                                   recording.metadata);
  Object streams = hdf5::create_group(file, "streams", true, path + ":/streams");
  for (const Stream& stream : recording.streams) write_stream(streams.id(), stream, path);
}

}  // namespace

namespace hdf5 {

Object create_recording_file(const std::string& path, const std::string& where) {
  // The root group's header carries no modification time either.
  Object creation = checked(H5Pcreate(H5P_FILE_CREATE), H5Pclose, where, "property list");
  if (H5Pset_obj_track_times(creation.id(), false) < 0) fail(where, "cannot turn off time stamps");
  // The file format of HDF5 1.10: superblock, object headers and chunk indexes all
  // carry checksums (docs/FILE_FORMAT.md, format 2).
  Object access = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, where, "property list");
  if (H5Pset_libver_bounds(access.id(), H5F_LIBVER_V110, H5F_LIBVER_V110) < 0)
    fail(where, "cannot select the HDF5 1.10 file format");
  return checked(H5Fcreate(path.c_str(), H5F_ACC_EXCL, creation.id(), access.id()), H5Fclose, where,
                 "cannot create file");
}

Object create_stream_group(hid_t streams, const std::string& name, double rate_hz,
                           double start_time, const std::vector<std::string>& channels,
                           const std::vector<std::string>& units, const std::string& where) {
  Object group = create_group(streams, name, false, where);
  write_double_attribute(group.id(), "rate_hz", rate_hz, where);
  write_double_attribute(group.id(), "start_time", start_time, where);
  write_int_attribute(group.id(), "overview_block", kOverviewBlock, where);
  write_strings(group.id(), "channels", channels, where + "/channels");
  write_strings(group.id(), "units",
                units.empty() ? std::vector<std::string>(channels.size()) : units,
                where + "/units");
  return group;
}

void write_recording_attributes(hid_t file, const std::string& path,
                                const std::string& recording_id, const std::string& layout_id,
                                const Metadata& metadata) {
  const std::string root = path + ":/";
  write_string_attribute(file, "format", kFormatName, root);
  write_int_attribute(file, "format_version", kRecordingFormatVersion, root);
  write_string_attribute(file, "layout", layout_id, root);
  write_string_attribute(file, "recording_id", recording_id, root);
  Object group = create_group(file, "metadata", false, path + ":/metadata");
  for (const auto& [key, value] : metadata)
    write_string_attribute(group.id(), key, value, path + ":/metadata");
}

}  // namespace hdf5

void write_recording(const std::string& path, const Recording& recording) {
  hdf5::silence_errors();
  check_recording(path, recording);
  write_file_atomically(
      path,
      [&](const std::string& temporary) {
        Object file = hdf5::create_recording_file(temporary, path);
        write_contents(file.id(), path, recording);
        file.close(path);
      },
      "recording");
}

}  // namespace tactile
