#include "keys.h"

#include <imgui.h>

#include <algorithm>

#include "confusion.h"
#include "labelling.h"
#include "live.h"
#include "results.h"
#include "video.h"
#include "views.h"

namespace tactile {

namespace {

bool has_document(const WorkbenchState& state) { return state.document != nullptr; }
bool is_live(const WorkbenchState& state) { return state.live.connected; }
bool always(const WorkbenchState&) { return true; }

// A confusion cell's list of segments is open and has rows.
bool segment_list_open(const WorkbenchState& state) {
  return state.analysis.confusion.list_active && !state.analysis.confusion.cell_rows.empty() &&
         current_evaluation(state) != nullptr;
}
// Enter belongs to a cell's list while one is open and nothing is marked for labelling.
bool enter_lands(const WorkbenchState& state) {
  const LabellingState& labelling = state.labelling;
  return segment_list_open(state) && !labelling.mark_start && !labelling.mark_end &&
         labelling.pending_class.empty();
}
bool enter_commits(const WorkbenchState& state) {
  return has_document(state) && !enter_lands(state);
}

void step_cursor(WorkbenchState& state, double direction, bool by_second) {
  const double rate = state.document->samples().info().rate_hz;
  const double step = by_second ? 1.0 : (rate > 0 ? 1.0 / rate : 0.01);
  state.clock.seek(state.clock.time() + direction * step);
}

void move_in_segment_list(WorkbenchState& state, int direction) {
  AnalysisState& analysis = state.analysis;
  const int last = static_cast<int>(analysis.confusion.cell_rows.size()) - 1;
  analysis.confusion.cell_selected =
      std::clamp(analysis.confusion.cell_selected + direction, 0, last);
}

void land_on_selected_segment(WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  land_on(state, current_evaluation(state)->rows[analysis.confusion.cell_rows[static_cast<size_t>(
                     analysis.confusion.cell_selected)]]);
}

void drop_marks(WorkbenchState& state) {
  state.labelling.mark_start.reset();
  state.labelling.mark_end.reset();
  state.labelling.pending_class.clear();
}

void open_recording_dialog(WorkbenchState& state) {
  state.file_browser.open(state.workspace.empty() ? "." : state.workspace, {".h5"});
}

std::vector<std::string> digit_keys(const std::string& modifier) {
  std::vector<std::string> keys;
  for (int position = 1; position <= 10; ++position)
    keys.push_back(modifier + std::to_string(position % 10));
  return keys;
}

std::vector<KeyBinding> make_bindings() {
  using S = WorkbenchState;
  return {
      {"Files",
       {"Ctrl+O"},
       "open a recording",
       always,
       [](S& s, int) { open_recording_dialog(s); }},
      {"Files", {"Ctrl+Q"}, "quit", always, [](S& s, int) { s.quit = true; }},
      {"Files",
       {"F1"},
       "show or hide this sheet of keys",
       always,
       [](S& s, int) { s.help.keys_open = !s.help.keys_open; }},
      {"Playback", {"Space"}, "play / pause", has_document, [](S& s, int) { s.clock.toggle(); }},
      {"Playback",
       {"Left", "Right"},
       "step one sample back / on",
       has_document,
       [](S& s, int k) { step_cursor(s, k == 0 ? -1.0 : 1.0, false); },
       true},
      {"Playback",
       {"Shift+Left", "Shift+Right"},
       "step one second back / on",
       has_document,
       [](S& s, int k) { step_cursor(s, k == 0 ? -1.0 : 1.0, true); },
       true},
      {"Labelling",
       {"["},
       "mark the start at the cursor (playing: the reaction time earlier)",
       has_document,
       [](S& s, int) { mark_start(s); }},
      {"Labelling", {"]"}, "mark the end", has_document, [](S& s, int) { mark_end(s); }},
      {"Labelling", digit_keys(""), "choose class 1 to 10 of the skin's vocabulary (the legend)",
       has_document, [](S& s, int k) { choose_class(s, k + 1); }},
      {"Labelling", digit_keys("Shift+"), "choose class 11 to 20", has_document,
       [](S& s, int k) { choose_class(s, k + 11); }},
      {"Labelling",
       {"C"},
       "pick any class by typing part of its name",
       has_document,
       [](S& s, int) {
         s.labelling.picker_open = true;
         s.labelling.picker_text.fill('\0');
       }},
      {"Labelling",
       {"Enter", "KeypadEnter"},
       "commit the marked label (no marks: give the selected own label the chosen class)",
       enter_commits,
       [](S& s, int) { commit_label(s); }},
      {"Labelling",
       {"Escape"},
       "drop the marks and the chosen class",
       has_document,
       [](S& s, int) { drop_marks(s); }},
      {"Labelling",
       {"Tab", "Shift+Tab"},
       "select the next / previous own label",
       has_document,
       [](S& s, int k) { walk_labels(s, k == 0 ? +1 : -1); },
       true},
      {"Labelling",
       {"Delete"},
       "remove the selected own label",
       has_document,
       [](S& s, int) { remove_selected_label(s); }},
      {"Labelling",
       {"Ctrl+Z", "Ctrl+Shift+Z"},
       "undo / redo your last edit, also one of an earlier session (the status bar says what it "
       "took back and when), and go to it; while a segmenter runs, Ctrl+Z cancels the run",
       has_document,
       [](S& s, int k) { undo_edit(s, k == 1); }},
      {"Labelling",
       {"S"},
       "snapping of dragged times on / off",
       has_document,
       [](S& s, int) {
         s.labelling.snap = !s.labelling.snap;
         s.notice = s.labelling.snap ? "snapping on" : "snapping off";
       }},
      {"Suggestions",
       {"G"},
       "run the last segmenter again (on opening a skin's first recording: the skin's own)",
       has_document,
       [](S& s, int) { run_segmenter(s, s.labelling.last_segmenter); },
       false,
       [](const S& s) {
         const std::string params = s.labelling.segmenter_params.data();
         return "now: " + s.labelling.last_segmenter + (params.empty() ? "" : " " + params);
       }},
      {"Suggestions",
       {"A"},
       "accept the selected suggestion with the chosen class",
       has_document,
       [](S& s, int) { accept_suggestion(s); }},
      {"Suggestions",
       {"R"},
       "reject the selected suggestion",
       has_document,
       [](S& s, int) { reject_suggestion(s); }},
      {"Predictions",
       {"U"},
       "go to the least sure prediction (smallest margin) not yet decided",
       has_document,
       [](S& s, int) { next_uncertain_prediction(s); }},
      {"Predictions",
       {"Y"},
       "confirm the selected prediction (its class's key corrects it)",
       has_document,
       [](S& s, int) { confirm_prediction(s, ""); }},
      {"Confusion",
       {"N", "Shift+N"},
       "land on the next / previous misclassified segment",
       always,
       [](S& s, int k) { walk_misclassified(s, k == 0 ? +1 : -1); }},
      {"Confusion",
       {"Down", "Up"},
       "move in a clicked cell's list of segments",
       segment_list_open,
       [](S& s, int k) { move_in_segment_list(s, k == 0 ? +1 : -1); },
       true},
      {"Confusion",
       {"Enter", "KeypadEnter"},
       "land on the segment selected in the list",
       enter_lands,
       [](S& s, int) { land_on_selected_segment(s); }},
      {"Video",
       {",", "."},
       "step one frame of the selected video back / on (the cursor moves to it)",
       has_videos,
       [](S& s, int k) { step_video_frame(s, k == 0 ? -1 : 1); },
       true},
      {"Video",
       {"Alt+Left", "Alt+Right"},
       "nudge the selected video one frame earlier / later against the skin (Ctrl+Z undoes)",
       has_videos,
       [](S& s, int k) { nudge_video(s, (k == 0 ? -1.0 : 1.0) * video_frame_seconds(s)); },
       true},
      {"Video",
       {"Alt+Shift+Left", "Alt+Shift+Right"},
       "nudge the selected video a tenth of a second earlier / later",
       has_videos,
       [](S& s, int k) { nudge_video(s, k == 0 ? -0.1 : 0.1); },
       true},
      {"Video",
       {"M"},
       "mark an instant where the video and the skin show the same event; a second mark sets "
       "offset and rate from both",
       has_videos,
       [](S& s, int) { mark_video_instant(s); }},
      {"Video",
       {"V"},
       "choose the next video for these keys",
       has_videos,
       [](S& s, int) { s.video.selected = (s.video.selected + 1) % s.video.videos.size(); }},
      {"Live",
       {"Ctrl+R"},
       "start / stop recording (with the pre-trigger's seconds)",
       is_live,
       [](S& s, int) { s.live.record_request = true; }},
      {"Live",
       {"F"},
       "follow the newest sample, or stay",
       is_live,
       [](S& s, int) { s.live.follow = !s.live.follow; }},
  };
}

// The chords of every binding, parsed once.
struct ParsedBinding {
  const KeyBinding* binding;
  std::vector<KeyChord> chords;
};

const std::vector<ParsedBinding>& parsed_bindings() {
  static const std::vector<ParsedBinding> parsed = [] {
    std::vector<ParsedBinding> all;
    for (const KeyBinding& binding : key_bindings()) {
      ParsedBinding entry{&binding, {}};
      for (const std::string& key : binding.keys) entry.chords.push_back(parse_chord(key));
      all.push_back(std::move(entry));
    }
    return all;
  }();
  return parsed;
}

bool chord_pressed(const KeyChord& chord, bool repeat) {
  const ImGuiIO& io = ImGui::GetIO();
  return io.KeyCtrl == chord.ctrl && io.KeyShift == chord.shift && io.KeyAlt == chord.alt &&
         io.KeySuper == chord.super && ImGui::IsKeyPressed(chord.code, repeat);
}

}  // namespace

const std::vector<KeyBinding>& key_bindings() {
  static const std::vector<KeyBinding> bindings = make_bindings();
  return bindings;
}

std::string keys_text(const KeyBinding& binding) {
  const std::vector<std::string>& keys = binding.keys;
  if (keys.size() > 2) return keys.front() + " ... " + keys[keys.size() - 2] + ", " + keys.back();
  if (keys.size() == 2 && keys[1] == "KeypadEnter") return keys.front();
  return keys.size() == 2 ? keys[0] + " / " + keys[1] : keys.front();
}

std::string key_sheet_text(const KeyBinding& binding, const WorkbenchState& state) {
  std::string text = binding.what;
  if (binding.now && state.document) text += "; " + binding.now(state);
  return text;
}

std::string class_key(int position) {
  if (position < 1 || position > 20) return "";
  const std::string digit = std::to_string(position % 10);
  return position <= 10 ? digit : "Shift+" + digit;
}

void handle_keys(WorkbenchState& state) {
  const bool typing = ImGui::GetIO().WantTextInput;
  // Collected first: an action may change what the conditions of later bindings see (Enter
  // that lands closes the list; Enter that commits must not then land as well).
  std::vector<std::pair<const KeyBinding*, int>> fired;
  for (const ParsedBinding& entry : parsed_bindings()) {
    const KeyBinding& binding = *entry.binding;
    if (typing && binding.keys.front() != "F1") continue;
    if (binding.when && !binding.when(state)) continue;
    for (size_t k = 0; k < entry.chords.size(); ++k)
      if (chord_pressed(entry.chords[k], binding.repeat))
        fired.emplace_back(&binding, static_cast<int>(k));
  }
  for (const auto& [binding, index] : fired) binding->act(state, index);
}

void draw_key_sheet(WorkbenchState& state) {
  if (!state.help.keys_open) return;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowSize(ImVec2(std::min(720.0f, viewport->WorkSize.x - 40.0f),
                                  std::min(600.0f, viewport->WorkSize.y - 40.0f)),
                           ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x * 0.5f,
                                 viewport->WorkPos.y + viewport->WorkSize.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Keys (F1)", &state.help.keys_open, ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  remember_item(state, "window:keys");
  if (ImGui::IsWindowFocused() && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    state.help.keys_open = false;
  ImGui::TextDisabled("Keys act on the open recording; none while a text field has the keyboard.");
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY)) {
    ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, 240.0f);
    ImGui::TableSetupColumn("what");
    const char* area = "";
    for (const KeyBinding& binding : key_bindings()) {
      if (std::string(area) != binding.area) {
        area = binding.area;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.4f, 1.0f), "%s", area);
      }
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(keys_text(binding).c_str());
      ImGui::TableNextColumn();
      ImGui::TextWrapped("%s", key_sheet_text(binding, state).c_str());
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace tactile
