#pragma once
// A small file dialog drawn with ImGui: Dear ImGui has none, and the workbench must not depend
// on a desktop toolkit. Three modes: open a file (listing the wanted extensions), choose a
// folder, save a file (a name field; an existing file is written over only after a
// confirmation). One dialog at a time; the choice comes back once, with the purpose it was
// opened for, so one dialog serves File > Open, Open folder, Import, Export, Verify, ...
// Escape closes it (a modal that stayed open would take every click and key).
//
// Items for scripts: browser:folder:NAME, browser:file:NAME, browser:Up, browser:path (the
// path or name field), browser:OK (Open / Choose / Save), browser:Overwrite, browser:Cancel.

#include <optional>
#include <string>
#include <vector>

namespace tactile {

struct WorkbenchState;

enum class BrowseMode { kOpenFile, kChooseFolder, kSaveFile };
const char* to_string(BrowseMode mode);

struct BrowseRequest {
  BrowseMode mode = BrowseMode::kOpenFile;
  std::string purpose = "open";  // handed back with the choice
  std::string title = "Open recording";
  std::string directory;                // where it starts ("" = the current folder)
  std::vector<std::string> extensions;  // files listed (open, save); empty = every file
  std::string file_name;                // save: the name proposed
};

struct BrowseChoice {
  std::string purpose;
  std::string path;  // absolute
};

class FileBrowser {
 public:
  void open(BrowseRequest request);
  // File > Open: a recording.
  void open(const std::string& directory, std::vector<std::string> extensions);
  // Draws the dialog when open; the choice once, when made.
  std::optional<BrowseChoice> draw(WorkbenchState& state);
  bool is_open() const { return open_; }
  const BrowseRequest& request() const { return request_; }
  const std::string& directory() const { return directory_; }

 private:
  void list_directory();
  void enter(const std::string& directory);
  void close();
  // The typed text as a path (relative: to the folder shown).
  std::string typed_path() const;

  bool open_ = false;
  bool request_popup_ = false;
  BrowseRequest request_;
  std::string directory_;
  std::vector<std::string> folders_;
  std::vector<std::string> files_;
  std::string error_;
  std::string confirm_;  // save: the existing file waiting for "Overwrite"
  char typed_[1024] = {};
};

}  // namespace tactile
