#pragma once
// The io tests' files: the shared temporary folder and refusal (tests/support), small file
// helpers.

#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include "tactile/error.h"
#include "tactile/io/recording.h"
#include "temp_folder.h"

namespace tactile::testing {

using test::refusal_of;
// The io tests' name for the shared temporary folder (tests/support/temp_folder.h).
using TemporaryDirectory = test::TempFolder;

// Same shape and the same bits in every sample (NaNs included).
inline bool bit_equal(const SampleMatrix& left, const SampleMatrix& right) {
  // memcmp must not be given the null data of an empty matrix, even for no bytes (UBSan).
  return left.rows() == right.rows() && left.cols() == right.cols() &&
         (left.size() == 0 ||
          std::memcmp(left.data(), right.data(), sizeof(float) * size_t(left.size())) == 0);
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace tactile::testing
