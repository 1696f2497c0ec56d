// Recording arguments shared by the commands that take files or folders of them.
#include <algorithm>
#include <filesystem>

#include "commands.h"
#include "tactile/error.h"

namespace tactile::cli {

// Files as given; folders expanded to their .h5 files, sorted, so runs are repeatable.
std::vector<std::string> recording_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& input : inputs) {
    std::error_code error;
    if (std::filesystem::is_directory(input, error)) {
      std::vector<std::string> found;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(input))
        if (entry.is_regular_file() && entry.path().extension() == ".h5")
          found.push_back(entry.path().string());
      if (found.empty()) throw Error(input, "folder holds no .h5 recordings");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (std::filesystem::is_regular_file(input, error)) {
      files.push_back(input);
    } else {
      throw Error(input, "no such recording file or folder");
    }
  }
  return files;
}

}  // namespace tactile::cli
