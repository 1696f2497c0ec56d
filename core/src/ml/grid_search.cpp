#include "tactile/ml/grid_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>
#include <set>

#include "tactile/error.h"
#include "tactile/features/stack.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

const char* const kGridSearchWhere = "classifier grid-search";
constexpr size_t kMostCandidates = 10'000;

std::vector<std::string> alternatives(const std::string& key, const std::string& values) {
  std::vector<std::string> result;
  size_t start = 0;
  while (true) {
    const size_t bar = values.find('|', start);
    const std::string value = values.substr(start, bar == std::string::npos ? bar : bar - start);
    if (value.empty()) throw Error(kGridSearchWhere, key + "=" + values + ": an empty alternative");
    result.push_back(value);
    if (bar == std::string::npos) return result;
    start = bar + 1;
  }
}

// The base of "select:...,base=S" with S's ',' back in place ("" when there is none).
std::string base_of_select(const std::string& specification) {
  const size_t at = specification.find("base=");
  if (at == std::string::npos) return "";
  std::string base = specification.substr(at + 5);
  base = base.substr(0, base.find(','));
  std::replace(base.begin(), base.end(), ';', ',');
  return base;
}

// The training rows (all when `rows` is empty) as a table the evaluation takes; with
// `groups` (one per row of x), each row's group as its subject.
Dataset inner_dataset(const Matrix& x, const std::vector<int>& y, const std::vector<int64_t>& rows,
                      const std::vector<std::string>& groups = {}) {
  Dataset inner;
  if (rows.empty()) {
    inner.features = x;
    for (int label : y) inner.classes.push_back(std::to_string(label));
    inner.subjects = groups;
    return inner;
  }
  inner.features.resize(static_cast<Eigen::Index>(rows.size()), x.cols());
  for (size_t i = 0; i < rows.size(); ++i) {
    inner.features.row(static_cast<Eigen::Index>(i)) = x.row(rows[i]);
    inner.classes.push_back(std::to_string(y[static_cast<size_t>(rows[i])]));
    if (!groups.empty()) inner.subjects.push_back(groups[static_cast<size_t>(rows[i])]);
  }
  return inner;
}

size_t distinct_count(std::vector<std::string> values) {
  std::sort(values.begin(), values.end());
  return static_cast<size_t>(std::unique(values.begin(), values.end()) - values.begin());
}

// The fewest groups for which auto keeps its inner folds to whole groups.
constexpr size_t kFewestInnerGroups = 3;

// An early rung's one split of grouped rows: about 30 % of the groups (at least one, drawn
// by `seed`) tested, the others trained on, as `split:auto_part=train/auto_part=test`.
// The distinct groups of the inner rows (their subjects), in an order shuffled by `seed`.
std::vector<std::string> shuffled_groups(const Dataset& inner, uint64_t seed) {
  std::vector<std::string> names = inner.subjects;
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::mt19937_64 engine(seed);
  shuffle(names, engine);
  return names;
}

// Each inner row's metadata replaced by one key: its group's value in `value_of`.
void mark_groups(Dataset& inner, const std::string& key,
                 const std::map<std::string, std::string>& value_of) {
  inner.metadata.clear();
  for (const std::string& subject : inner.subjects)
    inner.metadata.push_back({{key, value_of.at(subject)}});
}

Protocol grouped_holdout(Dataset& inner, uint64_t seed) {
  const std::vector<std::string> names = shuffled_groups(inner, seed);
  const size_t tested = std::max<size_t>(
      1, static_cast<size_t>(std::llround(0.3 * static_cast<double>(names.size()))));
  std::map<std::string, std::string> part_of;
  for (size_t k = 0; k < names.size(); ++k) part_of[names[k]] = k < tested ? "test" : "train";
  mark_groups(inner, "auto_part", part_of);
  return Protocol::parse("split:auto_part=train/auto_part=test");
}

// The last rung's folds of grouped rows: the groups shuffled by `seed` and dealt into
// min(kInnerGroupFolds, groups) folds of whole groups, as `group:auto_fold`. Leaving one group
// out at a time made the search grow with the square of the groups (the outer protocol's
// folds times the inner ones: 37 recordings, 22 minutes for 330 rows).
constexpr size_t kInnerGroupFolds = 5;

Protocol grouped_folds(Dataset& inner, uint64_t seed) {
  const std::vector<std::string> names = shuffled_groups(inner, seed);
  const size_t folds = std::min(kInnerGroupFolds, names.size());
  std::map<std::string, std::string> fold_of;
  for (size_t k = 0; k < names.size(); ++k) fold_of[names[k]] = std::to_string(k % folds + 1);
  mark_groups(inner, "auto_fold", fold_of);
  return Protocol::parse("group:auto_fold");
}

}  // namespace

std::vector<AutoBlock> parse_auto_blocks(const std::string& text) {
  std::vector<AutoBlock> blocks;
  size_t start = 0;
  while (start < text.size()) {
    const size_t bar = std::min(text.find('|', start), text.size());
    const std::string item = text.substr(start, bar - start);
    const size_t colon = item.rfind(':');
    const size_t dash = item.find('-', colon == std::string::npos ? 0 : colon);
    AutoBlock block;
    bool good = colon != std::string::npos && colon > 0 && dash != std::string::npos;
    if (good) {
      block.name = item.substr(0, colon);
      const std::string first = item.substr(colon + 1, dash - colon - 1),
                        last = item.substr(dash + 1);
      good = !first.empty() && !last.empty() &&
             first.find_first_not_of("0123456789") == std::string::npos &&
             last.find_first_not_of("0123456789") == std::string::npos && first.size() < 10 &&
             last.size() < 10;
      if (good) {
        block.first = std::stoi(first);
        block.last = std::stoi(last);
        good = block.first <= block.last;
      }
    }
    if (!good)
      throw Error("classifier auto",
                  "blocks=" + text + ": '" + item + "' is not NAME:A-B (0-based columns, A <= B)");
    blocks.push_back(block);
    start = bar + 1;
  }
  return blocks;
}

std::vector<int64_t> rung_sizes(int64_t rows, int class_count, size_t candidates) {
  // One rung per halving until at most kHalvingFactor candidates are left for the last; each
  // earlier rung a third of the next's rows, but never fewer than kSmallestRung rows or 5 a
  // class (a small table repeats its size: the early rungs are then told apart by their
  // single hold-out splits alone).
  const int64_t smallest = std::max<int64_t>(kSmallestRung, 5 * static_cast<int64_t>(class_count));
  std::vector<int64_t> sizes = {rows};
  size_t left = candidates;
  while (left > kHalvingFactor) {
    sizes.insert(
        sizes.begin(),
        std::min(rows, std::max(smallest, sizes.front() / static_cast<int64_t>(kHalvingFactor))));
    left = (left + kHalvingFactor - 1) / kHalvingFactor;
  }
  return sizes;
}

GridSearchClassifier::GridSearchClassifier(std::string base,
                                           std::vector<std::pair<std::string, std::string>> axes,
                                           Protocol inner)
    : base_(std::move(base)), axes_(std::move(axes)), inner_(std::move(inner)) {
  if (base_.empty()) throw Error(kGridSearchWhere, "base= is required, e.g. grid:base=knn,k=1|3|5");
  if (base_ == "grid-search" || base_ == "grid")
    throw Error(kGridSearchWhere, "base=" + base_ + ": a grid search cannot search a grid search");
  if (inner_.kind == Protocol::Kind::kLeaveOneSubjectOut ||
      inner_.kind == Protocol::Kind::kLeaveOneGroupOut || inner_.kind == Protocol::Kind::kSplit)
    throw Error(kGridSearchWhere, "inner=" + inner_.to_string() +
                                      ": the inner protocol must be kfold, loo or holdout");
  // The cartesian product, the last key varying fastest.
  std::vector<std::string> specifications = {""};
  for (const auto& [key, values] : axes_) {
    std::vector<std::string> extended;
    for (const std::string& prefix : specifications)
      for (const std::string& value : alternatives(key, values))
        extended.push_back(prefix + (prefix.empty() ? "" : ",") + key + "=" + value);
    if (extended.size() > kMostCandidates)
      throw Error(kGridSearchWhere,
                  "more than " + std::to_string(kMostCandidates) + " combinations");
    specifications = std::move(extended);
  }
  for (const std::string& parameters : specifications) {
    const std::string specification = base_ + (parameters.empty() ? "" : ":" + parameters);
    make_classifier(specification);  // an unknown base or parameter fails here, before any fit
    candidates_.push_back({specification, 0.0, 0});
  }
  listed_count_ = candidates_.size();
}

GridSearchClassifier::GridSearchClassifier(std::vector<std::string> specifications, Protocol inner,
                                           std::string listed, std::string blocks)
    : auto_(true),
      blocks_(std::move(blocks)),
      listed_(std::move(listed)),
      inner_(std::move(inner)) {
  if (inner_.kind == Protocol::Kind::kLeaveOneSubjectOut ||
      inner_.kind == Protocol::Kind::kLeaveOneGroupOut || inner_.kind == Protocol::Kind::kSplit)
    throw Error("classifier auto", "inner=" + inner_.to_string() +
                                       ": the inner protocol must be kfold, loo or holdout");
  if (specifications.empty()) throw Error("classifier auto", "no candidates");
  for (const std::string& specification : specifications) {
    const std::string name = specification.substr(0, specification.find(':'));
    if (name == "auto" || name == "grid" || name == "grid-search")
      throw Error("classifier auto",
                  "candidate '" + specification + "': searches are not candidates");
    make_classifier(specification);  // an unknown classifier or parameter fails here
  }
  // Without blocks every candidate sees every column; with blocks, each candidate once per
  // block, on that block's columns.
  std::vector<AutoBlock> parsed = parse_auto_blocks(blocks_);
  if (parsed.empty()) parsed.push_back({"", -1, -1});
  for (const AutoBlock& block : parsed)
    for (const std::string& specification : specifications) {
      if (block.first < 0) {
        candidates_.push_back({specification, 0.0, 0});
      } else {
        std::string base = specification;
        std::replace(base.begin(), base.end(), ',', ';');
        candidates_.push_back({"select:columns=" + std::to_string(block.first) + "-" +
                                   std::to_string(block.last) + ",base=" + base,
                               0.0, 0});
      }
      candidate_blocks_.push_back(block);
    }
  listed_count_ = candidates_.size();
}

Parameters GridSearchClassifier::parameters() const {
  Parameters parameters;
  if (auto_) {
    parameters.set("inner", inner_.to_string());
    if (!listed_.empty()) parameters.set("candidates", listed_);
    if (!blocks_.empty()) parameters.set("blocks", blocks_);
    return parameters;
  }
  parameters.set("base", base_);
  parameters.set("inner", inner_.to_string());
  for (const auto& [key, values] : axes_) parameters.set(key, values);
  return parameters;
}

double GridSearchClassifier::inner_accuracy(const Dataset& inner, const std::string& specification,
                                            uint64_t inner_seed) const {
  EvaluationControl control;  // every core, unless this fit runs in a fold of a parallel evaluation
  return evaluate(inner, specification, inner_, inner_seed, control).accuracy;
}

void GridSearchClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                               uint64_t seed) {
  check_training_set(x, y, class_count, kGridSearchWhere);
  // Every candidate sees the same inner folds, so they are compared on equal terms.
  const uint64_t inner_seed = derive_seed(seed, 0);
  size_t best = 0;
  if (auto_) {
    best = halve_candidates(x, y, class_count, seed);
  } else {
    const Dataset inner = inner_dataset(x, y, {});
    for (size_t i = 0; i < candidates_.size(); ++i) {
      if (cancel_requested()) throw Error(kGridSearchWhere, "cancelled");
      try {
        candidates_[i].inner_accuracy =
            inner_accuracy(inner, candidates_[i].specification, inner_seed);
      } catch (const Error& error) {
        throw Error(kGridSearchWhere, "inner " + inner_.to_string() + " on " +
                                          std::to_string(x.rows()) +
                                          " training rows: " + error.what());
      }
      candidates_[i].rows = x.rows();
      if (candidates_[i].inner_accuracy > candidates_[best].inner_accuracy) best = i;
    }
  }
  std::unique_ptr<Classifier> chosen = make_classifier(candidates_[best].specification);
  chosen->fit(x, y, class_count, seed);
  chosen_ = std::move(chosen);
}

size_t GridSearchClassifier::halve_candidates(const Matrix& x, const std::vector<int>& y,
                                              int class_count, uint64_t seed) {
  // Columns that outnumber the rows, or more than a candidate takes whole (its catalog
  // widest): the candidate also runs on the k columns that best separate the classes of the
  // training rows (chosen inside every inner fold); on more than its widest, only so.
  candidates_.resize(listed_count_);
  std::vector<bool> too_wide(listed_count_, false);
  for (size_t i = 0; i < listed_count_; ++i) {
    const AutoBlock& block = candidate_blocks_[i];
    const int64_t width = block.first < 0 ? x.cols() : block.last - block.first + 1;
    if (block.last >= x.cols())
      throw Error("classifier auto", "blocks=" + blocks_ + ": block " + block.name +
                                         " ends at column " + std::to_string(block.last) +
                                         ", the table has " + std::to_string(x.cols()));
    std::string base = block.first < 0 ? candidates_[i].specification
                                       : base_of_select(candidates_[i].specification);
    const int64_t widest = widest_columns(base);
    too_wide[i] = widest > 0 && width > widest;
    if (width <= x.rows() && !too_wide[i]) continue;
    int64_t k = std::clamp<int64_t>(x.rows() / 4, 10, width);
    if (widest > 0) k = std::min(k, widest);
    std::replace(base.begin(), base.end(), ',', ';');
    const std::string columns = block.first < 0 ? ""
                                                : "columns=" + std::to_string(block.first) + "-" +
                                                      std::to_string(block.last) + ",";
    candidates_.push_back(
        {"select:" + columns + "k=" + std::to_string(k) + ",base=" + base, 0.0, 0});
  }
  // The groups of the rows, when the outer evaluation holds groups out.
  const std::vector<std::string>& groups = fit_groups();
  const bool grouped = static_cast<int64_t>(groups.size()) == x.rows() &&
                       distinct_count(groups) >= kFewestInnerGroups;
  // The candidates that run: all but those too wide to run whole.
  std::vector<size_t> alive;
  for (size_t i = 0; i < candidates_.size(); ++i)
    if (i >= listed_count_ || !too_wide[i])
      alive.push_back(i);
    else
      candidates_[i].inner_accuracy = -1.0;
  const std::vector<int64_t> sizes = rung_sizes(x.rows(), class_count, alive.size());
  // Rows of every rung: per class, one shuffled order, each rung taking a longer prefix of
  // it, so a rung's rows hold the smaller rungs' rows and the classes keep their shares.
  std::vector<std::vector<int64_t>> by_class(static_cast<size_t>(class_count));
  for (int64_t r = 0; r < x.rows(); ++r)
    by_class[static_cast<size_t>(y[static_cast<size_t>(r)])].push_back(r);
  std::mt19937_64 engine(derive_seed(seed, 1));
  for (std::vector<int64_t>& rows : by_class) shuffle(rows, engine);
  const uint64_t inner_seed = derive_seed(seed, 0);
  for (size_t rung = 0; rung < sizes.size(); ++rung) {
    std::vector<int64_t> rows;
    for (const std::vector<int64_t>& members : by_class) {
      const auto share = static_cast<size_t>(
          std::llround(static_cast<double>(members.size()) * static_cast<double>(sizes[rung]) /
                       static_cast<double>(x.rows())));
      const size_t take =
          std::min(members.size(), std::max<size_t>(share, std::min<size_t>(members.size(), 2)));
      rows.insert(rows.end(), members.begin(), members.begin() + static_cast<std::ptrdiff_t>(take));
    }
    std::sort(rows.begin(), rows.end());
    Dataset inner = inner_dataset(x, y, rows, grouped ? groups : std::vector<std::string>{});
    // The early rungs sort out the weak candidates on one stratified hold-out split each (a
    // new split per rung); the last compares the few left by the inner protocol. When the
    // outer evaluation holds groups out (subjects, recordings), so do these: a hold-out of
    // whole groups, and at the last rung five folds of whole groups (one group a fold when
    // there are no more than five).
    const bool last = rung + 1 == sizes.size();
    const bool rung_grouped = grouped && distinct_count(inner.subjects) >= kFewestInnerGroups;
    const uint64_t rung_seed = last ? inner_seed : derive_seed(seed, 2 + rung);
    const Protocol protocol = last ? (rung_grouped ? grouped_folds(inner, rung_seed) : inner_)
                              : rung_grouped ? grouped_holdout(inner, rung_seed)
                                             : Protocol::parse("holdout:0.3x1");
    for (size_t i : alive) {
      if (cancel_requested()) throw Error("classifier auto", "cancelled");
      try {
        candidates_[i].inner_accuracy =
            evaluate(inner, candidates_[i].specification, protocol, rung_seed).accuracy;
      } catch (const Error&) {
        // A candidate that cannot learn from these rows (too few per class, ...) is passed over.
        candidates_[i].inner_accuracy = -1.0;
      }
      candidates_[i].rows = static_cast<int64_t>(rows.size());
    }
    // The best first; equal ones in listed order.
    std::stable_sort(alive.begin(), alive.end(), [&](size_t a, size_t b) {
      return candidates_[a].inner_accuracy > candidates_[b].inner_accuracy;
    });
    if (rung + 1 < sizes.size()) alive.resize((alive.size() + kHalvingFactor - 1) / kHalvingFactor);
  }
  if (candidates_[alive.front()].inner_accuracy < 0.0)
    throw Error("classifier auto",
                "no candidate could learn from " + std::to_string(x.rows()) + " training rows");
  return alive.front();
}

const Classifier& GridSearchClassifier::chosen() const {
  if (!chosen_) throw Error(kGridSearchWhere, "not fitted");
  return *chosen_;
}

std::string GridSearchClassifier::chosen_specification() const {
  const std::string specification = specification_of(chosen());
  for (const AutoBlock& block : parse_auto_blocks(blocks_))
    if (specification.find("columns=" + std::to_string(block.first) + "-" +
                           std::to_string(block.last)) != std::string::npos)
      return block.name + "/" + specification;
  return specification;
}

Matrix GridSearchClassifier::scores(const Matrix& x) const { return chosen().scores(x); }

std::vector<int> GridSearchClassifier::predict(const Matrix& x) const {
  return chosen().predict(x);
}

nlohmann::json GridSearchClassifier::save() const {
  nlohmann::json candidates = nlohmann::json::array();
  for (const GridCandidate& candidate : candidates_)
    candidates.push_back({{"specification", candidate.specification},
                          {"inner_accuracy", candidate.inner_accuracy},
                          {"rows", candidate.rows}});
  return {{"candidates", candidates}, {"chosen", save_classifier(chosen())}};
}

void GridSearchClassifier::load(const nlohmann::json& model) {
  const nlohmann::json& candidates = model.at("candidates");
  // auto adds the column-selecting variants at fit time, after the listed candidates.
  if (!candidates.is_array() || candidates.size() < listed_count_ ||
      (!auto_ && candidates.size() != listed_count_))
    throw Error("model " + name(), "the candidates differ from the search's parameters");
  std::vector<GridCandidate> loaded;
  for (size_t i = 0; i < candidates.size(); ++i) {
    GridCandidate candidate{candidates[i].at("specification").get<std::string>(),
                            candidates[i].at("inner_accuracy").get<double>(),
                            candidates[i].value("rows", int64_t{0})};
    if (i < listed_count_ && candidate.specification != candidates_[i].specification)
      throw Error("model " + name(), "the candidates differ from the search's parameters");
    loaded.push_back(std::move(candidate));
  }
  candidates_ = std::move(loaded);
  chosen_ = load_classifier(model.at("chosen"));
}

std::unique_ptr<Classifier> make_grid_search_classifier(const Parameters& parameters) {
  std::vector<std::pair<std::string, std::string>> axes;
  for (const auto& [key, value] : parameters.values())
    if (key != "base" && key != "inner") axes.emplace_back(key, value);
  Protocol inner = Protocol::parse("kfold:5");
  if (parameters.has("inner")) {
    try {
      inner = Protocol::parse(parameters.text("inner", ""));
    } catch (const Error& error) {
      throw Error(kGridSearchWhere,
                  "inner=" + parameters.text("inner", "") + ": " + error.message());
    }
  }
  return std::make_unique<GridSearchClassifier>(parameters.text("base", ""), std::move(axes),
                                                inner);
}

}  // namespace tactile::ml

namespace tactile::ml {

std::vector<std::string> auto_candidates() {
  std::vector<std::string> candidates;
  for (const ClassifierEntry& entry : classifier_catalog())
    // Not the searches and wrappers, and not em (clusters mapped to classes afterwards: not
    // a classifier to pick by accuracy).
    if (entry.preset && entry.name != "em") candidates.push_back(entry.name);
  // The standard k-NN grid.
  for (const char* k : {"3", "5", "10"})
    candidates.push_back(std::string("knn:k=") + k + ",standardize=true");
  return candidates;
}

std::string searched_specification(const std::string& specification,
                                   const std::vector<FeatureColumn>& columns) {
  const size_t colon = specification.find(':');
  if (specification.substr(0, colon) != "auto") return specification;
  if (colon != std::string::npos &&
      Parameters::parse(specification.substr(colon + 1), "classifier auto").has("blocks"))
    return specification;
  const std::string blocks = stack_blocks(columns);
  if (blocks.empty()) return specification;
  return specification + (colon == std::string::npos ? ":" : ",") + "blocks=" + blocks;
}

std::unique_ptr<Classifier> make_auto_classifier(const Parameters& parameters) {
  parameters.expect_only({"inner", "candidates", "blocks"});
  Protocol inner = Protocol::parse("kfold:5");
  if (parameters.has("inner")) {
    try {
      inner = Protocol::parse(parameters.text("inner", ""));
    } catch (const Error& error) {
      throw Error("classifier auto",
                  "inner=" + parameters.text("inner", "") + ": " + error.message());
    }
  }
  const std::string listed = parameters.text("candidates", "");
  std::vector<std::string> specifications;
  if (listed.empty()) {
    specifications = auto_candidates();
  } else {
    // "linear-svm|knn:k=3;metric=cosine": ';' stands for ',' inside one candidate.
    size_t start = 0;
    while (start <= listed.size()) {
      const size_t bar = std::min(listed.find('|', start), listed.size());
      std::string candidate = listed.substr(start, bar - start);
      std::replace(candidate.begin(), candidate.end(), ';', ',');
      if (!candidate.empty()) specifications.push_back(candidate);
      start = bar + 1;
    }
  }
  return std::make_unique<GridSearchClassifier>(std::move(specifications), inner, listed,
                                                parameters.text("blocks", ""));
}

}  // namespace tactile::ml
