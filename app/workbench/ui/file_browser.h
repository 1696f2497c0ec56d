#pragma once
// A small file-open dialog drawn with ImGui: Dear ImGui has none, and the workbench
// must not depend on a desktop toolkit.

#include <optional>
#include <string>
#include <vector>

namespace tactile {

class FileBrowser {
 public:
  // Opens the dialog at `directory`, listing files whose name ends in one of `extensions`.
  void open(const std::string& directory, std::vector<std::string> extensions);
  // Draws the dialog when open; returns the chosen file once.
  std::optional<std::string> draw();
  bool is_open() const { return open_; }

 private:
  void list_directory();

  bool open_ = false;
  bool request_popup_ = false;
  std::string directory_;
  std::vector<std::string> extensions_;
  std::vector<std::string> folders_;
  std::vector<std::string> files_;
  std::string error_;
  char typed_path_[1024] = {};
};

}  // namespace tactile
