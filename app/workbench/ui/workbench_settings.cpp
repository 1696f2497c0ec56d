// The workbench's settings: panel sizes and lanes, per user (~/.config/tactile-workbench).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "workbench.h"

namespace tactile {

namespace fs = std::filesystem;

std::string Workbench::settings_path() const {
  if (!state_.options.settings_path.empty()) return state_.options.settings_path;
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  fs::path folder = config && *config ? fs::path(config) : fs::path(home ? home : ".") / ".config";
  return (folder / "tactile-workbench" / "settings.json").string();
}

void Workbench::load_settings() {
  std::ifstream in(settings_path());
  if (!in) return;
  const nlohmann::json settings = nlohmann::json::parse(in, nullptr, false);
  if (settings.is_discarded() || !settings.is_object() || !settings.contains("panels")) {
    state_.notice = "ignored unreadable settings file " + settings_path();
    return;
  }
  const nlohmann::json& panels = settings["panels"];
  PanelSizes sizes;
  sizes.sidebar_width = panels.value("sidebar_width", sizes.sidebar_width);
  sizes.skin_fraction =
      std::clamp(panels.value("skin_fraction", sizes.skin_fraction), 0.05f, 0.95f);
  sizes.timeline_height = panels.value("timeline_height", sizes.timeline_height);
  state_.sizes = sizes;
  if (settings.contains("labelling") && settings["labelling"].is_object()) {
    const nlohmann::json& labelling = settings["labelling"];
    LabellingState& state = state_.labelling;
    state.annotator = labelling.value("annotator", std::string());
    state.reaction_seconds = std::clamp(labelling.value("reaction_seconds", 0.25), 0.0, 2.0);
    try {
      state.lane_order = labelling.value("lane_order", std::vector<std::string>{});
      const auto hidden = labelling.value("hidden", std::vector<std::string>{});
      const auto collapsed = labelling.value("collapsed", std::vector<std::string>{});
      state.hidden = {hidden.begin(), hidden.end()};
      state.collapsed = {collapsed.begin(), collapsed.end()};
    } catch (const nlohmann::json::exception&) {
      state_.notice = "ignored the lane settings in " + settings_path();
    }
  }
}

void Workbench::save_settings() const {
  const fs::path path = settings_path();
  std::error_code error;
  fs::create_directories(path.parent_path(), error);
  nlohmann::json settings;
  settings["panels"] = {{"sidebar_width", state_.sizes.sidebar_width},
                        {"skin_fraction", state_.sizes.skin_fraction},
                        {"timeline_height", state_.sizes.timeline_height}};
  const LabellingState& labelling = state_.labelling;
  settings["labelling"] = {
      {"annotator", state_.options.annotator.empty() ? labelling.annotator : std::string()},
      {"reaction_seconds", labelling.reaction_seconds},
      {"lane_order", labelling.lane_order},
      {"hidden", std::vector<std::string>(labelling.hidden.begin(), labelling.hidden.end())},
      {"collapsed",
       std::vector<std::string>(labelling.collapsed.begin(), labelling.collapsed.end())}};
  // Written beside and renamed over, so a crash never leaves half a settings file; a
  // folder that cannot be written keeps the sizes for this run only.
  try {
    write_file_atomically(path.string(), settings.dump(2) + "\n", "settings");
  } catch (const Error&) {
  }
}

}  // namespace tactile
