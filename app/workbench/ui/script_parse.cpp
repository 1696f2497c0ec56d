#include "script_parse.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "tactile/error.h"

namespace tactile {

namespace {

const std::map<std::string, int>& named_keys() {
  static const std::map<std::string, int> keys = {
      {"tab", kKeyTab},         {"left", kKeyLeft},         {"right", kKeyRight},
      {"up", kKeyUp},           {"down", kKeyDown},         {"pageup", kKeyPageUp},
      {"pagedown", kKeyPageDown}, {"home", kKeyHome},       {"end", kKeyEnd},
      {"insert", kKeyInsert},   {"delete", kKeyDelete},     {"backspace", kKeyBackspace},
      {"space", kKeySpace},     {"enter", kKeyEnter},       {"return", kKeyEnter},
      {"escape", kKeyEscape},   {"esc", kKeyEscape}};
  return keys;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
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
    if (modifier == "ctrl" || modifier == "control") chord.ctrl = true;
    else if (modifier == "shift") chord.shift = true;
    else if (modifier == "alt") chord.alt = true;
    else if (modifier == "super" || modifier == "cmd") chord.super = true;
    else throw std::invalid_argument("unknown modifier '" + parts[k] + "' (Ctrl, Shift, Alt, Super)");
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
    throw Error(where + ":" + std::to_string(step.line), step.command + ": a number is missing");
  const std::string& word = step.words[index];
  try {
    size_t used = 0;
    const double value = std::stod(word, &used);
    if (used != word.size() || !std::isfinite(value)) throw std::invalid_argument(word);
    return value;
  } catch (const std::exception&) {
    throw Error(where + ":" + std::to_string(step.line),
                step.command + ": '" + word + "' is not a number");
  }
}


//---- Parsing

std::vector<ScriptStep> parse_script(const std::string& text, const std::string& where) {
  static const std::map<std::string, std::pair<size_t, size_t>> kArity = {
      {"open", {1, 99}},  {"time", {1, 1}},  {"key", {1, 99}},   {"type", {1, 99}},
      {"click", {2, 99}},  {"drag", {3, 5}},  {"menu", {1, 99}},  {"wait", {1, 1}},
      {"play", {1, 1}},   {"sleep", {1, 1}}, {"screenshot", {1, 99}}, {"state", {1, 99}}};
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
    const std::string place = where + ":" + std::to_string(number);
    const auto arity = kArity.find(step.command);
    if (arity == kArity.end())
      throw Error(place, "unknown command '" + step.command +
                             "' (open, time, key, type, click, drag, menu, wait, play, sleep, "
                             "screenshot, state)");
    if (step.words.size() < arity->second.first || step.words.size() > arity->second.second)
      throw Error(place, step.command + ": wrong number of arguments (docs/SCRIPTING.md)");
    // Check what can be checked before anything runs.
    if (step.command == "wait" && (step.words[0] == "training" || step.words[0] == "jobs")) {
      // Draws frames until the model panel's run, or the views' jobs, end.
    } else if (step.command == "time" || step.command == "wait" || step.command == "play" ||
               step.command == "sleep") {
      const double value = parse_number(step, 0, where);
      if (value < 0) throw Error(place, step.command + ": must not be negative");
      // `wait 0.5` would draw no frame at all: a script meaning seconds gets told so.
      if (step.command == "wait" && (value != std::floor(value) || value > 1e6))
        throw Error(place, "wait: " + step.words[0] +
                               " is not a whole number of frames (up to 1000000); for seconds "
                               "use 'sleep' (wall clock) or 'play' (recording time)");
    } else if (step.command == "key") {
      for (const std::string& word : step.words) {
        try {
          parse_chord(word);
        } catch (const std::invalid_argument& reason) {
          throw Error(place, "key " + word + ": " + reason.what());
        }
      }
    } else if (step.command == "click") {
      const std::string& what = step.words[0];
      if (what == "taxel") {
        const double id = parse_number(step, 1, where);
        if (id != std::floor(id)) throw Error(place, "click taxel: " + step.words[1] + " is not a taxel id");
      } else if (what == "time") {
        parse_number(step, 1, where);
      } else if (what == "recording" && step.words.size() == 2) {
      } else if (what == "item") {  // the rest of the line: names may hold spaces
      } else if (what == "cell" && step.words.size() == 3) {
      } else if (step.words.size() == 3) {
        parse_number(step, 1, where), parse_number(step, 2, where);
      } else {
        throw Error(place,
                    "click: expected 'taxel ID', 'time T [in VIEW]', 'recording NAME', 'item NAME', "
                    "'cell TRUE PREDICTED' or 'VIEW X Y'");
      }
    } else if (step.command == "drag") {
      if (step.words[0] != "time" && step.words[0] != "taxel")
        throw Error(place, "drag: expected 'time T0 T1 [in VIEW]' or 'taxel A B'");
      parse_number(step, 1, where), parse_number(step, 2, where);
    }
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
