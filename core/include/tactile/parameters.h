#pragma once
// Named parameters of a method (a segmenter, a feature set, a classifier), given on the
// command line as `key=value,...` and read with typed getters that name the bad key.

#include <map>
#include <string>
#include <vector>

namespace tactile {

class Parameters {
 public:
  Parameters() = default;
  // Parses "a=1,b=cosine"; `where` names the source in errors (e.g. "--params").
  static Parameters parse(const std::string& text, const std::string& where);

  void set(const std::string& key, const std::string& value) { values_[key] = value; }
  bool has(const std::string& key) const { return values_.count(key) != 0; }
  // Typed getters: the default when absent; tactile::Error naming `where` and the key
  // when the value does not parse or is not finite.
  double number(const std::string& key, double fallback) const;
  int64_t integer(const std::string& key, int64_t fallback) const;
  bool flag(const std::string& key, bool fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
  // Throws tactile::Error naming any key not in `known` (catches typos).
  void expect_only(const std::vector<std::string>& known) const;

  const std::map<std::string, std::string>& values() const { return values_; }
  // Every key a typed getter was asked for, with the value it answered: the given text, or
  // the fallback written so that it reads back the same (numbers round-trip exactly). A method
  // that reads all its parameters when built thus leaves its effective settings here, so a
  // saved model can record them and not only what the user typed. Because the getters write
  // this record, one Parameters object must not be read from two threads at once (none is:
  // every method reads its own copy when it is built).
  const std::map<std::string, std::string>& answered() const { return answered_; }
  // answered() as "key=value,..." in key order.
  std::string answered_text() const;
  std::string where() const { return where_; }
  void set_where(std::string where) { where_ = std::move(where); }

 private:
  std::string answer(const std::string& key, std::string value) const;

  std::map<std::string, std::string> values_;
  mutable std::map<std::string, std::string> answered_;
  std::string where_ = "parameters";
};

}  // namespace tactile
