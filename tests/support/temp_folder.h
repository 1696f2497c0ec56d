#pragma once
// The tests' one temporary folder and their one way to read a refusal: every suite (core, cli,
// render) includes this instead of writing its own.
#include <stdlib.h>

#include <filesystem>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>

#include "tactile/error.h"

namespace tactile::test {

// A fresh folder under the system's temp directory (PREFIX-XXXXXX, mkdtemp), removed with
// everything in it when the object goes.
class TempFolder {
 public:
  explicit TempFolder(const std::string& prefix = "tactile-test") {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (!mkdtemp(pattern.data()))
      throw std::runtime_error("cannot create a temp folder " + pattern);
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // The entries in the folder, to see that nothing was left behind.
  int entry_count() const {
    return static_cast<int>(std::distance(std::filesystem::directory_iterator(path_),
                                          std::filesystem::directory_iterator()));
  }

 private:
  std::filesystem::path path_;
};

// The message of the tactile::Error that `call` threw, "" when it threw none.
inline std::string refusal_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

}  // namespace tactile::test
