#pragma once
// The workbench's window, drawn with ImGui; shared by the windowed and the headless
// program, which only supply the frame loop and the OpenGL backend. It arranges the
// views (views.h) with splitters, runs the menus and carries out the views' requests.

#include <array>
#include <initializer_list>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "services.h"
#include "tactile/widgets/image.h"
#include "workbench_state.h"

namespace tactile {

// A view to write as PNG once the frame is rendered: the caller crops `area` from the
// frame's pixels.
struct ViewExport {
  std::string view;
  std::string path;
  ScreenRect area;
};

class Workbench {
 public:
  explicit Workbench(const WorkbenchOptions& options);
  ~Workbench();  // a recording in progress is finished
  // Advances the replay clock by `seconds` of wall time and draws one frame.
  void frame(double seconds);
  bool quit_requested() const { return state_.quit; }
  // A job (segmenter, predict, SOM, scatter, somatosensory map, export, a file command or the
  // import preview) runs or its result is not applied yet: a screenshot waits for it, and so
  // does `wait jobs`.
  bool jobs_running() const;
  // The last error (opening a file, ...), shown in the status bar; "" when none.
  const std::string& error() const { return state_.error; }
  WorkbenchState& state() { return state_; }
  const WorkbenchState& state() const { return state_; }
  // The threads, sockets and files behind the state (services.h); for the program's loop and
  // benchmarks, never for views.
  WorkbenchServices& services() { return services_; }

  // Commands (scripts and menus go through these too).
  // False when the recording cannot be opened: it is marked damaged, with the reason.
  bool open(const std::string& path);
  // A folder as the workspace, and its first recording that opens (as `tactile-workbench
  // FOLDER` and File > Open folder do).
  void open_folder(const std::string& folder);
  void seek(double time);
  void fail(const std::string& message) { state_.error = message; }
  // A view export requested this frame (File > Export view as PNG), taken once.
  std::optional<ViewExport> take_export();
  // Writes the export's pixels (cropped from the rendered frame) as PNG on a worker; the
  // notice names the file once it is written.
  void write_export(const ViewExport& request, Image pixels);
  // The state as JSON (the script command `state PATH`).
  nlohmann::json state_json() const;

 private:
  void frame_work(double seconds);  // frame() without its timing
  void set_workspace(const std::string& folder);
  void select_stream(const std::string& stream);
  DocumentOptions document_options(const std::string& stream) const;
  void choose_default_view();
  void draw_menu_bar();
  void draw_video_menu();
  // A tab bar of views; a view asked for by state.analysis.tab_request comes to front.
  void draw_tabs(std::initializer_list<const char*> names);
  void open_analysis_files();
  nlohmann::json analysis_json() const;
  void draw_arrangement(ImVec2 area);
  void draw_view(const char* name, ImVec2 size);
  void draw_status_bar();
  // An empty window says what to do first: open, import, or make the demo workspace.
  void draw_welcome(ImVec2 size);
  // Help > Getting started: the first hour in a few lines.
  void draw_getting_started();
  // Makes the demo workspace in `folder` as a job; when it ends the folder opens.
  void start_demo(const std::string& folder);
  void carry_out_requests();
  // The file commands' requests (files.h): a new workspace, a list to read again.
  void carry_out_file_requests();
  // Marks the open recording damaged when its source read a damaged chunk as a gap.
  void note_damage();
  void load_settings();
  void save_settings() const;
  std::string settings_path() const;

  WorkbenchState state_;
  // How many of state_.frame_seconds the last state_json() had seen: its `since_last_state`
  // figures are of the frames after them (a benchmark's measured stretch).
  mutable size_t frames_reported_ = 0;
  WorkbenchServices services_;  // after the state: destroyed first (a recording is finished)
  std::array<char, 256> connect_url_{"sim://nao"};
  std::array<char, 32> connect_skin_{};
  std::array<char, 1024> demo_folder_{};
  std::optional<ViewExport> export_;
};

}  // namespace tactile
