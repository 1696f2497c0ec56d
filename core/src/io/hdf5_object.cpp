#include "tactile/io/hdf5_object.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

namespace tactile::hdf5 {

void silence_errors() {
  // Per thread in a thread-safe libhdf5: once on each thread that touches a file (the UI,
  // a job, a recorder's writer), so HDF5 never prints its error stack to a user.
  thread_local bool silenced = false;
  if (silenced) return;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  silenced = true;
}

namespace {

// The file driver's message for a failed read or write spans lines ("file write failed: time =
// ..., errno = 28, error message = 'No space left on device', buf = ..."): what happened is
// the system's message, which is what a user is shown.
std::string one_line(std::string message) {
  const size_t quoted = message.find("error message = '");
  if (quoted != std::string::npos) {
    const size_t begin = quoted + 17, end = message.find('\'', begin);
    const std::string action = message.rfind("file read failed", 0) == 0 ? "cannot read the file: "
                               : message.rfind("file write failed", 0) == 0
                                   ? "cannot write the file: "
                                   : "";
    if (end != std::string::npos) return action + message.substr(begin, end - begin);
  }
  const size_t line = message.find('\n');
  if (line != std::string::npos) message.erase(line);
  while (!message.empty() && (message.back() == ',' || message.back() == ' ')) message.pop_back();
  return message;
}

herr_t keep_innermost(unsigned index, const H5E_error2_t* error, void* data) {
  // Walking upward, index 0 is the function that detected the error: the message
  // that says what is actually wrong ("truncated file: eof = ...").
  if (index == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
  return 0;
}

}  // namespace

std::string last_error() {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &message);
  H5Eclear2(H5E_DEFAULT);
  return one_line(std::move(message));
}

void fail(const std::string& where, const std::string& what) {
  const std::string detail = last_error();
  throw Error(where, detail.empty() ? what : what + " (" + detail + ")");
}

void Object::close(const std::string& where) {
  if (id_ < 0) return;
  const herr_t status = closer_ != nullptr ? closer_(id_) : 0;
  id_ = H5I_INVALID_HID;
  if (status < 0) fail(where, "cannot close");
}

Object checked(hid_t id, Object::Closer closer, const std::string& where, const std::string& what) {
  if (id < 0) fail(where, what);
  return Object(id, closer);
}

bool has_link(hid_t location, const std::string& name) {
  return H5Lexists(location, name.c_str(), H5P_DEFAULT) > 0;
}

bool has_attribute(hid_t location, const std::string& name) {
  return H5Aexists(location, name.c_str()) > 0;
}

Object open_group(hid_t location, const std::string& name, const std::string& where) {
  if (!has_link(location, name)) throw Error(where, "missing group");
  return checked(H5Gopen2(location, name.c_str(), H5P_DEFAULT), H5Gclose, where,
                 "cannot open group");
}

Object open_dataset(hid_t location, const std::string& name, const std::string& where) {
  if (!has_link(location, name)) throw Error(where, "missing dataset");
  return checked(H5Dopen2(location, name.c_str(), H5P_DEFAULT), H5Dclose, where,
                 "cannot open dataset");
}

namespace {

// Attributes (and links) stay in the object header, which carries a checksum, up
// to this many; beyond, HDF5 would move them to its dense storage.
constexpr unsigned kMaxCompact = 65535;
constexpr unsigned kDeflateLevel = 4;

void keep_attributes_compact(hid_t properties, const std::string& where) {
  if (H5Pset_attr_phase_change(properties, kMaxCompact, 0) < 0)
    fail(where, "cannot keep attributes in the object header");
}

}  // namespace

Object untimed_dataset_properties(const std::string& where) {
  Object properties =
      checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, where, "cannot create property list");
  if (H5Pset_obj_track_times(properties.id(), false) < 0)
    fail(where, "cannot turn off time stamps");
  keep_attributes_compact(properties.id(), where);
  return properties;
}

void add_checked_storage(hid_t properties, int rank, const hsize_t* shape, const hsize_t* chunk,
                         bool compress, const std::string& where) {
  bool empty = false;
  for (int d = 0; d < rank; ++d) empty = empty || shape[d] == 0;
  if (empty) {
    // No data: the object header (checksummed) is all there is.
    if (H5Pset_layout(properties, H5D_COMPACT) < 0) fail(where, "cannot set compact layout");
    return;
  }
  add_chunked_storage(properties, rank, chunk, compress, where);
}

void add_chunked_storage(hid_t properties, int rank, const hsize_t* chunk, bool compress,
                         const std::string& where) {
  if (H5Pset_chunk(properties, rank, chunk) < 0) fail(where, "cannot set chunking");
  if (compress && (H5Pset_shuffle(properties) < 0 || H5Pset_deflate(properties, kDeflateLevel) < 0))
    fail(where, "cannot set compression");
  // Last in the pipeline: the checksum covers the bytes as stored.
  if (H5Pset_fletcher32(properties) < 0) fail(where, "cannot set the Fletcher32 checksum");
}

Object create_group(hid_t location, const std::string& name, bool track_order,
                    const std::string& where) {
  Object properties = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, where, "property list");
  // No modification times in object headers: the same recording writes the same bytes.
  if (H5Pset_obj_track_times(properties.id(), false) < 0)
    fail(where, "cannot turn off time stamps");
  keep_attributes_compact(properties.id(), where);
  if (H5Pset_link_phase_change(properties.id(), kMaxCompact, 0) < 0)
    fail(where, "cannot keep links in the object header");
  // Tracking creation order lets a reader list streams in the order they were written.
  if (track_order && H5Pset_link_creation_order(properties.id(),
                                                H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0)
    fail(where, "cannot track link order");
  return checked(H5Gcreate2(location, name.c_str(), H5P_DEFAULT, properties.id(), H5P_DEFAULT),
                 H5Gclose, where, "cannot create group");
}

Object fixed_string_type(size_t size) {
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "", "cannot copy string type");
  if (H5Tset_size(type.id(), std::max<size_t>(size, 1)) < 0 ||
      H5Tset_strpad(type.id(), H5T_STR_NULLPAD) < 0 || H5Tset_cset(type.id(), H5T_CSET_UTF8) < 0)
    fail("", "cannot make a fixed-length UTF-8 string type");
  return type;
}

Object string_type() {
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "", "cannot copy string type");
  if (H5Tset_size(type.id(), H5T_VARIABLE) < 0 || H5Tset_cset(type.id(), H5T_CSET_UTF8) < 0)
    fail("", "cannot make a UTF-8 string type");
  return type;
}

//---- Attributes

namespace {

Object attribute_creation_properties(const std::string& where) {
  Object properties =
      checked(H5Pcreate(H5P_ATTRIBUTE_CREATE), H5Pclose, where, "cannot create property list");
  // Metadata keys may be any UTF-8 text.
  if (H5Pset_char_encoding(properties.id(), H5T_CSET_UTF8) < 0)
    fail(where, "cannot set UTF-8 names");
  return properties;
}

void write_attribute(hid_t location, const std::string& name, hid_t file_type, hid_t memory_type,
                     const void* value, const std::string& where) {
  const std::string place = where + " attribute " + name;
  Object space = checked(H5Screate(H5S_SCALAR), H5Sclose, place, "cannot create dataspace");
  Object properties = attribute_creation_properties(place);
  Object attribute = checked(
      H5Acreate2(location, name.c_str(), file_type, space.id(), properties.id(), H5P_DEFAULT),
      H5Aclose, place, "cannot create attribute");
  if (H5Awrite(attribute.id(), memory_type, value) < 0) fail(place, "cannot write attribute");
}

Object open_scalar_attribute(hid_t location, const std::string& name, const std::string& place) {
  if (!has_attribute(location, name)) throw Error(place, "missing attribute");
  Object attribute = checked(H5Aopen(location, name.c_str(), H5P_DEFAULT), H5Aclose, place,
                             "cannot open attribute");
  Object space = checked(H5Aget_space(attribute.id()), H5Sclose, place, "cannot read dataspace");
  if (H5Sget_simple_extent_npoints(space.id()) != 1) throw Error(place, "expected a single value");
  return attribute;
}

void read_numeric_attribute(hid_t location, const std::string& name, hid_t memory_type, void* value,
                            const std::string& where) {
  const std::string place = where + " attribute " + name;
  Object attribute = open_scalar_attribute(location, name, place);
  Object type = checked(H5Aget_type(attribute.id()), H5Tclose, place, "cannot read type");
  const H5T_class_t type_class = H5Tget_class(type.id());
  if (type_class != H5T_INTEGER && type_class != H5T_FLOAT) throw Error(place, "expected a number");
  if (H5Aread(attribute.id(), memory_type, value) < 0) fail(place, "cannot read attribute");
}

}  // namespace

void write_string_attribute(hid_t location, const std::string& name, const std::string& value,
                            const std::string& where) {
  Object type = fixed_string_type(value.size());
  std::string padded = value;
  padded.resize(std::max<size_t>(value.size(), 1), '\0');
  write_attribute(location, name, type.id(), type.id(), padded.data(), where);
}

void write_double_attribute(hid_t location, const std::string& name, double value,
                            const std::string& where) {
  write_attribute(location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, where);
}

void write_int_attribute(hid_t location, const std::string& name, int64_t value,
                         const std::string& where) {
  write_attribute(location, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, where);
}

std::string read_string_attribute(hid_t location, const std::string& name, const std::string& where,
                                  bool allow_variable) {
  const std::string place = where + " attribute " + name;
  Object attribute = open_scalar_attribute(location, name, place);
  Object file_type = checked(H5Aget_type(attribute.id()), H5Tclose, place, "cannot read type");
  if (H5Tget_class(file_type.id()) != H5T_STRING) throw Error(place, "expected a string");
  if (H5Tis_variable_str(file_type.id()) > 0) {
    if (!allow_variable)
      throw Error(place, "a variable-length string, which this format version does not use");
    Object type = string_type();
    char* text = nullptr;
    if (H5Aread(attribute.id(), type.id(), &text) < 0) fail(place, "cannot read attribute");
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const size_t size = H5Tget_size(file_type.id());
  // An attribute lives in its object header, which cannot exceed the file.
  if (size == 0 || size > file_size(location, place))
    throw Error(place, "string of " + std::to_string(size) + " bytes in a file of " +
                           std::to_string(file_size(location, place)));
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, place, "cannot copy string type");
  H5Tset_size(type.id(), size);
  H5Tset_strpad(type.id(), H5T_STR_NULLPAD);
  H5Tset_cset(type.id(), H5Tget_cset(file_type.id()));  // HDF5 converts no character sets
  std::string value(size, '\0');
  if (H5Aread(attribute.id(), type.id(), value.data()) < 0) fail(place, "cannot read attribute");
  value.resize(std::strlen(value.c_str()));
  return value;
}

double read_double_attribute(hid_t location, const std::string& name, const std::string& where) {
  double value = 0.0;
  read_numeric_attribute(location, name, H5T_NATIVE_DOUBLE, &value, where);
  return value;
}

int64_t read_int_attribute(hid_t location, const std::string& name, const std::string& where) {
  int64_t value = 0;
  read_numeric_attribute(location, name, H5T_NATIVE_INT64, &value, where);
  return value;
}

namespace {

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

}  // namespace

std::vector<std::string> attribute_names(hid_t location, const std::string& where) {
  std::vector<std::string> names;
  hsize_t index = 0;
  if (H5Aiterate2(location, H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names) < 0)
    fail(where, "cannot list attributes");
  return names;
}

//---- Datasets

void check_unique_names(const std::vector<std::string>& names, const std::string& where) {
  std::map<std::string, size_t> first;
  for (size_t index = 0; index < names.size(); ++index) {
    const auto [at, inserted] = first.emplace(names[index], index);
    if (!inserted)
      throw Error(where, "channel name '" + names[index] + "' is used by channels " +
                             std::to_string(at->second) + " and " + std::to_string(index));
  }
}

uint64_t file_size(hid_t location, const std::string& where) {
  const hid_t file = H5Iget_file_id(location);
  if (file < 0) fail(where, "cannot find the file");
  hsize_t size = 0;
  const herr_t status = H5Fget_filesize(file, &size);
  H5Fclose(file);
  if (status < 0) fail(where, "cannot read the file's size");
  return size;
}

void check_declared_size(hid_t dataset, double bytes, const std::string& where) {
  Object properties =
      checked(H5Dget_create_plist(dataset), H5Pclose, where, "cannot read dataset properties");
  double expansion = 1.0;
  const int filters = H5Pget_nfilters(properties.id());
  if (filters < 0) fail(where, "cannot read filters");
  for (int index = 0; index < filters; ++index) {
    unsigned flags = 0;
    size_t values = 0;
    unsigned config = 0;
    const H5Z_filter_t filter = H5Pget_filter2(properties.id(), static_cast<unsigned>(index),
                                               &flags, &values, nullptr, 0, nullptr, &config);
    if (filter == H5Z_FILTER_DEFLATE)
      expansion = 1032.0;  // deflate's largest compression ratio
    else if (filter != H5Z_FILTER_SHUFFLE && filter != H5Z_FILTER_FLETCHER32)
      throw Error(where, "stored through HDF5 filter " + std::to_string(filter) +
                             ", which this program does not read");
  }
  const double limit = static_cast<double>(file_size(dataset, where)) * expansion;
  if (bytes > limit)
    throw Error(where, "declares " + std::to_string(static_cast<uint64_t>(bytes)) +
                           " bytes of data, more than a file of " +
                           std::to_string(file_size(dataset, where)) + " bytes can hold");
}

std::vector<hsize_t> dataset_shape(hid_t dataset, const std::string& where) {
  Object space = checked(H5Dget_space(dataset), H5Sclose, where, "cannot read dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (rank < 0) fail(where, "cannot read rank");
  std::vector<hsize_t> shape(static_cast<size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.id(), shape.data(), nullptr) < 0)
    fail(where, "cannot read shape");
  return shape;
}

H5T_class_t dataset_class(hid_t dataset, const std::string& where) {
  Object type = checked(H5Dget_type(dataset), H5Tclose, where, "cannot read type");
  return H5Tget_class(type.id());
}

void write_strings(hid_t location, const std::string& name, const std::vector<std::string>& values,
                   const std::string& where) {
  const hsize_t count = values.size();
  size_t size = 1;
  for (const std::string& value : values) size = std::max(size, value.size());
  Object space = checked(H5Screate_simple(1, &count, nullptr), H5Sclose, where, "dataspace");
  Object type = fixed_string_type(size);
  Object properties = untimed_dataset_properties(where);
  // Not compressed: a reader can check the declared size against the file's.
  add_checked_storage(properties.id(), 1, &count, &count, false, where);
  Object dataset = checked(H5Dcreate2(location, name.c_str(), type.id(), space.id(), H5P_DEFAULT,
                                      properties.id(), H5P_DEFAULT),
                           H5Dclose, where, "cannot create dataset");
  std::vector<char> buffer(size * values.size(), '\0');
  for (size_t index = 0; index < values.size(); ++index)
    std::copy(values[index].begin(), values[index].end(), buffer.begin() + index * size);
  if (count > 0 &&
      H5Dwrite(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
    fail(where, "cannot write dataset");
}

std::vector<std::string> read_strings(hid_t location, const std::string& name,
                                      const std::string& where, bool allow_variable) {
  Object dataset = open_dataset(location, name, where);
  const std::vector<hsize_t> shape = dataset_shape(dataset.id(), where);
  if (shape.size() != 1) throw Error(where, "expected a 1-D dataset of strings");
  Object file_type = checked(H5Dget_type(dataset.id()), H5Tclose, where, "cannot read type");
  if (H5Tget_class(file_type.id()) != H5T_STRING) throw Error(where, "expected strings");
  const bool variable = H5Tis_variable_str(file_type.id()) > 0;
  if (variable && !allow_variable)
    throw Error(where, "variable-length strings, which this format version does not use");
  const size_t count = shape[0];
  // A variable-length string takes at least 16 bytes in the dataset (length and heap id).
  const size_t element = variable ? 16 : H5Tget_size(file_type.id());
  if (element == 0) throw Error(where, "strings of 0 bytes");
  check_declared_size(dataset.id(), static_cast<double>(count) * static_cast<double>(element),
                      where);
  std::vector<std::string> values;
  values.reserve(count);
  if (count == 0) return values;
  if (variable) {
    Object type = string_type();
    std::vector<char*> pointers(count, nullptr);
    if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0)
      fail(where, "cannot read dataset");
    for (char* text : pointers) values.emplace_back(text != nullptr ? text : "");
    Object space = checked(H5Dget_space(dataset.id()), H5Sclose, where, "dataspace");
    H5Dvlen_reclaim(type.id(), space.id(), H5P_DEFAULT, pointers.data());
    return values;
  }
  const size_t size = H5Tget_size(file_type.id());
  Object type = checked(H5Tcopy(H5T_C_S1), H5Tclose, where, "cannot copy string type");
  H5Tset_size(type.id(), size);
  H5Tset_strpad(type.id(), H5T_STR_NULLPAD);
  H5Tset_cset(type.id(), H5Tget_cset(file_type.id()));  // HDF5 converts no character sets
  std::vector<char> buffer(size * count, '\0');
  if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0)
    fail(where, "cannot read dataset");
  for (size_t index = 0; index < count; ++index) {
    const char* begin = buffer.data() + index * size;
    values.emplace_back(begin, strnlen(begin, size));
  }
  return values;
}

// The end of file address of an HDF5 superblock (format spec, "Superblock": versions 0-3),
// absolute; nothing when no superblock is found where HDF5 looks for one (offset 0, 512,
// 1024, ...) or its fields do not fit.
namespace {

// A little-endian number of `size` (1 to 8) bytes at `at`; none when it lies past the image.
std::optional<uint64_t> little_endian_at(std::span<const uint8_t> image, uint64_t at, size_t size) {
  if (size == 0 || size > 8 || at > image.size() || image.size() - at < size) return {};
  uint64_t value = 0;
  for (size_t k = 0; k < size; ++k) value |= static_cast<uint64_t>(image[at + k]) << (8 * k);
  return value;
}

// Where the superblock starts: at 0, or after a user block of 512, 1024, 2048... bytes.
std::optional<size_t> superblock_at(std::span<const uint8_t> image) {
  static const uint8_t kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  for (size_t at = 0; at + 16 <= image.size(); at = at == 0 ? 512 : 2 * at)
    if (std::equal(kSignature, kSignature + 8, image.begin() + static_cast<std::ptrdiff_t>(at)))
      return at;
  return {};
}

}  // namespace

std::optional<uint64_t> superblock_end_of_file(std::span<const uint8_t> image) {
  const std::optional<size_t> at = superblock_at(image);
  if (!at) return {};
  const uint8_t version = image[*at + 8];
  size_t offsets = 0, base_at = 0;
  if (version == 0 || version == 1) {
    offsets = image[*at + 13];
    base_at = *at + (version == 0 ? 24 : 28);
  } else if (version == 2 || version == 3) {
    offsets = image[*at + 9];
    base_at = *at + 12;
  } else {
    return {};
  }
  const auto base = little_endian_at(image, base_at, offsets);
  const auto end = little_endian_at(image, base_at + 2 * offsets, offsets);
  if (!base || !end || *end > UINT64_MAX - *base) return {};
  return *base + *end;
}

namespace {

// A little-endian number of `size` bytes at `at` of a file or image; none past its end.
using ByteReader = std::function<std::optional<uint64_t>(uint64_t at, size_t size)>;

// The driver information block of the version 0 or 1 superblock at `superblock` checked against
// a file of `file_size` bytes read through `read`.
std::optional<std::string> driver_info_problem(uint64_t superblock, uint64_t file_size,
                                               const ByteReader& read) {
  const auto version = read(superblock + 8, 1);
  const auto offsets = read(superblock + 13, 1);
  // Versions 2 and 3 have no driver information block (a superblock extension instead).
  if (!version || !offsets || (*version != 0 && *version != 1) || *offsets != 8) return {};
  const uint64_t fields_at = superblock + (*version == 0 ? 24 : 28);
  const auto base = read(fields_at, 8);
  const auto driver = read(fields_at + 24, 8);
  if (!base || !driver || *driver == UINT64_MAX) return {};
  const std::string past_end = "byte " + std::to_string(fields_at + 24) +
                               ": a driver information block past the end of the file";
  if (*base > file_size || *driver > file_size - *base || file_size - *base - *driver < 16)
    return past_end;
  const auto size = read(*base + *driver + 4, 4);
  if (!size || *size > file_size - (*base + *driver + 16)) return past_end;
  return {};
}

}  // namespace

std::optional<std::string> superblock_driver_info_problem(std::span<const uint8_t> image) {
  const std::optional<size_t> at = superblock_at(image);
  if (!at) return {};
  return driver_info_problem(*at, image.size(), [&](uint64_t where, size_t size) {
    return little_endian_at(image, where, size);
  });
}

std::optional<std::string> file_driver_info_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const uintmax_t file_size = std::filesystem::file_size(path, error);
  if (!in || error) return {};  // opening it says what is wrong
  std::vector<uint8_t> head(4096);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const std::optional<size_t> at = superblock_at(head);
  if (!at) return {};
  return driver_info_problem(*at, file_size, [&](uint64_t where, size_t size) {
    std::vector<uint8_t> bytes(size);
    in.clear();
    in.seekg(static_cast<std::streamoff>(where));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
      return std::optional<uint64_t>();
    return little_endian_at(bytes, 0, size);
  });
}

bool pad_to_declared_end(const std::string& path) {
  std::vector<uint8_t> head(4096);
  FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  head.resize(std::fread(head.data(), 1, head.size(), file));
  std::fclose(file);
  const std::optional<uint64_t> end = superblock_end_of_file(head);
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (!end || error || *end <= size) return false;
  std::filesystem::resize_file(path, *end, error);
  return !error;
}

}  // namespace tactile::hdf5
