#pragma once
// Every key of the workbench in one table. The key handling reads it each frame and the
// Help > Keys sheet (F1) lists it, so the sheet cannot drift from what the keys do. Keys are
// written as scripts write them (`Ctrl+Shift+Z`, `[`, `F1`: parse_chord in script_parse.h).

#include <string>
#include <vector>

#include "script_parse.h"
#include "workbench_state.h"

namespace tactile {

struct KeyBinding {
  const char* area;  // the sheet's heading: "Files", "Playback", "Labelling", ...
  // One action over one or several keys: the digits choose classes, by their position here.
  std::vector<std::string> keys;
  const char* what;
  // When the binding applies (null: whenever no text field has the keyboard). A key with two
  // meanings (Enter) has two bindings whose conditions exclude each other.
  bool (*when)(const WorkbenchState&) = nullptr;
  // `index`: which of `keys` was pressed.
  void (*act)(WorkbenchState&, int index) = nullptr;
  bool repeat = false;  // held down, the key repeats (arrows)
  // What the key would do now, when that depends on the state (G: the segmenter it runs);
  // the sheet shows it after `what`.
  std::string (*now)(const WorkbenchState&) = nullptr;
};

// The table, in the sheet's order.
const std::vector<KeyBinding>& key_bindings();
// The keys of a binding as the sheet shows them: "Ctrl+Z", "1 ... 9, 0", "Tab / Shift+Tab".
std::string keys_text(const KeyBinding& binding);
// A binding's line on the sheet: `what`, and what it would do now when that depends on the state.
std::string key_sheet_text(const KeyBinding& binding, const WorkbenchState& state);
// The key that chooses class `position` (1-based) of a vocabulary: 1-9, 0 for the tenth,
// Shift+1 ... Shift+0 for the 11th to 20th; "" beyond (the C picker reaches every class).
std::string class_key(int position);

// Carries out this frame's key presses through the table (ImGui's input path). Nothing while a
// text field has the keyboard, except F1.
void handle_keys(WorkbenchState& state);
// The Help > Keys window (F1), drawn from the table, when open.
void draw_key_sheet(WorkbenchState& state);

}  // namespace tactile
