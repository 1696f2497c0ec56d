#pragma once
// The structure of a MATLAB .mat file, checked before libmatio reads it (mat_files.cpp).
// libmatio allocates what a file declares (cell and struct element pointers, field names,
// each variable's data) and, in 1.5.23, divides by a struct's field-name length without
// looking at it; so every size of a v5 file is walked here first, against the bytes the file
// (or, in a compressed variable, the inflated stream) really holds.

#include <cstdint>
#include <string>

namespace tactile {

enum class MatFileVersion { v5, v73 };

// The header's version and byte-order fields (bytes 124-127), and the file's size.
struct MatHeader {
  uint16_t version = 0;
  bool swap = false;
  uint64_t size = 0;
};
// Throws tactile::Error naming `path` for a file shorter than the header or without its
// byte-order mark.
MatHeader read_mat_header(const std::string& path);

// The version the 128-byte header declares. Throws tactile::Error naming `path` for a file
// that is neither v5 nor v7.3 (v4 files, which have no header, are not read).
MatFileVersion mat_file_version(const std::string& path);

// Walks every variable of a v5 file: element tags, array flags, dimensions, names, each
// cell and struct field, and each numeric or char data element against its dimensions;
// compressed variables are inflated (into a small window, nothing kept) as they are walked.
// Throws tactile::Error naming the file, the variable and the byte (in the file, or in the
// inflated stream of a compressed variable) and what is wrong.
void check_mat_v5_structure(const std::string& path);

// Of a v7.3 file (mat_v73_structure.cpp), what libhdf5 follows unchecked when libmatio opens it:
// the superblock's end of file against the file's size, and the root group's B-tree, symbol-table
// nodes and local heap, every address within that end. Datasets' object headers are libhdf5's to
// check.
void check_mat_v73_structure(const std::string& path);

}  // namespace tactile
