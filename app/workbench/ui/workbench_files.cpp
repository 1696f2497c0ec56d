// The Workbench's side of the file commands (files.h): what changes the workspace.
#include <filesystem>

#include "workbench.h"

namespace tactile {

void Workbench::open_folder(const std::string& folder) {
  set_workspace(folder);
  // The first recording that opens; the damaged ones before it are marked.
  for (const std::string& file : state_.workspace_files)
    if (open(file)) return;
  if (state_.workspace_files.empty()) state_.notice = "no .h5 recordings in " + state_.workspace;
}

void Workbench::carry_out_file_requests() {
  FilesState& files = state_.files;
  if (auto folder = std::exchange(files.folder_request, std::nullopt)) open_folder(*folder);
  // Files were written (an import): the list shows them; an open request may follow.
  if (std::exchange(files.refresh_workspace, false) && !state_.workspace.empty())
    set_workspace(state_.workspace);
}

}  // namespace tactile
