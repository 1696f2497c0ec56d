#pragma once
// The script commands (docs/SCRIPTING.md), listed once. The parser (script_parse.cpp, built
// without ImGui so that it can be fuzzed alone) and the player (script.cpp) expand this one
// list, each taking the columns it needs; a test checks the documentation's table against it.
//
// X(USAGE, HELP, FEWEST, MOST, CHECK, EXPAND), one line per form of a command:
//   USAGE   as documented: the command, then a lower-case keyword when the form has one (the
//           first argument picks the form: `click taxel 3`; a form without a keyword takes
//           what no keyword took: `click skin 0.5 0.5`), then its arguments in upper case;
//   HELP    one line, the start of the documentation's description;
//   FEWEST, MOST  how many words may follow the command, the keyword counted (kAnyWords: no
//           limit; words beyond the usage's are ignored where they always were);
//   CHECK   the parser's check of the words before anything runs (script_parse.cpp), or
//           nullptr when the counts are all there is to check;
//   EXPAND  the ScriptPlayer member that turns the step into its frames' actions (script.cpp).

#include <cstddef>
#include <limits>

namespace tactile {

inline constexpr size_t kAnyWords = std::numeric_limits<size_t>::max();

}  // namespace tactile

// clang-format off
#define TACTILE_SCRIPT_COMMANDS(X)                                                                 \
  X("open PATH", "open a recording (or a folder: a workspace)",                                    \
    1, kAnyWords, nullptr, open_path)                                                              \
  X("time T", "move the time cursor to T",                                                         \
    1, 1, check_script_not_negative, move_time)                                                    \
  X("key KEYS", "press and release keys, one after the other",                                     \
    1, kAnyWords, check_script_key_chords, press_keys)                                             \
  X("type TEXT", "type text into the focused field",                                               \
    1, kAnyWords, nullptr, type_text)                                                              \
  X("click taxel ID", "click the centre of taxel ID in the skin view",                             \
    2, kAnyWords, check_script_taxel_id, click_taxel)                                              \
  X("click time T [in VIEW]", "click a time-axis view at T",                                       \
    2, kAnyWords, check_script_one_number, click_time)                                             \
  X("drag time T0 T1 [in VIEW]", "press at T0, move to T1 in 8 steps, release",                   \
    3, 5, check_script_two_numbers, drag_time)                                                     \
  X("drag taxel A B", "a left-drag over the skin from taxel A to taxel B",                         \
    3, 5, check_script_two_numbers, drag_taxels)                                                   \
  X("drag item NAME X0 Y0 X1 Y1",                                                                  \
    "a left-drag over a named item from fractions X0, Y0 of its size to X1, Y1",                   \
    6, 6, check_script_four_numbers, drag_item)                                                    \
  X("click recording NAME", "click a recording in the workspace list",                             \
    2, 2, nullptr, click_recording)                                                                \
  X("click item NAME", "click any named item as last drawn",                                       \
    2, kAnyWords, nullptr, click_item)                                                             \
  X("click cell TRUE PREDICTED", "click a cell of the confusion matrix",                           \
    3, 3, nullptr, click_cell)                                                                     \
  X("click VIEW X Y", "click a view at fractions X, Y of its size",                                \
    3, 3, check_script_two_numbers, click_view)                                                    \
  X("menu PATH", "choose a menu item",                                                             \
    1, kAnyWords, nullptr, choose_menu)                                                            \
  X("wait N", "draw N frames",                                                                     \
    1, 1, check_script_frame_count, wait_frames)                                                   \
  X("wait training", "keep drawing frames until the model panel's training run ends",              \
    1, 1, nullptr, wait_training)                                                                  \
  X("wait jobs", "keep drawing frames until no job runs and every result is applied",              \
    1, 1, nullptr, wait_jobs)                                                                      \
  X("wait video", "keep drawing frames until every video shows the frame at the cursor",          \
    1, 1, nullptr, wait_video)                                                                     \
  X("wait labels N", "keep drawing frames until the open recording shows N labels",                \
    2, 2, check_script_one_number, wait_labels)                                                    \
  X("wait results N", "keep drawing frames until the model panel's results hold N rows",           \
    2, 2, check_script_one_number, wait_results)                                                   \
  X("play SECONDS", "play for this much recording time (at the current speed), then pause",       \
    1, 1, check_script_not_negative, play_recording)                                               \
  X("sleep SECONDS", "keep drawing frames for this much wall-clock time (live data arrives)",      \
    1, 1, check_script_not_negative, sleep_wall_clock)                                             \
  X("fault read MODE", "make the open recording's reads hang, fail or work again",                  \
    2, 2, check_script_fault_mode, inject_fault)                                                   \
  X("screenshot PATH", "write the window as PNG",                                                  \
    1, kAnyWords, nullptr, write_screenshot)                                                       \
  X("state PATH", "write the workbench's state as JSON",                                           \
    1, kAnyWords, nullptr, write_state)
// clang-format on
