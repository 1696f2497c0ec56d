#pragma once
// The structure of an HDF5 file walked before libhdf5 is given it (hdf5_structure.cpp): what
// libhdf5 1.10 follows unchecked when it opens a file and a dataset. The MATLAB v7.3 reader
// (mat_structure.h) and the HDF5 import of other programs' files (array_files.h) share it.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile {

// One dataset as its object header declares it.
struct Hdf5DatasetShape {
  std::string path;            // "/sensors/pressure"
  std::vector<uint64_t> dims;  // the dataspace's extents, slowest first (C order)
  std::string type;            // "float64", "int16", "uint8", "string", "compound", ...
  bool readable() const;       // numbers (integer or float) or strings
};

// "/sensors/pressure 6x4 float64", as refusals list them.
std::string hdf5_dataset_line(const Hdf5DatasetShape& dataset);

struct Hdf5Structure {
  uint64_t superblock_at = 0;  // 0, or 512 x 2^n after a user block (MATLAB's v7.3: 512)
  int superblock_version = 0;
  // Superblocks of version 0 and 1 (what libhdf5 writes by default, and MATLAB v7.3): every
  // group and dataset is walked and listed. Versions 2 and 3 (new-style groups): only the end
  // of file is checked, nothing is listed.
  bool walked = false;
  std::vector<Hdf5DatasetShape> datasets;  // in the order of the groups' B-trees
};

// Walks the file from the superblock: its end of file against the file's size; then every
// group's B-tree, symbol-table nodes and local heap, and every object header (continuation
// blocks, each message within its block, attributes, dataspaces and datatypes), every address
// within the declared end of file. Throws tactile::Error naming `path`, the byte and what is
// wrong; a file without an HDF5 signature is refused as "not an HDF5 file".
Hdf5Structure check_hdf5_structure(const std::string& path);

}  // namespace tactile
