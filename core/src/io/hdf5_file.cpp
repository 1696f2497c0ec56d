// Reading the native HDF5 file; the layout is documented in docs/FILE_FORMAT.md.
#include "tactile/io/hdf5_file.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>

#include "tactile/io/hdf5_object.h"
#include "tactile/io/minmax_pyramid.h"

namespace tactile {

using hdf5::checked;
using hdf5::fail;
using hdf5::Object;

struct RecordingFile::Handle {
  Object file;
};

namespace {

std::string shape_text(const std::vector<hsize_t>& shape) {
  std::string text;
  for (hsize_t extent : shape) text += "[" + std::to_string(extent) + "]";
  return text.empty() ? "scalar" : text;
}

// Opens a dataset and checks its element class and exact shape.
Object open_checked(hid_t group, const std::string& name, const std::vector<hsize_t>& shape,
                    const std::string& where) {
  Object dataset = hdf5::open_dataset(group, name, where);
  const H5T_class_t type_class = hdf5::dataset_class(dataset.id(), where);
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER) throw Error(where, "expected numbers");
  const std::vector<hsize_t> actual = hdf5::dataset_shape(dataset.id(), where);
  if (actual != shape)
    throw Error(where, "shape " + shape_text(actual) + ", expected " + shape_text(shape));
  return dataset;
}

// Reads the [row_count][column_count] block at (row_first, column_first) of a 2-D or
// 1-D (row arguments ignored) dataset into contiguous memory, converting to `memory_type`.
void read_block(hid_t dataset, hid_t memory_type, int rank, hsize_t row_first, hsize_t row_count,
                hsize_t column_first, hsize_t column_count, void* out, const std::string& where) {
  if (row_count == 0 || column_count == 0) return;
  Object file_space = checked(H5Dget_space(dataset), H5Sclose, where, "cannot read dataspace");
  const hsize_t start[2] = {row_first, column_first};
  const hsize_t count[2] = {row_count, column_count};
  const hsize_t* start_of_rank = rank == 2 ? start : start + 1;
  const hsize_t* count_of_rank = rank == 2 ? count : count + 1;
  if (H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, start_of_rank, nullptr, count_of_rank,
                          nullptr) < 0)
    fail(where, "cannot select range");
  Object memory_space = checked(H5Screate_simple(rank, count_of_rank, nullptr), H5Sclose, where,
                                "cannot create dataspace");
  if (H5Dread(dataset, memory_type, memory_space.id(), file_space.id(), H5P_DEFAULT, out) < 0)
    fail(where, "cannot read");
}

herr_t collect_link_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

// Stream names in the order they were written when the file tracks it (ours do),
// else in name order (a file made by another tool).
std::vector<std::string> stream_names(hid_t streams, const std::string& where) {
  Object properties =
      checked(H5Gget_create_plist(streams), H5Pclose, where, "cannot read group properties");
  unsigned order_flags = 0;
  H5Pget_link_creation_order(properties.id(), &order_flags);
  const H5_index_t index_type =
      (order_flags & H5P_CRT_ORDER_INDEXED) != 0 ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  std::vector<std::string> names;
  hsize_t index = 0;
  if (H5Literate(streams, index_type, H5_ITER_INC, &index, collect_link_name, &names) < 0)
    fail(where, "cannot list streams");
  return names;
}

// How many of the last overview block's samples (those from `first` up to `count`) its stored
// minimum and maximum of every channel summarise exactly, as the writer computes them: the
// largest such count, `first` when none. A block that cannot be read counts as agreeing, for
// verify to report.
hsize_t agreeing_count(hid_t group, hid_t samples, hsize_t channels, hsize_t block, hsize_t first,
                       hsize_t count, const std::string& where) {
  const hsize_t length = count - first;
  std::vector<float> values(channels * length), low(channels), high(channels);
  try {
    read_block(samples, H5T_NATIVE_FLOAT, 2, 0, channels, first, length, values.data(),
               where + "/samples");
    Object minimum = hdf5::open_dataset(group, "overview_min", where + "/overview_min");
    Object maximum = hdf5::open_dataset(group, "overview_max", where + "/overview_max");
    read_block(minimum.id(), H5T_NATIVE_FLOAT, 2, 0, channels, first / block, 1, low.data(), where);
    read_block(maximum.id(), H5T_NATIVE_FLOAT, 2, 0, channels, first / block, 1, high.data(),
               where);
  } catch (const Error&) {
    return count;
  }
  auto same = [](float left, float right) {
    return std::memcmp(&left, &right, sizeof left) == 0 || (std::isnan(left) && std::isnan(right));
  };
  std::vector<MinMax> ranges(channels);
  hsize_t agreeing = first;
  for (hsize_t sample = 0; sample < length; ++sample) {
    bool all = true;
    for (hsize_t channel = 0; channel < channels; ++channel) {
      MinMax& range = ranges[channel];
      range.add(values[channel * length + sample]);
      // Nothing but gaps so far: stored as NaN.
      const float nothing = std::numeric_limits<float>::quiet_NaN();
      all = all && same(range.empty() ? nothing : range.min, low[channel]) &&
            same(range.empty() ? nothing : range.max, high[channel]);
    }
    if (all) agreeing = first + sample + 1;
  }
  return agreeing;
}

// A cut-off recording ends where its overview and its samples agree. The writer appends a
// flush's samples, then its overview, so a kill between the two leaves the last block
// summarising fewer samples than the file holds past its start (the flush before's), or, when
// the overview had grown but its values had not reached the disk, none: then the block before
// is the last one written whole, and is checked in turn.
hsize_t summarised_count(hid_t group, hid_t samples, hsize_t channels, hsize_t block, hsize_t count,
                         const std::string& where) {
  while (count > 0 && channels > 0) {
    const hsize_t first = (count - 1) / block * block;
    const hsize_t agreeing = agreeing_count(group, samples, channels, block, first, count, where);
    if (agreeing > first || first == 0) return agreeing;
    count = first;
  }
  return count;
}

// A dataset that grows (written by RecordingWriter as it happened), as opposed to one written
// whole at its final size.
bool grows(hid_t dataset) {
  Object space(H5Dget_space(dataset), H5Sclose);
  hsize_t shape[2] = {0, 0}, limit[2] = {0, 0};
  return space.valid() && H5Sget_simple_extent_ndims(space.id()) == 2 &&
         H5Sget_simple_extent_dims(space.id(), shape, limit) == 2 && limit[1] == H5S_UNLIMITED;
}

// `cut_off` in: the file was not closed by its writer; out: also when its writer failed
// mid-flush (a full disk) and closed it, so samples and overview disagree at the end.
StreamInfo read_stream_info(hid_t streams, const std::string& name, const std::string& path,
                            int format_version, bool& cut_off, int64_t& overview_block) {
  const std::string where = path + ":/streams/" + name;
  Object group = hdf5::open_group(streams, name, where);
  StreamInfo info;
  info.name = name;
  info.rate_hz = hdf5::read_double_attribute(group.id(), "rate_hz", where);
  info.start_time = hdf5::read_double_attribute(group.id(), "start_time", where);
  if (!std::isfinite(info.rate_hz) || info.rate_hz < 0.0)
    throw Error(where + " attribute rate_hz", "invalid rate " + std::to_string(info.rate_hz));
  if (!std::isfinite(info.start_time))
    throw Error(where + " attribute start_time", "not a finite time");
  const int64_t block = hdf5::read_int_attribute(group.id(), "overview_block", where);
  if (block <= 0) throw Error(where + " attribute overview_block", "must be positive");
  if (overview_block > 0 && block != overview_block)
    throw Error(where + " attribute overview_block", std::to_string(block) + " differs from " +
                                                         std::to_string(overview_block) +
                                                         " in an earlier stream");
  overview_block = block;
  const bool variable_strings = format_version == 1;
  info.channels = hdf5::read_strings(group.id(), "channels", where + "/channels", variable_strings);
  hdf5::check_unique_names(info.channels, where + "/channels");
  info.units = hdf5::read_strings(group.id(), "units", where + "/units", variable_strings);
  if (info.units.size() != info.channels.size())
    throw Error(where + "/units", std::to_string(info.units.size()) + " units for " +
                                      std::to_string(info.channels.size()) + " channels");

  Object samples = hdf5::open_dataset(group.id(), "samples", where + "/samples");
  const H5T_class_t samples_class = hdf5::dataset_class(samples.id(), where + "/samples");
  if (samples_class != H5T_FLOAT && samples_class != H5T_INTEGER)
    throw Error(where + "/samples", "expected numbers");
  const std::vector<hsize_t> shape = hdf5::dataset_shape(samples.id(), where + "/samples");
  if (shape.size() != 2 || shape[0] != info.channels.size())
    throw Error(where + "/samples", "shape " + shape_text(shape) + ", expected [" +
                                        std::to_string(info.channels.size()) +
                                        "][samples] for the channels listed");
  const auto channels = static_cast<hsize_t>(info.channels.size());
  auto samples_count = shape[1];
  hdf5::check_declared_size(samples.id(), 4.0 * channels * samples_count, where + "/samples");
  const auto block_size = static_cast<hsize_t>(block);
  // A recording whose writer stopped mid-way (killed, power lost, or a write that failed on a
  // full disk): the samples and the overview were appended in turns, so one may be a flush
  // ahead. The samples both cover and agree on are the recording. A whole growing file agrees
  // at its end (one block read to see it).
  const bool growing = !cut_off && grows(samples.id());
  if (cut_off || growing) {
    const hsize_t extent = samples_count;
    for (const char* overview : {"overview_min", "overview_max"}) {
      Object dataset = hdf5::open_dataset(group.id(), overview, where + "/" + overview);
      const std::vector<hsize_t> covered =
          hdf5::dataset_shape(dataset.id(), where + "/" + overview);
      if (covered.size() == 2) samples_count = std::min(samples_count, covered[1] * block_size);
    }
    samples_count =
        summarised_count(group.id(), samples.id(), channels, block_size, samples_count, where);
    if (growing && samples_count != extent) cut_off = true;
  }
  info.sample_count = static_cast<int64_t>(samples_count);

  info.has_timestamps = hdf5::has_link(group.id(), "timestamps");
  if (info.has_timestamps) {
    const std::string place = where + "/timestamps";
    Object timestamps = open_checked(group.id(), "timestamps", {samples_count}, place);
    hdf5::check_declared_size(timestamps.id(), 8.0 * samples_count, place);
    if (samples_count > 0) {
      read_block(timestamps.id(), H5T_NATIVE_DOUBLE, 1, 0, 1, 0, 1, &info.first_timestamp, place);
      read_block(timestamps.id(), H5T_NATIVE_DOUBLE, 1, 0, 1, samples_count - 1, 1,
                 &info.last_timestamp, place);
    }
  }
  const hsize_t blocks = (samples_count + block_size - 1) / block_size;
  for (const char* overview : {"overview_min", "overview_max"}) {
    const std::string place = where + "/" + overview;
    Object dataset = cut_off || growing
                         ? hdf5::open_dataset(group.id(), overview, place)
                         : open_checked(group.id(), overview, {channels, blocks}, place);
    hdf5::check_declared_size(dataset.id(), 4.0 * channels * blocks, place);
  }
  return info;
}

}  // namespace

double StreamInfo::duration() const {
  if (sample_count == 0) return 0.0;
  if (has_timestamps) return last_timestamp - first_timestamp + (rate_hz > 0 ? 1.0 / rate_hz : 0.0);
  return rate_hz > 0 ? static_cast<double>(sample_count) / rate_hz : 0.0;
}

Stream StreamInfo::empty_stream() const {
  Stream stream;
  stream.name = name;
  stream.rate_hz = rate_hz;
  stream.start_time = start_time;
  stream.channels = channels;
  stream.units = units;
  return stream;
}

RecordingFile::RecordingFile(const std::string& path)
    : path_(path), file_(std::make_unique<Handle>()) {
  hdf5::silence_errors();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    hdf5::last_error();
    throw Error(path, "not an HDF5 file");
  }
  if (const std::optional<std::string> problem = hdf5::file_driver_info_problem(path))
    throw Error(path, *problem);
  Object file_handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file_handle.valid()) {
    const std::string why = hdf5::last_error();
    // A live recording is written in HDF5's single-writer/multiple-reader mode, which keeps
    // the file whole at every moment; one being written now, or whose writer was killed,
    // opens this way (as h5py's swmr=True).
    // Only such a file: a damaged one must be refused at once, not retried.
    if (why.find("already open for write") == std::string::npos)
      throw Error(path, "cannot open HDF5 file (" + why + ")");
    Object access = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, path, "property list");
    // A reader in this mode retries a metadata block whose checksum fails (100 times by
    // default, for a writer caught mid-write); damage must fail at once.
    H5Pset_metadata_read_attempts(access.id(), 1);
    file_handle =
        Object(H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, access.id()), H5Fclose);
    if (!file_handle.valid())
      throw Error(path, "cannot open HDF5 file (" + hdf5::last_error() + ")");
    cut_off_ = true;
  } else {
    // A file this process has open already is shared, and a second open never sees the
    // open-for-write flag: it is cut off if it was opened so before.
    unsigned intent = 0;
    if (H5Fget_intent(file_handle.id(), &intent) >= 0 && (intent & H5F_ACC_SWMR_READ) != 0)
      cut_off_ = true;
  }
  file_->file = std::move(file_handle);
  load();
}

namespace {}  // namespace

RecordingFile RecordingFile::from_image(std::span<const uint8_t> image, const std::string& name) {
  hdf5::silence_errors();
  if (image.empty()) throw Error(name, "empty file");
  RecordingFile result;
  result.path_ = name;
  result.file_ = std::make_unique<Handle>();
  Object access = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, name, "property list");
  // The core driver serves the file from memory; nothing is written back (read-only anyway).
  if (H5Pset_fapl_core(access.id(), 64 * 1024, false) < 0 ||
      H5Pset_file_image(access.id(), const_cast<uint8_t*>(image.data()), image.size()) < 0)
    throw Error(name, "cannot hand the file image to HDF5 (" + hdf5::last_error() + ")");
  // HDF5 hands out the file already open under the same name instead of opening a second
  // one, so every image gets a name of its own.
  if (const std::optional<std::string> problem = hdf5::superblock_driver_info_problem(image))
    throw Error(name, *problem);
  static std::atomic<uint64_t> images{0};
  const std::string unique = name + "#image" + std::to_string(images++);
  Object file_handle(H5Fopen(unique.c_str(), H5F_ACC_RDONLY, access.id()), H5Fclose);
  if (!file_handle.valid()) throw Error(name, "cannot open HDF5 file (" + hdf5::last_error() + ")");
  // On disk HDF5 refuses a file shorter than its superblock's end of file address; from
  // memory it reads zeros past the end instead, so the check is made here.
  const std::optional<uint64_t> end = hdf5::superblock_end_of_file(image);
  if (end && *end > image.size())
    throw Error(name, "truncated file: " + std::to_string(image.size()) + " bytes of the " +
                          std::to_string(*end) + " its superblock declares");
  result.file_->file = std::move(file_handle);
  result.load();
  return result;
}

void RecordingFile::load() {
  const std::string& path = path_;
  const hid_t file = file_->file.id();
  const std::string root = path + ":/";
  if (!hdf5::has_attribute(file, "format"))
    throw Error(root, std::string("no attribute format: not a ") + hdf5::kFormatName + " file");
  // The version decides how strings are read, so it comes first.
  const int64_t version = hdf5::read_int_attribute(file, "format_version", root);
  if (version < 1 || version > kRecordingFormatVersion)
    throw Error(root + " attribute format_version",
                "version " + std::to_string(version) + " is not supported (this program reads " +
                    "1 to " + std::to_string(kRecordingFormatVersion) + ")");
  format_version_ = static_cast<int>(version);
  const bool variable_strings = version == 1;
  const std::string format = hdf5::read_string_attribute(file, "format", root, variable_strings);
  if (format != hdf5::kFormatName)
    throw Error(root + " attribute format",
                "'" + format + "' is not a " + hdf5::kFormatName + " file");
  layout_id_ = hdf5::read_string_attribute(file, "layout", root, variable_strings);
  recording_id_ = hdf5::read_string_attribute(file, "recording_id", root, variable_strings);

  Object metadata = hdf5::open_group(file, "metadata", path + ":/metadata");
  for (const std::string& key : hdf5::attribute_names(metadata.id(), path + ":/metadata"))
    metadata_[key] =
        hdf5::read_string_attribute(metadata.id(), key, path + ":/metadata", variable_strings);

  Object streams = hdf5::open_group(file, "streams", path + ":/streams");
  int64_t block = 0;
  for (const std::string& name : stream_names(streams.id(), path + ":/streams"))
    streams_.push_back(
        read_stream_info(streams.id(), name, path, format_version_, cut_off_, block));
  if (block > 0) overview_block_ = block;
}

RecordingFile::~RecordingFile() = default;
RecordingFile::RecordingFile(RecordingFile&&) noexcept = default;
RecordingFile& RecordingFile::operator=(RecordingFile&&) noexcept = default;

const StreamInfo& RecordingFile::stream(const std::string& name) const {
  for (const StreamInfo& info : streams_)
    if (info.name == name) return info;
  throw Error(path_ + ":/streams/" + name, "no such stream");
}

namespace {

void check_range(const StreamInfo& info, int64_t first, int64_t count, const std::string& where) {
  if (first < 0 || count < 0 || first > info.sample_count - count)
    throw Error(where, "samples [" + std::to_string(first) + ", " + std::to_string(first + count) +
                           ") outside [0, " + std::to_string(info.sample_count) + ")");
}

}  // namespace

SampleMatrix RecordingFile::read(const std::string& stream, int64_t first, int64_t count) const {
  hdf5::silence_errors();
  const StreamInfo& info = this->stream(stream);
  const std::string where = path_ + ":/streams/" + stream + "/samples";
  check_range(info, first, count, where);
  const auto channels = static_cast<hsize_t>(info.channels.size());
  SampleMatrix samples(count, static_cast<Eigen::Index>(channels));
  Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/samples", where);
  // [channels][count] row after row is Eigen's column-major count x channels.
  read_block(dataset.id(), H5T_NATIVE_FLOAT, 2, 0, channels, static_cast<hsize_t>(first),
             static_cast<hsize_t>(count), samples.data(), where);
  return samples;
}

std::vector<float> RecordingFile::read_channel(const std::string& stream, int channel,
                                               int64_t first, int64_t count) const {
  hdf5::silence_errors();
  const StreamInfo& info = this->stream(stream);
  const std::string where = path_ + ":/streams/" + stream + "/samples";
  if (channel < 0 || channel >= static_cast<int>(info.channels.size()))
    throw Error(where, "channel " + std::to_string(channel) + " outside [0, " +
                           std::to_string(info.channels.size()) + ")");
  check_range(info, first, count, where);
  std::vector<float> values(static_cast<size_t>(count));
  Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/samples", where);
  read_block(dataset.id(), H5T_NATIVE_FLOAT, 2, static_cast<hsize_t>(channel), 1,
             static_cast<hsize_t>(first), static_cast<hsize_t>(count), values.data(), where);
  return values;
}

SampleMatrix RecordingFile::read_channels(const std::string& stream, int channel_first,
                                          int channel_count, int64_t first, int64_t count) const {
  hdf5::silence_errors();
  const StreamInfo& info = this->stream(stream);
  const std::string where = path_ + ":/streams/" + stream + "/samples";
  if (channel_first < 0 || channel_count < 0 ||
      channel_first + channel_count > static_cast<int>(info.channels.size()))
    throw Error(where, "channels [" + std::to_string(channel_first) + ", " +
                           std::to_string(channel_first + channel_count) + ") outside [0, " +
                           std::to_string(info.channels.size()) + ")");
  check_range(info, first, count, where);
  SampleMatrix samples(count, channel_count);
  Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/samples", where);
  read_block(dataset.id(), H5T_NATIVE_FLOAT, 2, static_cast<hsize_t>(channel_first),
             static_cast<hsize_t>(channel_count), static_cast<hsize_t>(first),
             static_cast<hsize_t>(count), samples.data(), where);
  return samples;
}

int64_t RecordingFile::chunk_samples(const std::string& stream) const {
  hdf5::silence_errors();
  this->stream(stream);
  const std::string where = path_ + ":/streams/" + stream + "/samples";
  Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/samples", where);
  Object properties =
      checked(H5Dget_create_plist(dataset.id()), H5Pclose, where, "cannot read properties");
  if (H5Pget_layout(properties.id()) != H5D_CHUNKED) return 0;
  hsize_t chunk[2] = {0, 0};
  if (H5Pget_chunk(properties.id(), 2, chunk) != 2) return 0;
  return static_cast<int64_t>(chunk[1]);
}

std::vector<double> RecordingFile::read_timestamps(const std::string& stream) const {
  hdf5::silence_errors();
  const StreamInfo& info = this->stream(stream);
  if (!info.has_timestamps) return {};
  const std::string where = path_ + ":/streams/" + stream + "/timestamps";
  std::vector<double> timestamps(static_cast<size_t>(info.sample_count));
  Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/timestamps", where);
  read_block(dataset.id(), H5T_NATIVE_DOUBLE, 1, 0, 1, 0, timestamps.size(), timestamps.data(),
             where);
  return timestamps;
}

std::pair<SampleMatrix, SampleMatrix> RecordingFile::read_overview(
    const std::string& stream) const {
  hdf5::silence_errors();
  const StreamInfo& info = this->stream(stream);
  const auto channels = static_cast<hsize_t>(info.channels.size());
  const auto blocks =
      static_cast<hsize_t>((info.sample_count + overview_block_ - 1) / overview_block_);
  std::pair<SampleMatrix, SampleMatrix> overview{
      SampleMatrix(static_cast<Eigen::Index>(blocks), static_cast<Eigen::Index>(channels)),
      SampleMatrix(static_cast<Eigen::Index>(blocks), static_cast<Eigen::Index>(channels))};
  for (const auto& [name, matrix] :
       {std::pair{"overview_min", &overview.first}, std::pair{"overview_max", &overview.second}}) {
    const std::string where = path_ + ":/streams/" + stream + "/" + name;
    Object dataset = hdf5::open_dataset(file_->file.id(), "streams/" + stream + "/" + name, where);
    read_block(dataset.id(), H5T_NATIVE_FLOAT, 2, 0, channels, 0, blocks, matrix->data(), where);
  }
  return overview;
}

Recording RecordingFile::read_all(const std::function<void(double)>& step) const {
  int64_t done = 0;  // values read, for step
  Recording recording;
  recording.id = recording_id_;
  recording.layout_id = layout_id_;
  recording.metadata = metadata_;
  for (const StreamInfo& info : streams_) {
    Stream stream = info.empty_stream();
    if (!step) {
      stream.samples = read(info.name, 0, info.sample_count);
    } else {
      int64_t total = 0;
      for (const StreamInfo& each : streams_)
        total += each.sample_count * static_cast<int64_t>(each.channels.size());
      stream.samples.resize(info.sample_count, static_cast<Eigen::Index>(info.channels.size()));
      const int64_t block = std::max<int64_t>(
          1, (int64_t{1} << 20) / std::max<int64_t>(1, static_cast<int64_t>(info.channels.size())));
      for (int64_t first = 0; first < info.sample_count; first += block) {
        const int64_t rows = std::min(block, info.sample_count - first);
        stream.samples.middleRows(first, rows) = read(info.name, first, rows);
        done += rows * static_cast<int64_t>(info.channels.size());
        step(total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0);
      }
    }
    stream.timestamps = read_timestamps(info.name);
    recording.streams.push_back(std::move(stream));
  }
  return recording;
}

Recording read_recording(const std::string& path, const std::function<void(double)>& step) {
  return RecordingFile(path).read_all(step);
}

}  // namespace tactile
