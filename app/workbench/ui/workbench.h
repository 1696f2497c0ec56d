#pragma once
// The workbench's main window, drawn with ImGui; shared by the windowed and the
// headless program, which only supply the frame loop and the OpenGL backend.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "document.h"
#include "file_browser.h"
#include "tactile/live/playback.h"
#include "tactile/signal/display_scale.h"
#include "tactile/widgets/signal_plot.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {

struct WorkbenchOptions {
  std::string open_path;    // a recording, or a folder (workspace) whose first recording opens
  std::string labels_path;  // label database; default labels.db beside the recording
  std::optional<double> time;
  bool play = false;
};

class Workbench {
 public:
  explicit Workbench(const WorkbenchOptions& options);
  // Advances the replay clock by `seconds` of wall time and draws one frame.
  void frame(double seconds);
  bool quit_requested() const { return quit_; }
  // The last error (opening a file, ...), shown in the status bar; "" when none.
  const std::string& error() const { return error_; }
  const Document* document() const { return document_.get(); }

 private:
  void open(const std::string& path);
  void set_workspace(const std::string& folder);
  void choose_default_view();
  void draw_menu_bar();
  void draw_sidebar(float width, float height);
  void draw_skin_panel(float width, float height);
  void draw_plot_panel(float width, float height);
  void draw_transport(float width);
  void draw_labels_panel(float width, float height);
  void draw_status_bar();
  void toggle_taxel_channels(int64_t taxel_id);

  WorkbenchOptions options_;
  std::unique_ptr<Document> document_;
  std::string workspace_;
  std::vector<std::string> workspace_files_;
  PlaybackClock clock_;
  SignalPlotState plot_state_;
  std::vector<char> plotted_;  // per channel of the current stream
  int modality_ = 0;
  SkinViewZoom skin_zoom_;
  // The skin shows each taxel's change from its rest level unless raw values are asked for.
  bool show_raw_values_ = false;
  RestScale rest_scale_;
  int rest_scale_modality_ = -1;  // modality rest_scale_ was computed for; -1: stale
  bool quit_ = false;
  std::string error_;
  FileBrowser file_browser_;
};

}  // namespace tactile
