// The structure of an HDF5 file walked before libhdf5 is given it (hdf5_structure.h): the
// groups and object headers libhdf5 follows when a file is opened and a dataset read. MATLAB
// v7.3 files (mat_structure.h) and other programs' .h5 files (array_files.cpp) are walked alike.
#include "hdf5_structure.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "mat_structure.h"
#include "tactile/error.h"

namespace tactile {

namespace {

// libhdf5 1.10 follows a group's B-tree and symbol-table node addresses without checking them
// against the file (a child address past the end made it copy from a null pointer under the
// fuzzer: tests/fuzz/regressions/mat/v73-group-btree-child-past-the-end.mat). So the root
// group's B-tree, its symbol-table nodes and its local heap are walked here first (HDF5 format
// specification, version 0/1 superblock, "Group B-tree nodes", "Symbol Table Node", "Local
// Heap"): every address within the end of file the superblock declares, every node whole,
// every count within the node's capacity; each link's name is read from its group's heap, so
// the datasets are listed by path as they are walked. Superblocks of version 2 and 3
// (new-style groups) are only checked for their end of file.
class Hdf5Walker {
 public:
  Hdf5Walker(std::string path, std::ifstream& in, uint64_t size)
      : path_(std::move(path)), in_(in), size_(size) {}

  Hdf5Structure file() {
    const uint64_t superblock = find_superblock();
    structure_.superblock_at = superblock;
    const std::vector<uint8_t> head = bytes(superblock, 24, "the HDF5 superblock");
    const uint8_t version = head[8];
    structure_.superblock_version = version;
    if (version > 3) fail(superblock + 8, "superblock version " + std::to_string(version));
    if (version >= 2) {
      const std::vector<uint8_t> fields = bytes(superblock + 12, 32, "the HDF5 superblock");
      if (head[9] != 8) fail(superblock + 9, "offsets of " + std::to_string(head[9]) + " bytes");
      check_end(superblock, number(fields, 0), number(fields, 16));
      return structure_;
    }
    if (head[13] != 8 || head[14] != 8)
      fail(superblock + 13, "offsets and lengths of other than 8 bytes");
    leaf_k_ = static_cast<uint64_t>(head[16] | head[17] << 8);
    internal_k_ = static_cast<uint64_t>(head[18] | head[19] << 8);
    if (leaf_k_ == 0 || internal_k_ == 0 || leaf_k_ > 4096 || internal_k_ > 4096)
      fail(superblock + 16, "group node sizes K of " + std::to_string(leaf_k_) + " and " +
                                std::to_string(internal_k_));
    const uint64_t fields_at = superblock + (version == 0 ? 24 : 28);
    const std::vector<uint8_t> fields = bytes(fields_at, 32 + 40, "the HDF5 superblock");
    check_end(fields_at, number(fields, 0), number(fields, 16));
    driver_info(number(fields, 24), fields_at + 24);
    // The root group's symbol-table entry: its object header, and the B-tree and heap it caches
    // (walked, not listed: the object header's own symbol table is what the listing follows).
    const uint64_t root_header = address(number(fields, 40), fields_at + 40, 16);
    if (number(fields, 48) % (uint64_t{1} << 32) == 1) {
      listing_ = false;
      group(number(fields, 56), number(fields, 64), fields_at + 56, "");
      listing_ = true;
    }
    root_object_header(root_header);
    return structure_;
  }

 private:
  // The signature at byte 0, or at 512 x 2^n after a user block, as libhdf5 searches for it.
  uint64_t find_superblock() {
    static const uint8_t kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
    for (uint64_t at = 0; at + 8 <= size_; at = at == 0 ? 512 : at * 2) {
      const std::vector<uint8_t> signature = bytes(at, 8, "the HDF5 signature");
      if (std::equal(kSignature, kSignature + 8, signature.begin())) return at;
    }
    throw Error(path_, "not an HDF5 file (no HDF5 signature at byte 0 or after a user block)");
  }

  [[noreturn]] void fail(uint64_t at, const std::string& what) const {
    throw Error(path_, "byte " + std::to_string(at) + ": " + what);
  }

  std::vector<uint8_t> bytes(uint64_t at, uint64_t count, const std::string& what) {
    if (at > size_ || count > size_ - at)
      fail(at, what + " (" + std::to_string(count) + " bytes) is past the end of the file");
    std::vector<uint8_t> read(count);
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(reinterpret_cast<char*>(read.data()), static_cast<std::streamsize>(count));
    if (!in_) fail(at, "cannot read " + what);
    return read;
  }

  static uint64_t number(const std::vector<uint8_t>& bytes, size_t at, size_t size = 8) {
    uint64_t value = 0;
    for (size_t k = 0; k < size; ++k) value |= static_cast<uint64_t>(bytes[at + k]) << (8 * k);
    return value;
  }

  // The driver information block (format spec, "Driver Info Block"), when the superblock names
  // one: libhdf5 1.10 allocates the size it declares before reading it (4 GB under the fuzzer:
  // tests/fuzz/regressions/hdf5/driver-info-size-makes-libhdf5-allocate-4-gb.h5).
  void driver_info(uint64_t relative, uint64_t named_at) {
    if (relative == UINT64_MAX) return;  // the undefined address: no block
    const uint64_t at = address(relative, named_at, 16);
    const std::vector<uint8_t> block = bytes(at, 16, "the driver information block");
    if (block[0] != 0)
      fail(at, "a driver information block of version " + std::to_string(block[0]));
    address(relative + 16, at + 4, number(block, 4, 4));
  }

  // The end of file as libmatio's files store it counts the 512-byte block before the
  // superblock; addresses are relative to the base (the superblock).
  void check_end(uint64_t at, uint64_t base, uint64_t end) {
    if (base > size_ || end > size_ || end < base)
      fail(at, "the superblock declares a base at " + std::to_string(base) +
                   " and an end of file at " + std::to_string(end) + ", the file has " +
                   std::to_string(size_) + " bytes");
    base_ = base;
    end_ = end;
  }

  // An address relative to the base, whose `count` bytes must lie within the declared end.
  uint64_t address(uint64_t relative, uint64_t named_at, uint64_t count) {
    if (relative > end_ - base_ || count > end_ - base_ - relative)
      fail(named_at, "an address " + std::to_string(relative) + " (" + std::to_string(count) +
                         " bytes) past the end of file");
    return base_ + relative;
  }

  void root_object_header(uint64_t at) {
    const std::vector<uint8_t> prefix = bytes(at, 16, "the root group's object header");
    if (prefix[0] != 1) return;  // version 2 ("OHDR"): new-style links, not walked here
    structure_.walked = true;
    const uint64_t length = number(prefix, 8, 4);
    if (length > 65536) fail(at + 8, "an object header of " + std::to_string(length) + " bytes");
    address(at - base_ + 16, at, length);
    const std::vector<uint8_t> messages = bytes(at + 16, length, "the root group's messages");
    for (uint64_t offset = 0; offset + 8 <= length;) {
      const uint64_t type = number(messages, offset, 2);
      const uint64_t size = number(messages, offset + 2, 2);
      if (size > length - offset - 8) fail(at + 16 + offset, "a header message past its header");
      if (type == 0x11 && size >= 16)  // the symbol table message: B-tree and heap
        group(number(messages, offset + 8), number(messages, offset + 16), at + 16 + offset + 8,
              "");
      offset += 8 + size;
    }
  }

  // The group whose links are in the B-tree at `btree` and whose names are in the heap at
  // `heap`; `group_path` is "" for the root, "/sensors" for a group in it.
  void group(uint64_t btree, uint64_t heap, uint64_t named_at, const std::string& group_path) {
    const uint64_t heap_at = address(heap, named_at + 8, 32);
    const std::vector<uint8_t> header = bytes(heap_at, 32, "a local heap");
    if (std::memcmp(header.data(), "HEAP", 4) != 0) fail(heap_at, "no local heap signature");
    heap_size_ = number(header, 8);
    heap_data_ = address(number(header, 24), heap_at + 24, heap_size_);
    nodes_ = 0;
    btree_node(btree, named_at, UINT32_MAX, group_path);
  }

  void btree_node(uint64_t relative, uint64_t named_at, uint64_t level_above,
                  const std::string& group_path) {
    if (++nodes_ > 65536) fail(named_at, "more than 65536 group B-tree nodes (a cycle?)");
    const uint64_t node_bytes = 8 + 2 * 8 + (2 * internal_k_ + 1) * 8 + 2 * internal_k_ * 8;
    const uint64_t at = address(relative, named_at, node_bytes);
    const std::vector<uint8_t> node = bytes(at, node_bytes, "a group B-tree node");
    if (std::memcmp(node.data(), "TREE", 4) != 0 || node[4] != 0)
      fail(at, "not a group B-tree node");
    const uint64_t level = node[5];
    if (level >= level_above) fail(at + 5, "a B-tree level that does not descend");
    const uint64_t entries = number(node, 6, 2);
    if (entries > 2 * internal_k_)
      fail(at + 6,
           std::to_string(entries) + " entries in a node of " + std::to_string(2 * internal_k_));
    for (uint64_t entry = 0; entry < entries; ++entry) {
      const size_t child_at = 24 + 8 + static_cast<size_t>(entry) * 16;
      const uint64_t child = number(node, child_at);
      if (level > 0)
        btree_node(child, at + child_at, level, group_path);
      else
        symbol_node(child, at + child_at, group_path);
    }
  }

  void symbol_node(uint64_t relative, uint64_t named_at, const std::string& group_path) {
    const uint64_t node_bytes = 8 + 2 * leaf_k_ * 40;
    const uint64_t at = address(relative, named_at, node_bytes);
    const std::vector<uint8_t> node = bytes(at, node_bytes, "a symbol table node");
    if (std::memcmp(node.data(), "SNOD", 4) != 0) fail(at, "not a symbol table node");
    const uint64_t symbols = number(node, 6, 2);
    if (symbols > 2 * leaf_k_)
      fail(at + 6,
           std::to_string(symbols) + " symbols in a node of " + std::to_string(2 * leaf_k_));
    for (uint64_t symbol = 0; symbol < symbols; ++symbol) {
      const size_t entry = 8 + static_cast<size_t>(symbol) * 40;
      const uint64_t name = number(node, entry);
      if (name >= heap_size_) fail(at + entry, "a link name past its heap");
      const uint64_t header = address(number(node, entry + 8), at + entry + 8, 16);
      object_header(header, group_path + "/" + link_name(name, at + entry));
    }
  }

  // The link name at `offset` of the current group's heap: NUL-terminated within the heap.
  std::string link_name(uint64_t offset, uint64_t named_at) {
    constexpr uint64_t kMostNameBytes = 1024;
    const uint64_t left = std::min(heap_size_ - offset, kMostNameBytes);
    const std::vector<uint8_t> text = bytes(heap_data_ + offset, left, "a link name");
    const auto end = std::find(text.begin(), text.end(), uint8_t{0});
    if (end == text.end())
      fail(named_at, heap_size_ - offset > kMostNameBytes
                         ? "a link name longer than " + std::to_string(kMostNameBytes) + " bytes"
                         : "a link name without its end in its heap");
    if (end == text.begin()) fail(named_at, "a link of no name");
    return std::string(text.begin(), end);
  }

  // A variable's (or a struct's group's) object header, version 1: every message within its
  // block, continuation blocks followed within the file, and the messages libhdf5 decodes
  // without checking their sizes against the message (attributes: MATLAB_class on every
  // variable; dataspaces; datatypes) checked here. A struct's group is walked in turn.
  void object_header(uint64_t at, const std::string& object_path) {
    if (++headers_ > 65536) fail(at, "more than 65536 object headers (a cycle?)");
    const std::vector<uint8_t> prefix = bytes(at, 16, "an object header");
    if (std::memcmp(prefix.data(), "OHDR", 4) == 0)
      fail(at, "an object header of version 2, which is not read here");
    if (prefix[0] != 1) fail(at, "an object header of version " + std::to_string(prefix[0]));
    const uint64_t declared = number(prefix, 2, 2);
    const uint64_t length = number(prefix, 8, 4);
    std::vector<std::pair<uint64_t, uint64_t>> blocks = {{at + 16, length}};
    uint64_t messages = 0;
    std::optional<uint64_t> elements, element_bytes;
    std::vector<uint64_t> dims;
    std::string type_name;
    bool is_group = false;
    for (size_t block = 0; block < blocks.size(); ++block) {
      if (block > 64) fail(at, "more than 64 continuation blocks");
      const auto [start, size] = blocks[block];
      if (size > (uint64_t{1} << 20))
        fail(start, "a header block of " + std::to_string(size) + " bytes");
      address(start - base_, start, size);
      const std::vector<uint8_t> data = bytes(start, size, "an object header block");
      for (uint64_t offset = 0; offset + 8 <= size;) {
        const uint64_t type = number(data, offset, 2);
        const uint64_t message = number(data, offset + 2, 2);
        const uint64_t body = start + offset + 8;
        if (message > size - offset - 8) fail(start + offset, "a header message past its block");
        if (++messages > declared + 64)
          fail(start + offset, "more messages than the header declares");
        const std::vector<uint8_t> content(
            data.begin() + static_cast<std::ptrdiff_t>(offset + 8),
            data.begin() + static_cast<std::ptrdiff_t>(offset + 8 + message));
        if (type == 0x0001) elements = dataspace(content, 0, message, body, &dims);
        if (type == 0x0003) {
          element_bytes = datatype(content, 0, message, body);
          type_name = datatype_name(content);
        }
        if (type == 0x000C) attribute(content, body);
        if (type == 0x0010) {
          if (message < 16)
            fail(body, "a continuation message of " + std::to_string(message) + " bytes");
          blocks.emplace_back(address(number(content, 0), body, number(content, 8)),
                              number(content, 8));
        }
        if (type == 0x0011) {
          if (message < 16)
            fail(body, "a symbol table message of " + std::to_string(message) + " bytes");
          if (++depth_ > 32) fail(body, "groups nested deeper than 32");
          is_group = true;
          const uint64_t saved_heap = heap_size_, saved_data = heap_data_, saved_nodes = nodes_;
          group(number(content, 0), number(content, 8), body, object_path);
          heap_size_ = saved_heap;
          heap_data_ = saved_data;
          nodes_ = saved_nodes;
          --depth_;
        }
        offset += 8 + message;
      }
    }
    // A dataset's value: libhdf5 allocates elements x element size to read it (and to convert
    // it), whatever the file holds, so it must be what the file's bytes could hold even
    // deflated (1032:1).
    if (elements && element_bytes &&
        (*elements != 0 && *element_bytes > size_ / *elements * 1032 + 1032))
      fail(at, "a dataset of " + std::to_string(*elements) + " elements of " +
                   std::to_string(*element_bytes) + " bytes, more than the file's " +
                   std::to_string(size_) + " bytes could hold");
    if (listing_ && !is_group && elements && element_bytes)
      structure_.datasets.push_back({object_path, dims, type_name});
  }

  // Dataspace message (versions 1 and 2) at `from` of `content`, `limit` bytes long: its rank
  // and dimension sizes within those bytes. Returns the element count (1 for a scalar).
  uint64_t dataspace(const std::vector<uint8_t>& content, size_t from, uint64_t limit, uint64_t at,
                     std::vector<uint64_t>* dims = nullptr) {
    if (limit < 8) fail(at, "a dataspace of " + std::to_string(limit) + " bytes");
    const uint8_t version = content[from], rank = content[from + 1], flags = content[from + 2];
    if (version < 1 || version > 2) fail(at, "a dataspace of version " + std::to_string(version));
    if (rank > 32) fail(at + 1, "a dataspace of rank " + std::to_string(rank));
    const uint64_t header = version == 1 ? 8 : 4;
    const uint64_t needed = header + uint64_t{rank} * 8 * ((flags & 1) ? 2 : 1);
    if (needed > limit)
      fail(at, "a dataspace of rank " + std::to_string(rank) + " needs " + std::to_string(needed) +
                   " bytes, its message has " + std::to_string(limit));
    uint64_t elements = 1;
    for (uint64_t d = 0; d < rank; ++d) {
      const uint64_t extent = number(content, from + header + d * 8);
      if (dims) dims->push_back(extent);
      if (extent != 0 && elements > (uint64_t{1} << 40) / extent)
        fail(at, "a dataspace of more than 2^40 elements");
      elements *= extent;
    }
    return elements;
  }

  // Datatype message: at least its 8-byte header within `limit`; returns the element size.
  uint64_t datatype(const std::vector<uint8_t>& content, size_t from, uint64_t limit, uint64_t at) {
    if (limit < 8) fail(at, "a datatype of " + std::to_string(limit) + " bytes");
    const uint64_t size = number(content, from + 4, 4);
    if (size == 0) fail(at + 4, "a datatype of 0 bytes");
    return size;
  }

  // A datatype message's class and size as a name ("float64", "int16", "string", ...).
  static std::string datatype_name(const std::vector<uint8_t>& content) {
    const uint8_t type_class = content[0] & 0x0f;
    const uint64_t bits = number(content, 4, 4) * 8;
    switch (type_class) {
      case 0:
        return ((content[1] & 0x08) ? "int" : "uint") + std::to_string(bits);
      case 1:
        return "float" + std::to_string(bits);
      case 3:
        return "string";
      case 9:
        return (content[1] & 0x0f) == 1 ? "string" : "variable-length sequence";
      case 6:
        return "compound";
      case 7:
        return "reference";
      case 8:
        return "enum";
      case 10:
        return "array";
      default:
        return "type class " + std::to_string(type_class);
    }
  }

  // Attribute message, versions 1 to 3: name, datatype and dataspace within the message, and
  // the value (elements x element size) within what is left.
  void attribute(const std::vector<uint8_t>& content, uint64_t at) {
    const uint64_t limit = content.size();
    if (limit < 8) fail(at, "an attribute of " + std::to_string(limit) + " bytes");
    const uint8_t version = content[0];
    if (version < 1 || version > 3) fail(at, "an attribute of version " + std::to_string(version));
    const uint64_t name = number(content, 2, 2), type = number(content, 4, 2),
                   space = number(content, 6, 2);
    auto padded = [version](uint64_t n) { return version == 1 ? (n + 7) / 8 * 8 : n; };
    const uint64_t header = version == 3 ? 9 : 8;
    const uint64_t type_at = header + padded(name), space_at = type_at + padded(type),
                   value_at = space_at + padded(space);
    if (name == 0 || value_at > limit)
      fail(at, "an attribute whose name (" + std::to_string(name) + "), datatype (" +
                   std::to_string(type) + ") and dataspace (" + std::to_string(space) +
                   " bytes) do not fit its " + std::to_string(limit) + " bytes");
    const uint64_t element = datatype(content, type_at, type, at + type_at);
    const uint64_t elements = dataspace(content, space_at, space, at + space_at);
    if (elements != 0 && element > (limit - value_at) / elements)
      fail(at, "an attribute value of " + std::to_string(elements) + " x " +
                   std::to_string(element) + " bytes past its message");
  }

  std::string path_;
  std::ifstream& in_;
  uint64_t size_;
  uint64_t base_ = 0, end_ = 0;
  uint64_t leaf_k_ = 0, internal_k_ = 0, heap_size_ = 0, heap_data_ = 0, nodes_ = 0, headers_ = 0,
           depth_ = 0;
  bool listing_ = true;
  Hdf5Structure structure_;
};

}  // namespace

bool Hdf5DatasetShape::readable() const {
  return type == "string" || type.starts_with("int") || type.starts_with("uint") ||
         type.starts_with("float");
}

std::string hdf5_dataset_line(const Hdf5DatasetShape& dataset) {
  // Names are the file's bytes: anything but printable ASCII is shown as \xNN.
  std::string line;
  for (const char character : dataset.path) {
    const auto byte = static_cast<uint8_t>(character);
    if (byte >= 0x20 && byte < 0x7f) {
      line += character;
    } else {
      static const char kHex[] = "0123456789abcdef";
      line += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 0x0f];
    }
  }
  std::string dims;
  for (const uint64_t extent : dataset.dims)
    dims += (dims.empty() ? "" : "x") + std::to_string(extent);
  return line + " " + (dims.empty() ? "scalar" : dims) + " " + dataset.type;
}

Hdf5Structure check_hdf5_structure(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  const uint64_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (!in || error) throw Error(path, "cannot open");
  return Hdf5Walker(path, in, size).file();
}

void check_mat_v73_structure(const std::string& path) {
  // MATLAB's 128-byte header, padded to 512 bytes, is the user block before the superblock.
  if (check_hdf5_structure(path).superblock_at != 512)
    throw Error(path, "byte 512: no HDF5 superblock where a v7.3 file has it");
}

}  // namespace tactile
