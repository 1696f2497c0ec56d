// Words as a POSIX shell splits and quotes them, for the commands `tactile cluster` writes.
#include <string>
#include <vector>

#include "tactile/cluster/slurm.h"
#include "tactile/error.h"

namespace tactile::cluster {

std::vector<std::string> split_command(const std::string& text, const std::string& where) {
  // Characters an unquoted shell word would act on (operators, expansions, globs, comments).
  static const std::string active = ";|&<>()$`*?[]{}~#";  // ~ and # only where a word starts
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else if (c == '\'') {
      const size_t close = text.find('\'', at + 1);
      if (close == std::string::npos)
        throw Error(where, "unbalanced single quote at character " + std::to_string(at + 1));
      word += text.substr(at + 1, close - at - 1);
      at = close;
      in_word = true;
    } else if (c == '"') {
      size_t close = at + 1;
      for (; close < text.size() && text[close] != '"'; ++close) {
        const char inner = text[close];
        if (inner == '\\' && close + 1 < text.size() &&
            std::string("\"\\$`\n").find(text[close + 1]) != std::string::npos) {
          ++close;
          if (text[close] != '\n') word += text[close];  // backslash-newline joins lines
        } else if (inner == '$' || inner == '`') {
          throw Error(where, std::string("`") + inner + "` inside double quotes at character " +
                                 std::to_string(close + 1) +
                                 ": a shell would expand it; give the value itself");
        } else {
          word += inner;
        }
      }
      if (close >= text.size())
        throw Error(where, "unbalanced double quote at character " + std::to_string(at + 1));
      at = close;
      in_word = true;
    } else if (c == '\\') {
      if (at + 1 >= text.size())
        throw Error(where, "a backslash at the end with nothing to escape");
      ++at;
      if (text[at] != '\n') word += text[at];
      in_word = in_word || text[at] != '\n';
    } else if (active.find(c) != std::string::npos && !((c == '#' || c == '~') && in_word)) {
      throw Error(where, std::string("unquoted `") + c + "` at character " +
                             std::to_string(at + 1) +
                             ": a shell would act on it; quote it or give a plain command");
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

std::string shell_quoted(const std::string& word) {
  static const std::string plain =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=/.,:@%";
  if (!word.empty() && word.find_first_not_of(plain) == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_line(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    line += shell_quoted(word);
  }
  return line;
}

}  // namespace tactile::cluster
