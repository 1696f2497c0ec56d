// Evaluation protocols: parsing "kfold:5x10"-style specifications and turning them into
// train/test folds over a dataset (spec §6.6).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "tactile/error.h"
#include "tactile/ml/evaluation.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

const char* const kProtocolWhere = "--protocol";

int64_t parse_whole(const std::string& text, const std::string& protocol, const char* what) {
  int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    throw Error(kProtocolWhere, protocol + ": " + what + " '" + text + "' is not a whole number");
  return value;
}

double parse_fraction(const std::string& text, const std::string& protocol) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !(value > 0.0 && value < 1.0))
    throw Error(kProtocolWhere,
                protocol + ": the test fraction '" + text + "' is not between 0 and 1");
  return value;
}

// "AxB" -> {A, B}; "A" -> {A, "1"} (one repetition); "Ax" -> {A, ""}, which fails to parse.
std::pair<std::string, std::string> split_times(const std::string& text) {
  const size_t times = text.find('x');
  if (times == std::string::npos) return {text, "1"};
  return {text.substr(0, times), text.substr(times + 1)};
}

// Class index per row, classes numbered in first-seen order (Dataset::class_names).
std::vector<int> class_indices(const Dataset& dataset, int& class_count) {
  const std::vector<std::string> names = dataset.class_names();
  std::map<std::string, int> index;
  for (size_t i = 0; i < names.size(); ++i) index[names[i]] = static_cast<int>(i);
  std::vector<int> classes;
  classes.reserve(dataset.classes.size());
  for (const std::string& name : dataset.classes) classes.push_back(index.at(name));
  class_count = static_cast<int>(names.size());
  return classes;
}

std::vector<std::vector<int64_t>> rows_per_class(const Dataset& dataset) {
  int class_count = 0;
  const std::vector<int> classes = class_indices(dataset, class_count);
  std::vector<std::vector<int64_t>> rows(static_cast<size_t>(class_count));
  for (size_t row = 0; row < classes.size(); ++row)
    rows[static_cast<size_t>(classes[row])].push_back(static_cast<int64_t>(row));
  return rows;
}

// Train = every row not in test; both ascending.
Fold fold_of_test(std::vector<int64_t> test, int64_t row_count) {
  std::sort(test.begin(), test.end());
  Fold fold;
  fold.train.reserve(static_cast<size_t>(row_count) - test.size());
  size_t next = 0;
  for (int64_t row = 0; row < row_count; ++row) {
    if (next < test.size() && test[next] == row) {
      ++next;
      continue;
    }
    fold.train.push_back(row);
  }
  fold.test = std::move(test);
  return fold;
}

std::string value_of(const Dataset& dataset, size_t row, const std::string& key, bool& present) {
  present = true;
  if (key == "class") return dataset.classes[row];
  if (key == "subject" && row < dataset.subjects.size()) return dataset.subjects[row];
  if (key == "recording" && row < dataset.recordings.size()) return dataset.recordings[row];
  if (key == "segment_id" && row < dataset.segment_ids.size())
    return std::to_string(dataset.segment_ids[row]);
  if (row < dataset.metadata.size()) {
    const auto found = dataset.metadata[row].find(key);
    if (found != dataset.metadata[row].end()) return found->second;
  }
  present = false;
  return {};
}

}  // namespace

//---- Protocol -------------------------------------------------------------------------------

Protocol Protocol::parse(const std::string& text) {
  Protocol protocol;
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string argument = colon == std::string::npos ? "" : text.substr(colon + 1);
  const bool has_argument = colon != std::string::npos;
  if (kind == "loo" || kind == "loso") {
    if (has_argument) throw Error(kProtocolWhere, "'" + text + "': " + kind + " takes no argument");
    protocol.kind = kind == "loo" ? Kind::kLeaveOneOut : Kind::kLeaveOneSubjectOut;
    protocol.folds = 0;
    return protocol;
  }
  if (kind == "group") {
    if (argument.empty())
      throw Error(kProtocolWhere,
                  "'" + text + "': expected group:COLUMN, e.g. group:recording or group:session");
    protocol.kind = Kind::kLeaveOneGroupOut;
    protocol.group_column = argument;
    protocol.folds = 0;
    return protocol;
  }
  if (kind == "kfold") {
    if (!has_argument) throw Error(kProtocolWhere, "'" + text + "': expected kfold:K or kfold:KxR");
    const auto [folds, repetitions] = split_times(argument);
    if (folds.empty() || repetitions.empty())
      throw Error(kProtocolWhere,
                  "'" + text + "': expected kfold:K or kfold:KxR, e.g. kfold:10 or kfold:5x10");
    protocol.kind = Kind::kKFold;
    const int64_t k = parse_whole(folds, text, "the fold count");
    const int64_t r = parse_whole(repetitions, text, "the repetition count");
    if (k < 2 || k > 1'000'000)
      throw Error(kProtocolWhere, text + ": k-fold needs at least 2 folds");
    if (r < 1 || r > 10'000) throw Error(kProtocolWhere, text + ": repetitions must be 1..10000");
    protocol.folds = static_cast<int>(k);
    protocol.repetitions = static_cast<int>(r);
    return protocol;
  }
  if (kind == "holdout") {
    if (!has_argument)
      throw Error(kProtocolWhere, "'" + text + "': expected holdout:FxR, e.g. holdout:0.15x10");
    const auto [fraction, repetitions] = split_times(argument);
    protocol.kind = Kind::kHoldout;
    protocol.test_fraction = parse_fraction(fraction, text);
    const int64_t r = parse_whole(repetitions, text, "the repetition count");
    if (r < 1 || r > 10'000) throw Error(kProtocolWhere, text + ": repetitions must be 1..10000");
    protocol.repetitions = static_cast<int>(r);
    protocol.folds = 0;
    return protocol;
  }
  if (kind == "split") {
    const size_t slash = argument.find('/');
    if (!has_argument || slash == std::string::npos ||
        argument.find('/', slash + 1) != std::string::npos)
      throw Error(kProtocolWhere, "'" + text +
                                      "': expected split:TRAIN/TEST with one '/', e.g. "
                                      "split:side=back,condition=stationary/side=front");
    protocol.kind = Kind::kSplit;
    protocol.train_query = argument.substr(0, slash);
    protocol.test_query = argument.substr(slash + 1);
    if (protocol.train_query.empty() || protocol.test_query.empty())
      throw Error(kProtocolWhere,
                  "'" + text + "': the train and the test query must both be given");
    protocol.folds = 1;
    return protocol;
  }
  throw Error(
      kProtocolWhere,
      "unknown protocol '" + text +
          "' (known: kfold:K[xR], loo, loso, group:COLUMN, holdout:FxR, split:QUERY/QUERY)");
}

std::string Protocol::to_string() const {
  switch (kind) {
    case Kind::kLeaveOneOut:
      return "loo";
    case Kind::kLeaveOneSubjectOut:
      return "loso";
    case Kind::kLeaveOneGroupOut:
      return "group:" + group_column;
    case Kind::kHoldout: {
      char fraction[32];
      const auto end = std::to_chars(fraction, fraction + sizeof fraction, test_fraction).ptr;
      return "holdout:" + std::string(fraction, end) + "x" + std::to_string(repetitions);
    }
    case Kind::kSplit:
      return "split:" + train_query + "/" + test_query;
    case Kind::kKFold:
      break;
  }
  std::string text = "kfold:" + std::to_string(folds);
  if (repetitions > 1) text.append("x").append(std::to_string(repetitions));
  return text;
}

//---- Queries --------------------------------------------------------------------------------

std::vector<int64_t> rows_matching(const Dataset& dataset, const std::string& query,
                                   const std::string& where) {
  const Parameters conditions = Parameters::parse(query, where + " query '" + query + "'");
  if (conditions.values().empty()) throw Error(where, "empty query '" + query + "'");
  const auto rows = static_cast<size_t>(dataset.rows());
  for (const auto& [key, value] : conditions.values()) {
    bool any = false;
    for (size_t row = 0; row < rows && !any; ++row) value_of(dataset, row, key, any);
    if (any) continue;
    std::set<std::string> keys = {"class"};
    if (!dataset.subjects.empty()) keys.insert("subject");
    if (!dataset.recordings.empty()) keys.insert("recording");
    if (!dataset.segment_ids.empty()) keys.insert("segment_id");
    for (const Metadata& metadata : dataset.metadata)
      for (const auto& [name, ignored] : metadata) keys.insert(name);
    std::string known;
    for (const std::string& name : keys) known += (known.empty() ? "" : ", ") + name;
    throw Error(where, "query '" + query + "': no row has '" + key + "' (keys: " + known + ")");
  }
  std::vector<int64_t> matching;
  for (size_t row = 0; row < rows; ++row) {
    bool all = true;
    for (const auto& [key, value] : conditions.values()) {
      bool present = false;
      all = all && value_of(dataset, row, key, present) == value && present;
    }
    if (all) matching.push_back(static_cast<int64_t>(row));
  }
  if (matching.empty()) throw Error(where, "query '" + query + "' matches no row");
  return matching;
}

//---- Folds ----------------------------------------------------------------------------------

std::vector<std::string> protocol_groups(const Dataset& dataset, const Protocol& protocol) {
  const int64_t row_count = dataset.rows();
  std::vector<std::string> values;
  if (protocol.kind == Protocol::Kind::kLeaveOneSubjectOut) {
    if (static_cast<int64_t>(dataset.subjects.size()) != row_count)
      throw Error(kProtocolWhere, "loso needs a subject for every row; the dataset has none");
    for (int64_t row = 0; row < row_count; ++row) {
      const std::string& subject = dataset.subjects[static_cast<size_t>(row)];
      if (subject.empty())
        throw Error(kProtocolWhere,
                    "loso needs a subject for every row; row " + std::to_string(row) +
                        " (segment " +
                        std::to_string(row < static_cast<int64_t>(dataset.segment_ids.size())
                                           ? dataset.segment_ids[static_cast<size_t>(row)]
                                           : row) +
                        ") has none");
      values.push_back(subject);
    }
  } else if (protocol.kind == Protocol::Kind::kLeaveOneGroupOut) {
    // The column's value per row: the table's own columns first, then the metadata.
    const std::string& column = protocol.group_column;
    for (int64_t row = 0; row < row_count; ++row) {
      const auto r = static_cast<size_t>(row);
      std::string value;
      if (column == "subject" && r < dataset.subjects.size()) {
        value = dataset.subjects[r];
      } else if (column == "recording" && r < dataset.recordings.size()) {
        value = dataset.recordings[r];
      } else if (column == "class") {
        value = dataset.classes[r];
      } else if (r < dataset.metadata.size()) {
        const auto found = dataset.metadata[r].find(column);
        if (found != dataset.metadata[r].end()) value = found->second;
      }
      if (value.empty())
        throw Error(kProtocolWhere, protocol.to_string() + ": row " + std::to_string(row) +
                                        " has no value in column '" + column + "'");
      values.push_back(std::move(value));
    }
  }
  return values;
}

std::vector<Fold> make_folds(const Dataset& dataset, const Protocol& protocol, uint64_t seed) {
  const int64_t row_count = dataset.rows();
  if (row_count == 0) throw Error(kProtocolWhere, "the dataset has no rows");
  if (static_cast<int64_t>(dataset.classes.size()) != row_count)
    throw Error(kProtocolWhere, "the dataset has " + std::to_string(dataset.classes.size()) +
                                    " classes for " + std::to_string(row_count) + " rows");
  const std::string name = protocol.to_string();
  std::mt19937_64 random(seed);
  std::vector<Fold> folds;
  switch (protocol.kind) {
    case Protocol::Kind::kKFold: {
      if (protocol.folds < 2 || protocol.repetitions < 1)
        throw Error(kProtocolWhere, name + ": needs at least 2 folds and 1 repetition");
      if (protocol.folds > row_count)
        throw Error(kProtocolWhere, name + ": " + std::to_string(protocol.folds) +
                                        " folds but only " + std::to_string(row_count) + " rows");
      const auto per_class = rows_per_class(dataset);
      for (int repetition = 0; repetition < protocol.repetitions; ++repetition) {
        std::vector<std::vector<int64_t>> tests(static_cast<size_t>(protocol.folds));
        for (std::vector<int64_t> members : per_class) {
          shuffle(members, random);
          for (size_t i = 0; i < members.size(); ++i) tests[i % tests.size()].push_back(members[i]);
        }
        for (auto& test : tests) folds.push_back(fold_of_test(std::move(test), row_count));
      }
      break;
    }
    case Protocol::Kind::kLeaveOneOut:
      if (row_count < 2) throw Error(kProtocolWhere, "loo needs at least 2 rows");
      for (int64_t row = 0; row < row_count; ++row) folds.push_back(fold_of_test({row}, row_count));
      break;
    case Protocol::Kind::kLeaveOneSubjectOut:
    case Protocol::Kind::kLeaveOneGroupOut: {
      const std::vector<std::string> values = protocol_groups(dataset, protocol);
      std::vector<std::string> order;
      std::map<std::string, std::vector<int64_t>> rows_of;
      for (int64_t row = 0; row < row_count; ++row) {
        auto& rows = rows_of[values[static_cast<size_t>(row)]];
        if (rows.empty()) order.push_back(values[static_cast<size_t>(row)]);
        rows.push_back(row);
      }
      if (order.size() < 2)
        throw Error(kProtocolWhere,
                    protocol.kind == Protocol::Kind::kLeaveOneSubjectOut
                        ? "loso needs at least 2 subjects; the dataset has only '" + order[0] + "'"
                        : name + " needs at least 2 groups; column '" + protocol.group_column +
                              "' has only '" + order[0] + "'");
      for (const std::string& group : order)
        folds.push_back(fold_of_test(rows_of[group], row_count));
      break;
    }
    case Protocol::Kind::kHoldout: {
      if (!(protocol.test_fraction > 0.0 && protocol.test_fraction < 1.0) ||
          protocol.repetitions < 1)
        throw Error(kProtocolWhere, name + ": the test fraction must lie between 0 and 1");
      const auto per_class = rows_per_class(dataset);
      for (int repetition = 0; repetition < protocol.repetitions; ++repetition) {
        std::vector<int64_t> test;
        for (std::vector<int64_t> members : per_class) {
          shuffle(members, random);
          const auto size = static_cast<int64_t>(members.size());
          const int64_t count =
              size < 2
                  ? 0
                  : std::min<int64_t>(
                        std::llround(protocol.test_fraction * static_cast<double>(size)), size - 1);
          test.insert(test.end(), members.begin(), members.begin() + count);
        }
        if (test.empty())
          throw Error(kProtocolWhere,
                      name + ": leaves no test row (classes too small for this fraction)");
        folds.push_back(fold_of_test(std::move(test), row_count));
      }
      break;
    }
    case Protocol::Kind::kSplit: {
      const std::vector<int64_t> train =
          rows_matching(dataset, protocol.train_query, kProtocolWhere);
      const std::vector<int64_t> test = rows_matching(dataset, protocol.test_query, kProtocolWhere);
      std::vector<int64_t> both;
      std::set_intersection(train.begin(), train.end(), test.begin(), test.end(),
                            std::back_inserter(both));
      if (!both.empty())
        throw Error(kProtocolWhere, name + ": row " + std::to_string(both.front()) + " and " +
                                        std::to_string(both.size() - 1) +
                                        " more match both the train and the test query");
      folds.push_back({train, test});
      break;
    }
  }
  return folds;
}

}  // namespace tactile::ml
