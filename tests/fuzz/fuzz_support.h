#pragma once
// Shared by the fuzz targets (tests/fuzz/README.md). Each target defines
// LLVMFuzzerTestOneInput: libFuzzer calls it with mutated bytes in the fuzz build
// (clang, -DTACTILE_FUZZ=ON), and replay_main.cpp calls it with every saved input in the
// normal build, so each corpus file and each input that once crashed runs in `make test`.
//
// A target feeds the bytes to one reader the way a user's file would reach it. Refusing bad
// input with tactile::Error is the expected outcome; anything else (another exception, a
// sanitizer report, a timeout, a leak, an allocation past the RSS limit) is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

namespace tactile::fuzz {

inline std::span<const uint8_t> bytes_of(const uint8_t* data, size_t size) { return {data, size}; }

// A file of this process holding `bytes`, for readers that take a path (named with the
// extension they decide by). Rewritten on every call; in a tmpfs when there is one.
inline std::string write_input(std::span<const uint8_t> bytes, const std::string& extension) {
  static const std::string directory = [] {
    std::error_code error;
    if (std::filesystem::is_directory("/dev/shm", error)) return std::string("/dev/shm");
    return std::filesystem::temp_directory_path().string();
  }();
  const std::string path = directory + "/tactile-fuzz-" + std::to_string(::getpid()) + extension;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) __builtin_trap();
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size())
    __builtin_trap();
  std::fclose(file);
  return path;
}

}  // namespace tactile::fuzz
