#include "file_browser.h"

#include <imgui.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

namespace tactile {

namespace fs = std::filesystem;

void FileBrowser::open(const std::string& directory, std::vector<std::string> extensions) {
  std::error_code error;
  directory_ = fs::absolute(directory.empty() ? "." : directory, error).lexically_normal().string();
  extensions_ = std::move(extensions);
  open_ = true;
  request_popup_ = true;
  typed_path_[0] = '\0';
  list_directory();
}

void FileBrowser::list_directory() {
  folders_.clear();
  files_.clear();
  error_.clear();
  std::error_code error;
  for (fs::directory_iterator it(directory_, error), end; !error && it != end;
       it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code type_error;
    if (it->is_directory(type_error)) {
      folders_.push_back(name);
    } else {
      const bool wanted =
          extensions_.empty() ||
          std::any_of(extensions_.begin(), extensions_.end(), [&](const std::string& ext) {
            return name.size() >= ext.size() &&
                   name.compare(name.size() - ext.size(), ext.size(), ext) == 0;
          });
      if (wanted) files_.push_back(name);
    }
  }
  if (error) error_ = directory_ + ": " + error.message();
  std::sort(folders_.begin(), folders_.end());
  std::sort(files_.begin(), files_.end());
}

std::optional<std::string> FileBrowser::draw() {
  if (!open_) return std::nullopt;
  if (request_popup_) {
    ImGui::OpenPopup("Open recording");
    request_popup_ = false;
  }
  std::optional<std::string> chosen;
  ImGui::SetNextWindowSize(ImVec2(620, 440), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal("Open recording", &open_)) {
    ImGui::TextUnformatted(directory_.c_str());
    if (ImGui::Button("Up")) {
      directory_ = fs::path(directory_).parent_path().string();
      list_directory();
    }
    if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
    ImGui::BeginChild("entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2), true);
    std::string enter;
    for (const std::string& folder : folders_)
      if (ImGui::Selectable((folder + "/").c_str(), false, ImGuiSelectableFlags_DontClosePopups))
        enter = folder;
    for (const std::string& file : files_)
      if (ImGui::Selectable(file.c_str(), false, ImGuiSelectableFlags_AllowDoubleClick))
        chosen = (fs::path(directory_) / file).string();
    ImGui::EndChild();
    if (!enter.empty()) {
      directory_ = (fs::path(directory_) / enter).string();
      list_directory();
    }
    ImGui::SetNextItemWidth(-80);
    const bool typed = ImGui::InputText("##path", typed_path_, sizeof(typed_path_),
                                        ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button("Open") || typed) && typed_path_[0] != '\0') {
      const fs::path typed_path(typed_path_);
      chosen = (typed_path.is_absolute() ? typed_path : fs::path(directory_) / typed_path).string();
    }
    if (chosen) {
      open_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  return chosen;
}

}  // namespace tactile
