#include "tactile/ml/grid_search.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
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

}  // namespace

GridSearchClassifier::GridSearchClassifier(std::string base,
                                           std::vector<std::pair<std::string, std::string>> axes,
                                           Protocol inner)
    : base_(std::move(base)), axes_(std::move(axes)), inner_(std::move(inner)) {
  if (base_.empty()) throw Error(kGridSearchWhere, "base= is required, e.g. grid:base=knn,k=1|3|5");
  if (base_ == "grid-search" || base_ == "grid")
    throw Error(kGridSearchWhere, "base=" + base_ + ": a grid search cannot search a grid search");
  if (inner_.kind == Protocol::Kind::kLeaveOneSubjectOut || inner_.kind == Protocol::Kind::kLeaveOneGroupOut ||
      inner_.kind == Protocol::Kind::kSplit)
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
      throw Error(kGridSearchWhere, "more than " + std::to_string(kMostCandidates) + " combinations");
    specifications = std::move(extended);
  }
  for (const std::string& parameters : specifications) {
    const std::string specification = base_ + (parameters.empty() ? "" : ":" + parameters);
    make_classifier(specification);  // an unknown base or parameter fails here, before any fit
    candidates_.push_back({specification, 0.0});
  }
}

GridSearchClassifier::GridSearchClassifier(std::vector<std::string> specifications, Protocol inner,
                                           std::string listed)
    : auto_(true), listed_(std::move(listed)), inner_(std::move(inner)) {
  if (inner_.kind == Protocol::Kind::kLeaveOneSubjectOut || inner_.kind == Protocol::Kind::kLeaveOneGroupOut ||
      inner_.kind == Protocol::Kind::kSplit)
    throw Error("classifier auto", "inner=" + inner_.to_string() + ": the inner protocol must be kfold, loo or holdout");
  if (specifications.empty()) throw Error("classifier auto", "no candidates");
  for (const std::string& specification : specifications) {
    const std::string name = specification.substr(0, specification.find(':'));
    if (name == "auto" || name == "grid" || name == "grid-search")
      throw Error("classifier auto", "candidate '" + specification + "': searches are not candidates");
    make_classifier(specification);  // an unknown classifier or parameter fails here
    candidates_.push_back({specification, 0.0});
  }
}

Parameters GridSearchClassifier::parameters() const {
  Parameters parameters;
  if (auto_) {
    parameters.set("inner", inner_.to_string());
    if (!listed_.empty()) parameters.set("candidates", listed_);
    return parameters;
  }
  parameters.set("base", base_);
  parameters.set("inner", inner_.to_string());
  for (const auto& [key, values] : axes_) parameters.set(key, values);
  return parameters;
}

void GridSearchClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                               uint64_t seed) {
  check_training_set(x, y, class_count, kGridSearchWhere);
  Dataset inner;
  inner.features = x;
  for (int label : y) inner.classes.push_back(std::to_string(label));
  EvaluationControl sequential;
  sequential.threads = 1;  // the outer evaluation already runs one fold per core
  // Every candidate sees the same inner folds, so they are compared on equal terms.
  const uint64_t inner_seed = derive_seed(seed, 0);
  size_t best = 0;
  for (size_t i = 0; i < candidates_.size(); ++i) {
    try {
      candidates_[i].inner_accuracy =
          evaluate(inner, candidates_[i].specification, inner_, inner_seed, sequential).accuracy;
    } catch (const Error& error) {
      // A candidate that cannot learn from these rows (too few per class, ...) is passed
      // over by auto; a grid's base failing is the grid's failure.
      if (auto_) {
        candidates_[i].inner_accuracy = -1.0;
        continue;
      }
      throw Error(kGridSearchWhere, "inner " + inner_.to_string() + " on " + std::to_string(x.rows()) +
                              " training rows: " + error.what());
    }
    if (candidates_[i].inner_accuracy > candidates_[best].inner_accuracy) best = i;
  }
  if (candidates_[best].inner_accuracy < 0.0)
    throw Error(auto_ ? "classifier auto" : kGridSearchWhere, "no candidate could learn from " + std::to_string(x.rows()) + " training rows");
  std::unique_ptr<Classifier> chosen = make_classifier(candidates_[best].specification);
  chosen->fit(x, y, class_count, seed);
  chosen_ = std::move(chosen);
}

const Classifier& GridSearchClassifier::chosen() const {
  if (!chosen_) throw Error(kGridSearchWhere, "not fitted");
  return *chosen_;
}

std::string GridSearchClassifier::chosen_specification() const {
  return specification_of(chosen());
}

Matrix GridSearchClassifier::scores(const Matrix& x) const { return chosen().scores(x); }

std::vector<int> GridSearchClassifier::predict(const Matrix& x) const {
  return chosen().predict(x);
}

nlohmann::json GridSearchClassifier::save() const {
  nlohmann::json candidates = nlohmann::json::array();
  for (const GridCandidate& candidate : candidates_)
    candidates.push_back(
        {{"specification", candidate.specification}, {"inner_accuracy", candidate.inner_accuracy}});
  return {{"candidates", candidates}, {"chosen", save_classifier(chosen())}};
}

void GridSearchClassifier::load(const nlohmann::json& model) {
  const nlohmann::json& candidates = model.at("candidates");
  if (!candidates.is_array() || candidates.size() != candidates_.size())
    throw Error("model " + name(), "the candidates differ from the grid's parameters");
  for (size_t i = 0; i < candidates_.size(); ++i) {
    if (candidates[i].at("specification").get<std::string>() != candidates_[i].specification)
      throw Error("model " + name(), "the candidates differ from the grid's parameters");
    candidates_[i].inner_accuracy = candidates[i].at("inner_accuracy").get<double>();
  }
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
      throw Error(kGridSearchWhere, "inner=" + parameters.text("inner", "") + ": " + error.message());
    }
  }
  return std::make_unique<GridSearchClassifier>(parameters.text("base", ""), std::move(axes),
                                                inner);
}

}  // namespace tactile::ml

namespace tactile::ml {

std::vector<std::string> auto_candidates() {
  std::vector<std::string> candidates;
  for (const std::string& name : classifier_names())
    // Not the searches, and not em (clusters mapped to classes afterwards: not a classifier
    // to pick by accuracy).
    if (name != "grid" && name != "grid-search" && name != "auto" && name != "em") candidates.push_back(name);
  // The standard k-NN grid.
  for (const char* k : {"3", "5", "10"}) candidates.push_back(std::string("knn:k=") + k + ",standardize=true");
  return candidates;
}

std::unique_ptr<Classifier> make_auto_classifier(const Parameters& parameters) {
  parameters.expect_only({"inner", "candidates"});
  Protocol inner = Protocol::parse("kfold:5");
  if (parameters.has("inner")) {
    try {
      inner = Protocol::parse(parameters.text("inner", ""));
    } catch (const Error& error) {
      throw Error("classifier auto", "inner=" + parameters.text("inner", "") + ": " + error.message());
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
  return std::make_unique<GridSearchClassifier>(std::move(specifications), inner, listed);
}

}  // namespace tactile::ml
