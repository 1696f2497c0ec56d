#pragma once
// The text side of scripted input (docs/SCRIPTING.md): a script's lines parsed into steps and
// key chords, checked before anything runs. No ImGui here, so the parser can be tested and
// fuzzed on its own (tests/fuzz/fuzz_script.cpp); script.h plays the steps.

#include <string>
#include <vector>

namespace tactile {

struct ScriptStep {
  int line = 0;
  std::string command;             // "click", "key", ...
  std::vector<std::string> words;  // the arguments, split at spaces
  std::string rest;                // everything after the command, as written
  size_t form = 0;  // which line of TACTILE_SCRIPT_COMMANDS (script_commands.h) it matched
};

// Parses a script; throws tactile::Error naming "FILE:LINE" for an unknown command (listing
// every command with its help) or a wrong argument.
std::vector<ScriptStep> parse_script(const std::string& text, const std::string& where);
std::vector<ScriptStep> read_script(const std::string& path);

// GLFW's key codes (glfw3.h); printable keys are their ASCII upper case.
constexpr int kKeyTab = 258, kKeyLeft = 263, kKeyRight = 262, kKeyUp = 265, kKeyDown = 264,
              kKeyPageUp = 266, kKeyPageDown = 267, kKeyHome = 268, kKeyEnd = 269, kKeyInsert = 260,
              kKeyDelete = 261, kKeyBackspace = 259, kKeySpace = 32, kKeyEnter = 257,
              kKeyEscape = 256, kKeyPadEnter = 335, kKeyF1 = 290;

struct KeyChord {
  bool ctrl = false, shift = false, alt = false, super = false;
  int code = 0;
  unsigned character = 0;  // text the key types, 0 for none
};

// "Ctrl+Shift+Z", "2", "[", "Enter", "F5". Throws std::invalid_argument with a reason.
KeyChord parse_chord(const std::string& text);

// Argument `index` of `step` as a finite number; throws tactile::Error naming WHERE:LINE.
double parse_number(const ScriptStep& step, size_t index, const std::string& where);

}  // namespace tactile
