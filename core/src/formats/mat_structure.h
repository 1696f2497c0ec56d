#pragma once
// The structure of a MATLAB .mat file, checked before libmatio reads it (mat_files.cpp).
// libmatio allocates what a file declares (cell and struct element pointers, field names,
// each variable's data) and, in 1.5.23, divides by a struct's field-name length without
// looking at it; so every size of a v5 file is walked here first, against the bytes the file
// (or, in a compressed variable, the inflated stream) really holds.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile {

enum class MatFileVersion { v4, v5, v73 };

// The header's version and byte-order fields (bytes 124-127), and the file's size.
struct MatHeader {
  uint16_t version = 0;
  bool swap = false;
  uint64_t size = 0;
};
// Throws tactile::Error naming `path` for a file shorter than the header or without its
// byte-order mark.
MatHeader read_mat_header(const std::string& path);

// The version of the file: v5 or v7.3 as the 128-byte header declares it, or MATLAB 4 (Level
// 4: no header, each variable a 20-byte header of five int32, its name and its data) when the
// file begins with such a variable header. Throws tactile::Error naming `path` for a file that
// is none of them.
MatFileVersion mat_file_version(const std::string& path);

// An opaque object of a v5 file (array class 17: MATLAB 2017b+'s `string`, and `table`,
// `datetime`, ... of its MCOS type system): libmatio lists it without its name or class.
struct MatOpaqueVariable {
  std::string name;         // "label", or inside a struct or cell "s.label", "c{2}"
  std::string type_system;  // "MCOS" (printable)
  std::string class_name;   // "string" (printable)
  bool top_level = false;
};

// Walks every variable of a v5 file: element tags, array flags, dimensions, names, each
// cell and struct field, and each numeric or char data element against its dimensions;
// compressed variables are inflated (into a small window, nothing kept) as they are walked.
// Throws tactile::Error naming the file, the variable and the byte (in the file, or in the
// inflated stream of a compressed variable) and what is wrong. Returns the opaque objects met,
// in the file's order.
std::vector<MatOpaqueVariable> check_mat_v5_structure(const std::string& path);

// Walks every variable of a MATLAB 4 file (mat_v4_structure.cpp): each 20-byte header (its
// number format and type digits, dimensions, name length), the name ending in its NUL, and the
// data (rows x columns x the type's size, twice when imaginary) within the file. Sparse
// matrices and VAX or Cray number formats are refused naming the variable.
void check_mat_v4_structure(const std::string& path);

// The first bytes of a file begin a MATLAB 4 variable header (either byte order).
bool looks_like_mat_v4(const uint8_t* bytes, uint64_t size);

// Of a v7.3 file, what libhdf5 follows unchecked when libmatio opens it: the HDF5 walk of
// hdf5_structure.h (which other programs' .h5 files get too), its superblock after MATLAB's
// 512-byte header block.
void check_mat_v73_structure(const std::string& path);

}  // namespace tactile
