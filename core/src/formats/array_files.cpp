// NumPy, JSON and foreign HDF5 arrays read into recordings (formats/array_files.h).
#include "tactile/formats/array_files.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "hdf5_structure.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_object.h"
#include "zip_archive.h"

namespace tactile {

namespace {

using formats::little16;
using formats::little32;
using formats::zip_content;
using formats::zip_entries;
using formats::ZipEntry;

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Product of a shape, refusing a negative extent or one beyond kMaxImportedElements.
int64_t element_count(const std::vector<int64_t>& shape, const std::string& where) {
  int64_t count = 1;
  for (int64_t extent : shape) {
    if (extent < 0) throw Error(where, "negative extent in the shape");
    if (extent != 0 && count > kMaxImportedElements / extent)
      throw Error(where,
                  "declares more than " + std::to_string(kMaxImportedElements) + " elements");
    count *= extent;
  }
  return count;
}

std::string shape_text(const std::vector<int64_t>& shape) {
  std::string text;
  for (int64_t extent : shape) text += "[" + std::to_string(extent) + "]";
  return text.empty() ? "[] (a scalar)" : text;
}

//---- .npy header: a Python dict literal

struct NpyHeader {
  char order = '<';  // '<', '>', '|'
  char kind = 'f';   // f i u b U S
  int64_t item = 8;  // bytes per element
  bool fortran = false;
  std::vector<int64_t> shape;
};

std::string quoted_value(const std::string& header, const std::string& key,
                         const std::string& where) {
  const size_t at = header.find("'" + key + "'");
  if (at == std::string::npos) throw Error(where, "header has no '" + key + "'");
  const size_t colon = header.find(':', at);
  const size_t open = header.find_first_of("'\"", colon);
  if (colon == std::string::npos || open == std::string::npos)
    throw Error(where, "header's '" + key + "' is not a quoted text");
  const size_t close = header.find(header[open], open + 1);
  if (close == std::string::npos) throw Error(where, "header's '" + key + "' is not closed");
  return header.substr(open + 1, close - open - 1);
}

NpyHeader parse_npy_header(const std::string& header, const std::string& where) {
  NpyHeader parsed;
  const std::string descr = quoted_value(header, "descr", where + " header");
  if (descr.size() < 3 || std::string("<>|=").find(descr[0]) == std::string::npos)
    throw Error(where + " header",
                "descr '" + descr + "' is not a simple type (structured arrays are not read)");
  parsed.order =
      descr[0] == '=' ? (std::endian::native == std::endian::little ? '<' : '>') : descr[0];
  parsed.kind = descr[1];
  int64_t item = 0;
  for (size_t k = 2; k < descr.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(descr[k])) || item > 1'000'000)
      throw Error(where + " header", "descr '" + descr + "' has no size");
    item = item * 10 + (descr[k] - '0');
  }
  const std::string kinds = "fiubUS";
  if (kinds.find(parsed.kind) == std::string::npos)
    throw Error(where + " header",
                "descr '" + descr + "': only bool, integer, float and string arrays are read");
  const bool sized = (parsed.kind == 'f' && (item == 4 || item == 8)) ||
                     ((parsed.kind == 'i' || parsed.kind == 'u') &&
                      (item == 1 || item == 2 || item == 4 || item == 8)) ||
                     (parsed.kind == 'b' && item == 1) ||
                     ((parsed.kind == 'U' || parsed.kind == 'S') && item >= 1);
  if (!sized)
    throw Error(where + " header", "descr '" + descr + "' has a size this reader does not know");
  parsed.item = parsed.kind == 'U' ? item * 4 : item;
  const size_t fortran = header.find("'fortran_order'");
  if (fortran == std::string::npos) throw Error(where + " header", "header has no 'fortran_order'");
  const size_t value = header.find_first_not_of(" :", fortran + 15);
  if (value == std::string::npos) throw Error(where + " header", "'fortran_order' has no value");
  if (header.compare(value, 4, "True") == 0)
    parsed.fortran = true;
  else if (header.compare(value, 5, "False") != 0)
    throw Error(where + " header", "'fortran_order' is neither True nor False");
  const size_t shape = header.find("'shape'");
  const size_t open = shape == std::string::npos ? shape : header.find('(', shape);
  const size_t close = open == std::string::npos ? open : header.find(')', open);
  if (close == std::string::npos) throw Error(where + " header", "header has no 'shape' tuple");
  const std::string tuple = header.substr(open + 1, close - open - 1);
  size_t at = 0;
  while (at < tuple.size()) {
    at = tuple.find_first_not_of(" ,", at);
    if (at == std::string::npos) break;
    size_t end = at;
    int64_t extent = 0;
    while (end < tuple.size() && std::isdigit(static_cast<unsigned char>(tuple[end]))) {
      if (extent > kMaxImportedElements)
        throw Error(where + " header", "shape declares more than " +
                                           std::to_string(kMaxImportedElements) + " elements");
      extent = extent * 10 + (tuple[end++] - '0');
    }
    if (end == at)
      throw Error(where + " header", "shape (" + tuple + ") is not a tuple of whole numbers");
    parsed.shape.push_back(extent);
    at = end;
  }
  return parsed;
}

template <typename T>
T load(const uint8_t* bytes, bool swap) {
  uint8_t copy[sizeof(T)];
  std::memcpy(copy, bytes, sizeof(T));
  if (swap) std::reverse(copy, copy + sizeof(T));
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return value;
}

double number_at(const uint8_t* p, const NpyHeader& header) {
  const bool swap =
      (header.order == '>') != (std::endian::native == std::endian::big) && header.order != '|';
  switch (header.kind) {
    case 'f':
      return header.item == 4 ? load<float>(p, swap) : load<double>(p, swap);
    case 'b':
      return *p != 0 ? 1.0 : 0.0;
    case 'i':
      switch (header.item) {
        case 1:
          return static_cast<int8_t>(*p);
        case 2:
          return load<int16_t>(p, swap);
        case 4:
          return load<int32_t>(p, swap);
        default:
          return static_cast<double>(load<int64_t>(p, swap));
      }
    default:  // 'u'
      switch (header.item) {
        case 1:
          return *p;
        case 2:
          return load<uint16_t>(p, swap);
        case 4:
          return load<uint32_t>(p, swap);
        default:
          return static_cast<double>(load<uint64_t>(p, swap));
      }
  }
}

std::string text_at(const uint8_t* p, const NpyHeader& header) {
  std::string text;
  if (header.kind == 'S') {
    for (int64_t k = 0; k < header.item && p[k] != 0; ++k) text.push_back(static_cast<char>(p[k]));
    return text;
  }
  const bool big = header.order == '>';
  for (int64_t k = 0; k < header.item / 4; ++k) {
    const uint8_t* c = p + 4 * k;
    const uint32_t code =
        big ? (static_cast<uint32_t>(c[0]) << 24 | c[1] << 16 | c[2] << 8 | c[3]) : little32(c);
    if (code == 0) break;
    // UTF-8 of one code point.
    if (code < 0x80) {
      text.push_back(static_cast<char>(code));
    } else if (code < 0x800) {
      text.push_back(static_cast<char>(0xC0 | code >> 6));
      text.push_back(static_cast<char>(0x80 | (code & 0x3F)));
    } else if (code < 0x10000) {
      text.push_back(static_cast<char>(0xE0 | code >> 12));
      text.push_back(static_cast<char>(0x80 | (code >> 6 & 0x3F)));
      text.push_back(static_cast<char>(0x80 | (code & 0x3F)));
    } else {
      text.push_back(static_cast<char>(0xF0 | code >> 18));
      text.push_back(static_cast<char>(0x80 | (code >> 12 & 0x3F)));
      text.push_back(static_cast<char>(0x80 | (code >> 6 & 0x3F)));
      text.push_back(static_cast<char>(0x80 | (code & 0x3F)));
    }
  }
  return text;
}

// Index in C order of the element stored at Fortran position `position`.
int64_t c_index_of_fortran(int64_t position, const std::vector<int64_t>& shape) {
  int64_t index = 0, stride = 1;
  std::vector<int64_t> coordinate(shape.size());
  for (size_t d = 0; d < shape.size(); ++d) {
    coordinate[d] = position % shape[d];
    position /= shape[d];
  }
  for (size_t d = shape.size(); d-- > 0;) {
    index += coordinate[d] * stride;
    stride *= shape[d];
  }
  return index;
}

//---- JSON

void shape_of(const nlohmann::json& value, std::vector<int64_t>& shape) {
  const nlohmann::json* at = &value;
  while (at->is_array()) {
    shape.push_back(static_cast<int64_t>(at->size()));
    if (at->empty()) break;
    at = &at->front();
  }
}

void flatten(const nlohmann::json& value, const std::vector<int64_t>& shape, size_t depth,
             std::string path, ImportedArray& out, const std::string& where) {
  if (depth == shape.size()) {
    if (out.text) {
      if (!value.is_string())
        throw Error(where + " " + path, "expected text like the first element");
      out.strings.push_back(value.get<std::string>());
    } else {
      if (!value.is_number())
        throw Error(where + " " + path, "expected a number like the first element, not " +
                                            std::string(value.type_name()));
      const double number = value.get<double>();
      if (!std::isfinite(number)) throw Error(where + " " + path, "not a finite number");
      out.values.push_back(number);
    }
    return;
  }
  if (!value.is_array() || static_cast<int64_t>(value.size()) != shape[depth])
    throw Error(where + " " + path,
                "expected an array of " + std::to_string(shape[depth]) +
                    " like the first at this depth (the frames must be regular)");
  for (size_t k = 0; k < value.size(); ++k)
    flatten(value[k], shape, depth + 1, path + "[" + std::to_string(k) + "]", out, where);
}

}  // namespace

int64_t ImportedArray::size() const {
  int64_t count = 1;
  for (int64_t extent : shape) count *= extent;
  return count;
}

ImportedArray parse_npy(std::span<const uint8_t> bytes, const std::string& where) {
  static const uint8_t kMagic[6] = {0x93, 'N', 'U', 'M', 'P', 'Y'};
  if (bytes.size() < 10 || std::memcmp(bytes.data(), kMagic, 6) != 0)
    throw Error(where + " byte 0", "not a .npy file (no \\x93NUMPY magic)");
  const int major = bytes[6];
  if (major < 1 || major > 3)
    throw Error(where + " byte 6",
                "format version " + std::to_string(major) + " (1 to 3 are read)");
  const size_t length_size = major == 1 ? 2 : 4;
  if (bytes.size() < 8 + length_size)
    throw Error(where + " byte 8", "the file ends inside the header length");
  const size_t header_length = major == 1 ? little16(bytes.data() + 8) : little32(bytes.data() + 8);
  const size_t data_start = 8 + length_size + header_length;
  if (data_start > bytes.size())
    throw Error(where + " byte 8", "header of " + std::to_string(header_length) +
                                       " bytes runs past the end of the file");
  const std::string header(reinterpret_cast<const char*>(bytes.data()) + 8 + length_size,
                           header_length);
  const NpyHeader parsed = parse_npy_header(header, where);
  ImportedArray array;
  array.shape = parsed.shape;
  array.text = parsed.kind == 'U' || parsed.kind == 'S';
  const int64_t count = element_count(parsed.shape, where + " header");
  // The data must be exactly what the header declares: checked before anything is allocated.
  const uint64_t data_bytes = bytes.size() - data_start;
  if (parsed.item > 0 &&
      static_cast<uint64_t>(count) > data_bytes / static_cast<uint64_t>(parsed.item))
    throw Error(where + " byte " + std::to_string(data_start),
                "shape " + shape_text(parsed.shape) + " of " + std::to_string(parsed.item) +
                    "-byte elements needs " + std::to_string(count * parsed.item) +
                    " bytes, the file holds " + std::to_string(data_bytes) + " (truncated?)");
  if (static_cast<uint64_t>(count * parsed.item) != data_bytes)
    throw Error(where + " byte " + std::to_string(data_start + count * parsed.item),
                std::to_string(data_bytes - count * parsed.item) + " bytes after the data");
  const uint8_t* data = bytes.data() + data_start;
  if (array.text) {
    array.strings.resize(static_cast<size_t>(count));
    for (int64_t k = 0; k < count; ++k) {
      const int64_t index = parsed.fortran ? c_index_of_fortran(k, parsed.shape) : k;
      array.strings[static_cast<size_t>(index)] = text_at(data + k * parsed.item, parsed);
    }
  } else {
    array.values.resize(static_cast<size_t>(count));
    for (int64_t k = 0; k < count; ++k) {
      const int64_t index = parsed.fortran ? c_index_of_fortran(k, parsed.shape) : k;
      array.values[static_cast<size_t>(index)] = number_at(data + k * parsed.item, parsed);
    }
  }
  return array;
}

ImportedArray read_npy(const std::string& path) { return parse_npy(read_bytes(path), path); }

namespace {

std::string array_name(const std::string& entry) {
  return entry.size() > 4 && entry.ends_with(".npy") ? entry.substr(0, entry.size() - 4) : entry;
}

}  // namespace

std::vector<std::string> npz_names(const std::string& path) {
  std::vector<std::string> names;
  for (const ZipEntry& entry : zip_entries(read_bytes(path), path))
    names.push_back(array_name(entry.name));
  return names;
}

ImportedArray read_npz(const std::string& path, const std::string& name) {
  const std::vector<uint8_t> bytes = read_bytes(path);
  const std::vector<ZipEntry> entries = zip_entries(bytes, path);
  std::string names;
  for (const ZipEntry& entry : entries) {
    if (array_name(entry.name) == name) {
      const std::string where = path + ":" + entry.name;
      return parse_npy(zip_content(bytes, entry, where), where);
    }
    names += (names.empty() ? "" : ", ") + array_name(entry.name);
  }
  throw Error(path, "no array '" + name + "' (it holds: " + (names.empty() ? "none" : names) + ")");
}

ImportedArray read_json_array(const std::string& path, const std::string& key,
                              const std::string& member) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw Error(path + " byte " + std::to_string(error.byte),
                "not JSON: " + std::string(error.what()));
  } catch (const nlohmann::json::exception& error) {
    // A number too large for a double (1e400) is an out_of_range, not a parse_error.
    throw Error(path, "not readable JSON: " + std::string(error.what()));
  }
  const nlohmann::json* value = &document;
  std::string walked;
  for (size_t start = 0; !key.empty() && start <= key.size();) {
    const size_t dot = std::min(key.find('.', start), key.size());
    const std::string part = key.substr(start, dot - start);
    walked += (walked.empty() ? "" : ".") + part;
    if (!value->is_object() || !value->contains(part)) throw Error(path, "no key '" + walked + "'");
    value = &(*value)[part];
    start = dot + 1;
  }
  const std::string where = path + (key.empty() ? "" : " key " + key);
  if (!value->is_array()) throw Error(where, "not an array");
  // Frames given as objects ({"label": ..., "data": [...]}): each one's `member`.
  nlohmann::json members;
  if (!value->empty() && value->front().is_object()) {
    if (member.empty()) {
      std::string names;
      for (const auto& [name, ignored] : value->front().items())
        names += (names.empty() ? "" : ", ") + name;
      throw Error(where,
                  "holds objects, not arrays: name the member of each that holds its frame "
                  "(--value-key) or its class (--class-key); the first has " +
                      names);
    }
    members = nlohmann::json::array();
    for (size_t k = 0; k < value->size(); ++k) {
      const nlohmann::json& entry = (*value)[k];
      if (!entry.is_object() || !entry.contains(member))
        throw Error(where + " [" + std::to_string(k) + "]", "no member '" + member + "'");
      members.push_back(entry[member]);
    }
    value = &members;
  } else if (!member.empty()) {
    throw Error(where, "holds no objects, so no member '" + member +
                           "' (leave out --value-key/--class-key)");
  }
  ImportedArray array;
  shape_of(*value, array.shape);
  element_count(array.shape, where);
  const nlohmann::json* first = value;
  while (first->is_array() && !first->empty()) first = &first->front();
  array.text = first->is_string();
  flatten(*value, array.shape, 0, "", array, where);
  return array;
}

std::vector<Hdf5Dataset> hdf5_datasets(const std::string& path) {
  std::vector<Hdf5Dataset> readable;
  for (const Hdf5DatasetShape& dataset : check_hdf5_structure(path).datasets)
    if (dataset.readable()) readable.push_back({dataset.path, hdf5_dataset_line(dataset)});
  return readable;
}

ImportedArray read_hdf5_dataset(const std::string& path, const std::string& name) {
  hdf5::silence_errors();
  // Walked before libhdf5 is given the file: libhdf5 1.10 follows group and header addresses
  // unchecked (the MATLAB v7.3 reader's fuzz findings, tests/fuzz/README.md).
  const Hdf5Structure structure = check_hdf5_structure(path);
  const std::string where = path + ":" + name;
  if (structure.walked) {
    const std::string absolute = name.starts_with('/') ? name : "/" + name;
    const auto found =
        std::find_if(structure.datasets.begin(), structure.datasets.end(),
                     [&](const Hdf5DatasetShape& dataset) { return dataset.path == absolute; });
    if (found == structure.datasets.end()) {
      std::string known;
      for (const Hdf5DatasetShape& dataset : structure.datasets)
        if (dataset.readable()) known += (known.empty() ? "" : ", ") + hdf5_dataset_line(dataset);
      throw Error(where,
                  "no such dataset (the file holds " + (known.empty() ? "none" : known) + ")");
    }
    if (!found->readable())
      throw Error(where, "the dataset " + hdf5_dataset_line(*found) +
                             " is not read: only numbers and strings are");
  }
  hdf5::Object file = hdf5::checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                                    path, "cannot open");
  if (!hdf5::has_link(file.id(), name)) throw Error(where, "no such dataset");
  hdf5::Object dataset = hdf5::open_dataset(file.id(), name, where);
  ImportedArray array;
  for (hsize_t extent : hdf5::dataset_shape(dataset.id(), where))
    array.shape.push_back(static_cast<int64_t>(extent));
  const int64_t count = element_count(array.shape, where);
  const H5T_class_t type = hdf5::dataset_class(dataset.id(), where);
  if (type == H5T_STRING) {
    array.text = true;
    if (array.shape.size() != 1) throw Error(where, "strings are read from 1-D datasets only");
    array.strings = hdf5::read_strings(file.id(), name, where, true);
    return array;
  }
  if (type != H5T_FLOAT && type != H5T_INTEGER) throw Error(where, "neither numbers nor strings");
  // The bytes the file stores (a float32 dataset holds 4 per value), not those of the doubles
  // it is read into.
  const hdf5::Object stored_type =
      hdf5::checked(H5Dget_type(dataset.id()), H5Tclose, where, "cannot read type");
  const size_t stored_bytes = H5Tget_size(stored_type.id());
  if (stored_bytes == 0) throw Error(where, "values of 0 bytes");
  hdf5::check_declared_size(dataset.id(),
                            static_cast<double>(stored_bytes) * static_cast<double>(count), where);
  array.values.resize(static_cast<size_t>(count));
  if (count > 0 && H5Dread(dataset.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                           array.values.data()) < 0)
    hdf5::fail(where, "cannot read");
  return array;
}

std::vector<Label> labels_from_frame_classes(const std::vector<std::string>& classes, double start,
                                             double rate_hz) {
  std::vector<Label> labels;
  size_t run = 0;
  for (size_t k = 1; k <= classes.size(); ++k) {
    if (k < classes.size() && classes[k] == classes[run]) continue;
    const std::string& name = classes[run];
    if (!name.empty() && name != "none") {
      Label label;
      label.t0 = start + static_cast<double>(run) / rate_hz;
      label.t1 = start + static_cast<double>(k) / rate_hz;
      label.region = "all";
      label.class_name = name;
      label.annotator = "import";
      label.source = LabelSource::kGroundTruth;
      labels.push_back(std::move(label));
    }
    run = k;
  }
  return labels;
}

ImportedRecording recording_from_array(const ImportedArray& array, const SkinLayout& layout,
                                       const ArrayRecordingOptions& options,
                                       const std::string& where) {
  if (!(options.rate_hz > 0.0) || !std::isfinite(options.rate_hz))
    throw Error("--rate", "a sample rate above 0 is needed");
  if (array.text) throw Error(where, "holds text, not samples");
  const int64_t channels = static_cast<int64_t>(layout.channels.size());
  const std::vector<int64_t>& shape = array.shape;
  int64_t samples = 0;
  std::string expected;
  if (options.captures) {
    if (shape.size() != 3 || shape[1] != channels)
      throw Error(where, "shape " + shape_text(shape) + ", expected [captures][" +
                             std::to_string(channels) + " channels of " + layout.id + "][samples]");
    samples = shape[0] * shape[2];
  } else if (shape.size() == 2 && shape[1] == channels) {
    samples = shape[0];
  } else if (shape.size() == 3 && shape[1] * shape[2] == channels) {
    samples = shape[0];
  } else {
    throw Error(
        where,
        "shape " + shape_text(shape) + " does not fit " + layout.id + "'s " +
            std::to_string(channels) + " channels: expected [samples][" + std::to_string(channels) +
            "] or [frames][rows][columns] with rows x columns = " + std::to_string(channels) +
            " (or --captures for [captures][channels][samples])");
  }
  ImportedRecording imported;
  Stream stream;
  stream.name = options.stream_name;
  stream.rate_hz = options.rate_hz;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples.resize(samples, channels);
  for (int64_t row = 0; row < samples; ++row) {
    for (int64_t column = 0; column < channels; ++column) {
      int64_t index = row * channels + column;
      if (options.captures) {
        const int64_t capture = row / shape[2], sample = row % shape[2];
        index = (capture * channels + column) * shape[2] + sample;
      }
      const double value = array.values[static_cast<size_t>(index)];
      if (!std::isfinite(value)) {
        std::string place = "index ";
        int64_t rest = index;
        std::vector<int64_t> coordinate(shape.size());
        for (size_t d = shape.size(); d-- > 0;) coordinate[d] = rest % shape[d], rest /= shape[d];
        for (int64_t c : coordinate) {
          place += '[';
          place += std::to_string(c);
          place += ']';
        }
        throw Error(where + " " + place, "not a finite number");
      }
      stream.samples(row, column) = static_cast<float>(value);
    }
  }
  imported.recording.layout_id = layout.id;
  imported.recording.streams.push_back(std::move(stream));
  if (!options.classes.empty()) {
    if (options.captures) {
      if (static_cast<int64_t>(options.classes.size()) != shape[0])
        throw Error(where, std::to_string(options.classes.size()) + " classes for " +
                               std::to_string(shape[0]) + " captures");
      for (int64_t capture = 0; capture < shape[0]; ++capture) {
        std::vector<std::string> frames(static_cast<size_t>(shape[2]),
                                        options.classes[static_cast<size_t>(capture)]);
        for (Label& label : labels_from_frame_classes(
                 frames, static_cast<double>(capture * shape[2]) / options.rate_hz,
                 options.rate_hz))
          imported.labels.push_back(std::move(label));
      }
    } else {
      if (static_cast<int64_t>(options.classes.size()) != samples)
        throw Error(where, std::to_string(options.classes.size()) + " classes for " +
                               std::to_string(samples) + " frames");
      imported.labels = labels_from_frame_classes(options.classes, 0.0, options.rate_hz);
    }
  }
  return imported;
}

}  // namespace tactile
