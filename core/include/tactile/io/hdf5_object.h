#pragma once
// Core's own (it includes <hdf5.h>, which only core's sources see): RAII ownership of HDF5
// identifiers and the few typed reads and writes the recording file, its verify and repair,
// and other programs' HDF5 datasets need. Every failure becomes a tactile::Error
// whose `where` is "file.h5:/object/path", with HDF5's own innermost message.

#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/recording.h"

namespace tactile::hdf5 {

// Value of the root attribute `format`, so a reader can tell our files from others.
inline constexpr const char* kFormatName = "tactile-workbench";

// Turns off HDF5's automatic printing of its error stack. The library is built
// thread-safe here, where the setting is per thread, so every entry point calls it (free
// after the first call on a thread).
void silence_errors();

// The most specific message on HDF5's error stack (then clears the stack), or "" .
std::string last_error();

// Throws tactile::Error(where, what + ": " + HDF5's message).
[[noreturn]] void fail(const std::string& where, const std::string& what);

// The end of file address of an HDF5 superblock (format spec, "Superblock": versions 0-3),
// absolute; nothing when no superblock is found where HDF5 looks for one (offset 0, 512,
// 1024, ...) or its fields do not fit.
std::optional<uint64_t> superblock_end_of_file(std::span<const uint8_t> image);

// A version 0 or 1 superblock's driver information block, when it names one, within the image:
// libhdf5 1.10 allocates the size the block declares before it reads it (4 GB under the
// fuzzer: tests/fuzz/regressions/hdf5/driver-info-size-makes-libhdf5-allocate-4-gb.h5). What
// is wrong ("byte N: ..."), or nothing.
std::optional<std::string> superblock_driver_info_problem(std::span<const uint8_t> image);
// The same of a file on disk (its superblock within the first 4 KiB), before libhdf5 opens it.
std::optional<std::string> file_driver_info_problem(const std::string& path);

// A file whose writer failed to write its last allocations (a full disk) is shorter than its
// superblock declares, and HDF5 refuses to open it. Extends it (sparse: no room needed) to the
// declared end; the missing bytes read as zeros, which the checksums of what they held refuse.
// True when the file was extended.
bool pad_to_declared_end(const std::string& path);

// Owns one hid_t and closes it with the function that matches its kind.
class Object {
 public:
  using Closer = herr_t (*)(hid_t);
  Object() = default;
  Object(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Object() { reset(); }
  Object(Object&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  hid_t id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports failure (closing a file flushes it: errors matter).
  void close(const std::string& where);
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Each checks the returned id and throws tactile::Error(where, ...) when it is invalid.
Object checked(hid_t id, Object::Closer closer, const std::string& where, const std::string& what);
Object open_group(hid_t location, const std::string& name, const std::string& where);
Object open_dataset(hid_t location, const std::string& name, const std::string& where);
Object create_group(hid_t location, const std::string& name, bool track_order,
                    const std::string& where);
// A variable-length UTF-8 string type (read from files of format 1 only).
Object string_type();
// A fixed-length UTF-8 string type of `size` bytes (at least 1), padded with NULs.
Object fixed_string_type(size_t size);

bool has_link(hid_t location, const std::string& name);
bool has_attribute(hid_t location, const std::string& name);

//---- Attributes

void write_string_attribute(hid_t location, const std::string& name, const std::string& value,
                            const std::string& where);
void write_double_attribute(hid_t location, const std::string& name, double value,
                            const std::string& where);
void write_int_attribute(hid_t location, const std::string& name, int64_t value,
                         const std::string& where);
// Missing or mistyped attributes throw tactile::Error naming `where` and the attribute.
std::string read_string_attribute(hid_t location, const std::string& name, const std::string& where,
                                  bool allow_variable);
double read_double_attribute(hid_t location, const std::string& name, const std::string& where);
int64_t read_int_attribute(hid_t location, const std::string& name, const std::string& where);
std::vector<std::string> attribute_names(hid_t location, const std::string& where);

//---- Datasets

// Throws tactile::Error(where, ...) naming both positions when a channel name repeats:
// two channels of one name make every lookup by name ambiguous.
void check_unique_names(const std::vector<std::string>& names, const std::string& where);

// The size of the file `location` belongs to, in bytes.
uint64_t file_size(hid_t location, const std::string& where);
// Throws unless a dataset that declares `bytes` of data (uncompressed) can hold them:
// stored without compression it needs as many bytes of the file; deflated, at most
// 1032 times as many (deflate's largest ratio). Refuses filters other than shuffle,
// deflate and Fletcher32. Call before allocating anything for the whole dataset.
void check_declared_size(hid_t dataset, double bytes, const std::string& where);

// Dimensions of a dataset's extent.
std::vector<hsize_t> dataset_shape(hid_t dataset, const std::string& where);
H5T_class_t dataset_class(hid_t dataset, const std::string& where);
void write_strings(hid_t location, const std::string& name, const std::vector<std::string>& values,
                   const std::string& where);
// Reads a 1-D dataset of fixed- or variable-length strings; variable-length ones
// only when `allow_variable` (files of format 1: their bytes live in HDF5's global
// heap, which carries no checksum).
std::vector<std::string> read_strings(hid_t location, const std::string& name,
                                      const std::string& where, bool allow_variable);

// Dataset creation properties with object modification times off (same data, same
// bytes), attributes kept in the checksummed object header however many there are.
Object untimed_dataset_properties(const std::string& where);
// Makes `properties` (dataset creation) store data of `elements` elements covered by
// a check: in the object header when empty (compact), else in chunks of
// `chunk` (per dimension) with Fletcher32 after the optional shuffle and deflate.
void add_checked_storage(hid_t properties, int rank, const hsize_t* shape, const hsize_t* chunk,
                         bool compress, const std::string& where);
// Chunks of `chunk` with Fletcher32 after the optional shuffle and deflate, whatever the
// size (a dataset that grows starts empty).
void add_chunked_storage(hid_t properties, int rank, const hsize_t* chunk, bool compress,
                         const std::string& where);
// A new file in format 2 (HDF5 1.10 file format, no time stamps); fails when `path` exists.
// `where` names it in errors.
Object create_recording_file(const std::string& path, const std::string& where);
// A stream's group with its attributes, channel names and units (empty: none given), before
// its samples.
Object create_stream_group(hid_t streams, const std::string& name, double rate_hz,
                           double start_time, const std::vector<std::string>& channels,
                           const std::vector<std::string>& units, const std::string& where);
// The root attributes and /metadata of a recording.
void write_recording_attributes(hid_t file, const std::string& where,
                                const std::string& recording_id, const std::string& layout_id,
                                const Metadata& metadata);

}  // namespace tactile::hdf5
