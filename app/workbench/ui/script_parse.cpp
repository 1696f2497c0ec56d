#include "script_parse.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "script_commands.h"
#include "tactile/error.h"

namespace tactile {

namespace {

const std::map<std::string, int>& named_keys() {
  static const std::map<std::string, int> keys = {
      {"tab", kKeyTab},           {"left", kKeyLeft},
      {"right", kKeyRight},       {"up", kKeyUp},
      {"down", kKeyDown},         {"pageup", kKeyPageUp},
      {"pagedown", kKeyPageDown}, {"home", kKeyHome},
      {"end", kKeyEnd},           {"insert", kKeyInsert},
      {"delete", kKeyDelete},     {"backspace", kKeyBackspace},
      {"space", kKeySpace},       {"enter", kKeyEnter},
      {"return", kKeyEnter},      {"escape", kKeyEscape},
      {"esc", kKeyEscape},        {"keypadenter", kKeyPadEnter}};
  return keys;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// "FILE:LINE" of a step, where errors name it.
std::string place_of(const ScriptStep& step, const std::string& where) {
  return where + ":" + std::to_string(step.line);
}

}  // namespace

// Key names, F-keys and printable characters; modifiers joined by '+'.
KeyChord parse_chord(const std::string& text) {
  KeyChord chord;
  std::string rest = text;
  // Split at '+' except a trailing '+' that is the key itself ("Ctrl++").
  std::vector<std::string> parts;
  size_t start = 0;
  while (start < rest.size()) {
    size_t plus = rest.find('+', start);
    if (plus == start) plus = rest.find('+', start + 1);
    if (plus == std::string::npos) plus = rest.size();
    parts.push_back(rest.substr(start, plus - start));
    start = plus + 1;
  }
  if (parts.empty()) throw std::invalid_argument("no key");
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string modifier = lower(parts[k]);
    if (modifier == "ctrl" || modifier == "control")
      chord.ctrl = true;
    else if (modifier == "shift")
      chord.shift = true;
    else if (modifier == "alt")
      chord.alt = true;
    else if (modifier == "super" || modifier == "cmd")
      chord.super = true;
    else
      throw std::invalid_argument("unknown modifier '" + parts[k] + "' (Ctrl, Shift, Alt, Super)");
  }
  const std::string key = parts.back();
  const auto named = named_keys().find(lower(key));
  if (named != named_keys().end()) {
    chord.code = named->second;
    if (chord.code == kKeySpace) chord.character = ' ';
    return chord;
  }
  if (key.size() >= 2 && (key[0] == 'F' || key[0] == 'f') &&
      std::all_of(key.begin() + 1, key.end(), ::isdigit)) {
    // At most two digits: a longer number is no F-key (and would overflow std::stoi).
    const int number = key.size() <= 3 ? std::stoi(key.substr(1)) : 0;
    if (number < 1 || number > 12) throw std::invalid_argument("F1 to F12 only");
    chord.code = kKeyF1 + number - 1;
    return chord;
  }
  if (key.size() != 1 || static_cast<unsigned char>(key[0]) < 33 ||
      static_cast<unsigned char>(key[0]) > 126)
    throw std::invalid_argument("unknown key '" + key + "'");
  const char c = key[0];
  chord.code = std::toupper(static_cast<unsigned char>(c));
  chord.character = static_cast<unsigned char>(chord.shift ? std::toupper(c) : c);
  return chord;
}

double parse_number(const ScriptStep& step, size_t index, const std::string& where) {
  if (index >= step.words.size())
    throw Error(place_of(step, where), step.command + ": a number is missing");
  const std::string& word = step.words[index];
  try {
    size_t used = 0;
    const double value = std::stod(word, &used);
    if (used != word.size() || !std::isfinite(value)) throw std::invalid_argument(word);
    return value;
  } catch (const std::exception&) {
    throw Error(place_of(step, where), step.command + ": '" + word + "' is not a number");
  }
}

//---- Checks of the arguments (the CHECK column of script_commands.h)

namespace {

// The first argument, a number that is not negative.
double not_negative_number(const ScriptStep& step, const std::string& where) {
  const double value = parse_number(step, 0, where);
  if (value < 0) throw Error(place_of(step, where), step.command + ": must not be negative");
  return value;
}

void check_script_not_negative(const ScriptStep& step, const std::string& where) {
  not_negative_number(step, where);
}

// `wait 0.5` would draw no frame at all: a script meaning seconds gets told so.
void check_script_frame_count(const ScriptStep& step, const std::string& where) {
  const double frames = not_negative_number(step, where);
  if (frames != std::floor(frames) || frames > 1e6)
    throw Error(place_of(step, where),
                "wait: " + step.words[0] +
                    " is not a whole number of frames (up to 1000000); for seconds use 'sleep' "
                    "(wall clock) or 'play' (recording time)");
}

void check_script_fault_mode(const ScriptStep& step, const std::string& where) {
  const std::string& mode = step.words[1];
  if (mode != "hang" && mode != "fail" && mode != "off")
    throw Error(place_of(step, where), "fault read: " + mode + " is not hang, fail or off");
}

void check_script_key_chords(const ScriptStep& step, const std::string& where) {
  for (const std::string& word : step.words) {
    try {
      parse_chord(word);
    } catch (const std::invalid_argument& reason) {
      throw Error(place_of(step, where), "key " + word + ": " + reason.what());
    }
  }
}

void check_script_taxel_id(const ScriptStep& step, const std::string& where) {
  const double id = parse_number(step, 1, where);
  if (id != std::floor(id))
    throw Error(place_of(step, where), "click taxel: " + step.words[1] + " is not a taxel id");
}

void check_script_one_number(const ScriptStep& step, const std::string& where) {
  parse_number(step, 1, where);
}

void check_script_two_numbers(const ScriptStep& step, const std::string& where) {
  parse_number(step, 1, where), parse_number(step, 2, where);
}

// drag item NAME X0 Y0 X1 Y1: four fractions after the name.
void check_script_four_numbers(const ScriptStep& step, const std::string& where) {
  for (size_t k = 2; k < 6; ++k) parse_number(step, k, where);
}

//---- The table

using ScriptCheck = void (*)(const ScriptStep&, const std::string& where);

struct ScriptForm {
  std::string_view usage, help;
  size_t fewest, most;
  ScriptCheck check;

  std::string_view command() const { return usage.substr(0, usage.find(' ')); }
  // The lower-case word after the command that picks this form; "" for none.
  std::string_view keyword() const {
    if (usage.find(' ') == std::string_view::npos) return {};
    const size_t start = usage.find(' ') + 1;
    const std::string_view word = usage.substr(start, usage.find(' ', start) - start);
    return std::islower(static_cast<unsigned char>(word[0])) ? word : std::string_view();
  }
};

#define TACTILE_SCRIPT_FORM(usage, help, fewest, most, check, expand) \
  ScriptForm{usage, help, fewest, most, check},
constexpr ScriptForm kScriptForms[] = {TACTILE_SCRIPT_COMMANDS(TACTILE_SCRIPT_FORM)};
#undef TACTILE_SCRIPT_FORM

// "'a', 'b' or 'c'": the usages of `command`'s forms, or only `form`'s when it has a keyword.
std::string expected_usages(std::string_view command, const ScriptForm* form) {
  std::vector<std::string_view> usages;
  for (const ScriptForm& other : kScriptForms)
    if (other.command() == command && (!form || form->keyword().empty() || &other == form))
      usages.push_back(other.usage);
  std::string text = "expected ";
  for (size_t k = 0; k < usages.size(); ++k)
    text += (k == 0 ? "'" : k + 1 < usages.size() ? ", '" : " or '") + std::string(usages[k]) + "'";
  return text;
}

// Every form with its help, one a line, the usages in a column.
std::string every_usage() {
  size_t width = 0;
  for (const ScriptForm& form : kScriptForms) width = std::max(width, form.usage.size());
  std::string text;
  for (const ScriptForm& form : kScriptForms)
    text += "\n  " + std::string(form.usage) + std::string(width + 2 - form.usage.size(), ' ') +
            std::string(form.help);
  return text;
}

// The form of `step`: its command's form whose keyword is the first argument, else the one
// without a keyword. Throws naming the line when the command is unknown, no form takes the
// arguments or they are too few or too many.
size_t form_of(const ScriptStep& step, const std::string& where) {
  const std::string place = place_of(step, where);
  bool known = false;
  const ScriptForm* chosen = nullptr;
  for (const ScriptForm& form : kScriptForms) {
    if (form.command() != step.command) continue;
    known = true;
    const std::string_view keyword = form.keyword();
    if (!keyword.empty() && !step.words.empty() && keyword == step.words[0])
      chosen = &form;
    else if (keyword.empty() && !chosen)
      chosen = &form;
  }
  if (!known)
    throw Error(place, "unknown command '" + step.command +
                           "'; the commands are (docs/SCRIPTING.md):" + every_usage());
  if (!chosen) throw Error(place, step.command + ": " + expected_usages(step.command, nullptr));
  if (step.words.size() < chosen->fewest || step.words.size() > chosen->most) {
    const std::string name =
        step.command + (chosen->keyword().empty() ? "" : " ") + std::string(chosen->keyword());
    throw Error(place,
                name + ": wrong number of arguments, " + expected_usages(step.command, chosen));
  }
  return static_cast<size_t>(chosen - kScriptForms);
}

}  // namespace

//---- Parsing

std::vector<ScriptStep> parse_script(const std::string& text, const std::string& where) {
  std::vector<ScriptStep> steps;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    ScriptStep step;
    step.line = number;
    std::istringstream words(line.substr(first));
    words >> step.command;
    const size_t after = line.find_first_not_of(" \t", first + step.command.size());
    step.rest = after == std::string::npos ? "" : line.substr(after);
    while (!step.rest.empty() && (step.rest.back() == ' ' || step.rest.back() == '\t'))
      step.rest.pop_back();
    for (std::string word; words >> word;) step.words.push_back(word);
    step.form = form_of(step, where);
    const ScriptCheck check = kScriptForms[step.form].check;
    if (check) check(step, where);
    steps.push_back(std::move(step));
  }
  return steps;
}

std::vector<ScriptStep> read_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot read the script");
  std::stringstream text;
  text << in.rdbuf();
  return parse_script(text.str(), path);
}

}  // namespace tactile
