#include "tactile/ml/train_all.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml {

namespace {

double accuracy_or_below(const PresetOutcome& outcome) {
  return outcome.result ? outcome.result->accuracy : -1.0;
}

// An estimate of a preset's training and prediction work over n rows of d columns and k
// classes, from the shape of its algorithm (not measured constants): enough to run the quick
// ones first and to weigh the progress bar. Unknown names cost as a k-NN.
double preset_cost(const std::string& name, double n, double d, double k) {
  const double log_n = std::log2(std::max(2.0, n));
  const double narrow = std::min(n, d);
  const double tree = n * log_n * d * log_n;  // sort each column, scan it at each depth
  if (name == "gaussian-nb") return n * d;
  if (name == "ridge" || name == "clafic") return n * d * narrow;
  if (name == "tree" || name == "medium-tree") return tree;
  if (name == "random-forest") return n * log_n * d + 100.0 * n * log_n * std::sqrt(d) * log_n;
  if (name == "bagged-trees") return 30.0 * tree;
  if (name == "logitboost") return 10.0 * k * tree / log_n;
  // 100 rounds of a depth-6 tree per class: each level reads the rows, each of up to 64 nodes
  // weighs 256 histogram bins of every column.
  if (name == "boosted-trees") return 100.0 * k * d * (6.0 * n + 64.0 * 256.0);
  if (name == "gaussian-ml" || name == "qda") return k * d * d * d + n * d * d;
  if (name == "em") return 10.0 * 100.0 * k * n * d;  // restarts x iterations
  // 1000 epochs of a distance and an update to 49 neurons per row (in the rows' span when the
  // table is wide: its basis costs two passes of the table).
  if (name == "som") return 2.0 * 1000.0 * n * 49.0 * narrow + 2.0 * n * d * narrow;
  if (name == "subspace-knn") return 15.0 * n * n * d;  // 30 learners on half the columns
  if (name == "linear-svm") return n * n * d;
  if (name.find("-svm") != std::string::npos) return 3.0 * n * n * d;
  return n * n * d;  // the k-NN family, kernel-nb
}

}  // namespace

std::vector<TrainAllStep> train_all_plan(int64_t rows, int64_t columns, int classes) {
  std::vector<TrainAllStep> plan;
  for (const ClassifierEntry& entry : classifier_catalog()) {
    if (!entry.preset) continue;
    TrainAllStep step;
    step.classifier = entry.name;
    int64_t used = columns;
    if (entry.widest > 0 && columns > entry.widest) {
      step.classifier = "select:k=" + std::to_string(entry.widest) + ",base=" + entry.name;
      used = entry.widest;
    }
    // Choosing the columns reads the whole table once per fold.
    step.cost = preset_cost(entry.name, static_cast<double>(rows), static_cast<double>(used),
                            static_cast<double>(classes)) +
                (used < columns ? static_cast<double>(rows * columns) : 0.0);
    plan.push_back(step);
  }
  std::stable_sort(plan.begin(), plan.end(),
                   [](const TrainAllStep& a, const TrainAllStep& b) { return a.cost < b.cost; });
  return plan;
}

void sort_best_first(std::vector<PresetOutcome>& outcomes) {
  std::stable_sort(outcomes.begin(), outcomes.end(),
                   [](const PresetOutcome& a, const PresetOutcome& b) {
                     return accuracy_or_below(a) > accuracy_or_below(b);
                   });
}

int best_outcome(const std::vector<PresetOutcome>& outcomes) {
  int best = -1;
  for (size_t k = 0; k < outcomes.size(); ++k)
    if (outcomes[k].result &&
        (best < 0 ||
         accuracy_or_below(outcomes[k]) > accuracy_or_below(outcomes[static_cast<size_t>(best)])))
      best = static_cast<int>(k);
  return best;
}

nlohmann::json to_json(const TrainAllResult& result) {
  nlohmann::json presets = nlohmann::json::array(), evaluations = nlohmann::json::array();
  for (const PresetOutcome& outcome : result.outcomes) {
    presets.push_back(summary_json(outcome));
    if (!outcome.result) continue;
    evaluations.push_back(to_json(*outcome.result, true));
    evaluations.back()["features"] = result.features;
  }
  return {{"protocol", result.protocol},
          {"seed", result.seed},
          {"features", result.features},
          {"presets", presets},
          {"evaluations", evaluations}};
}

TrainAllResult train_all_from_json(const nlohmann::json& document, const std::string& where) {
  if (!document.is_object()) throw Error(where, "not a JSON object");
  TrainAllResult result;
  result.features = document.value("features", std::string());
  if (!document.contains("evaluations")) {  // one evaluation
    PresetOutcome outcome;
    outcome.result = evaluation_from_json(document, where);
    outcome.classifier = outcome.result->classifier;
    result.outcomes.push_back(std::move(outcome));
    return result;
  }
  result.protocol = document.value("protocol", std::string());
  if (document.contains("seed") && document["seed"].is_number_unsigned())
    result.seed = document["seed"].get<uint64_t>();
  const nlohmann::json& evaluations = document["evaluations"];
  if (!evaluations.is_array()) throw Error(where, "'evaluations' is not a list");
  for (size_t k = 0; k < evaluations.size(); ++k) {
    PresetOutcome outcome;
    outcome.result =
        evaluation_from_json(evaluations[k], where + ": evaluations[" + std::to_string(k) + "]");
    outcome.classifier = outcome.result->classifier;
    result.outcomes.push_back(std::move(outcome));
  }
  // The presets that did not fit the data: only in the table, with the reason.
  if (document.contains("presets") && document["presets"].is_array())
    for (const nlohmann::json& preset : document["presets"])
      if (preset.is_object() && preset.contains("skipped"))
        result.outcomes.push_back({preset.value("classifier", std::string("?")), std::nullopt,
                                   preset.value("skipped", std::string())});
  return result;
}

void write_train_all_file(const std::string& path, const TrainAllResult& result) {
  write_file_atomically(path, to_json(result).dump(1) + "\n", "evaluation");
}

TrainAllResult read_train_all_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, false);
  if (document.is_discarded()) throw Error(path, "not JSON");
  TrainAllResult result = train_all_from_json(document, path);
  if (result.outcomes.empty()) throw Error(path, "holds no evaluation");
  return result;
}

}  // namespace tactile::ml
