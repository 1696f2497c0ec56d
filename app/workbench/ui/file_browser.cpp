#include "file_browser.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

const char* to_string(BrowseMode mode) {
  switch (mode) {
    case BrowseMode::kOpenFile:
      return "open";
    case BrowseMode::kChooseFolder:
      return "folder";
    case BrowseMode::kSaveFile:
      return "save";
  }
  return "open";
}

void FileBrowser::open(BrowseRequest request) {
  request_ = std::move(request);
  open_ = true;
  request_popup_ = true;
  confirm_.clear();
  typed_[0] = '\0';
  if (request_.mode == BrowseMode::kSaveFile)
    std::snprintf(typed_, sizeof(typed_), "%s", request_.file_name.c_str());
  enter(request_.directory.empty() ? "." : request_.directory);
}

void FileBrowser::open(const std::string& directory, std::vector<std::string> extensions) {
  BrowseRequest request;
  request.directory = directory;
  request.extensions = std::move(extensions);
  open(std::move(request));
}

void FileBrowser::enter(const std::string& directory) {
  std::error_code error;
  directory_ = fs::absolute(directory, error).lexically_normal().string();
  while (directory_.size() > 1 && directory_.back() == '/') directory_.pop_back();
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
    } else if (request_.mode != BrowseMode::kChooseFolder) {
      const std::vector<std::string>& extensions = request_.extensions;
      const bool wanted =
          extensions.empty() ||
          std::any_of(extensions.begin(), extensions.end(), [&](const std::string& ext) {
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

void FileBrowser::close() {
  open_ = false;
  confirm_.clear();
}

std::string FileBrowser::typed_path() const {
  const fs::path typed(typed_);
  return (typed.is_absolute() ? typed : fs::path(directory_) / typed).lexically_normal().string();
}

std::optional<BrowseChoice> FileBrowser::draw(WorkbenchState& state) {
  if (!open_) return std::nullopt;
  // One popup id whatever the title, so a new request replaces the dialog shown.
  const std::string popup = request_.title + "###file browser";
  if (request_popup_) {
    ImGui::OpenPopup(popup.c_str());
    request_popup_ = false;
  }
  std::optional<std::string> chosen;
  ImGui::SetNextWindowSize(ImVec2(620, 440), ImGuiCond_Appearing);
  ImGui::SetNextWindowBgAlpha(1.0f);
  bool keep = true;
  if (!ImGui::BeginPopupModal(popup.c_str(), &keep)) {
    // Closed by its title bar's button (or never shown): the dialog is over.
    if (!keep || !ImGui::IsPopupOpen(popup.c_str())) close();
    return std::nullopt;
  }
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) keep = false;
  ImGui::TextUnformatted(directory_.c_str());
  if (ImGui::Button("Up")) enter(fs::path(directory_).parent_path().string());
  remember_item(state, "browser:Up");
  if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
  const bool saving = request_.mode == BrowseMode::kSaveFile;
  const bool folders = request_.mode == BrowseMode::kChooseFolder;
  ImGui::BeginChild("entries", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2.2f), true);
  std::string entered;
  for (const std::string& folder : folders_) {
    if (ImGui::Selectable((folder + "/").c_str(), false, ImGuiSelectableFlags_DontClosePopups))
      entered = folder;
    remember_item(state, "browser:folder:" + folder);
  }
  for (const std::string& file : files_) {
    if (ImGui::Selectable(file.c_str(), false, ImGuiSelectableFlags_DontClosePopups)) {
      if (saving) {
        // A click on a file takes its name; the save is still to be confirmed.
        std::snprintf(typed_, sizeof(typed_), "%s", file.c_str());
        confirm_.clear();
      } else {
        chosen = (fs::path(directory_) / file).string();
      }
    }
    remember_item(state, "browser:file:" + file);
  }
  ImGui::EndChild();
  if (!entered.empty()) enter((fs::path(directory_) / entered).string());
  const char* action = saving ? "Save" : (folders ? "Choose" : "Open");
  const char* hint = saving ? "file name" : (folders ? "folder (empty: the one shown)" : "path");
  ImGui::SetNextItemWidth(-80);
  const bool typed = ImGui::InputTextWithHint("##path", hint, typed_, sizeof(typed_),
                                              ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemEdited()) confirm_.clear();
  remember_item(state, "browser:path");
  ImGui::SameLine();
  const bool pressed = ImGui::Button(action);
  remember_item(state, "browser:OK");
  if ((pressed || typed) && confirm_.empty()) {
    if (folders) {
      chosen = typed_[0] == '\0' ? directory_ : typed_path();
    } else if (typed_[0] != '\0') {
      const std::string path = typed_path();
      std::error_code error;
      if (fs::is_directory(path, error)) {
        enter(path);  // a folder typed: shown, not chosen
        typed_[0] = '\0';
      } else if (saving && fs::exists(path, error)) {
        confirm_ = path;  // never written over without a second yes
      } else {
        chosen = path;
      }
    }
  }
  if (!confirm_.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "%s exists.",
                       fs::path(confirm_).filename().string().c_str());
    ImGui::SameLine();
    if (ImGui::Button("Overwrite")) chosen = confirm_;
    remember_item(state, "browser:Overwrite");
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) confirm_.clear();
    remember_item(state, "browser:Cancel");
  }
  if (chosen || !keep) {
    close();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  if (!chosen) return std::nullopt;
  return BrowseChoice{request_.purpose, *chosen};
}

}  // namespace tactile
