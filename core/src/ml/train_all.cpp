#include "tactile/ml/train_all.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"

namespace tactile::ml {

namespace {

double accuracy_or_below(const PresetOutcome& outcome) {
  return outcome.result ? outcome.result->accuracy : -1.0;
}

}  // namespace

void sort_best_first(std::vector<PresetOutcome>& outcomes) {
  std::stable_sort(outcomes.begin(), outcomes.end(), [](const PresetOutcome& a, const PresetOutcome& b) {
    return accuracy_or_below(a) > accuracy_or_below(b);
  });
}

int best_outcome(const std::vector<PresetOutcome>& outcomes) {
  int best = -1;
  for (size_t k = 0; k < outcomes.size(); ++k)
    if (outcomes[k].result &&
        (best < 0 || accuracy_or_below(outcomes[k]) > accuracy_or_below(outcomes[static_cast<size_t>(best)])))
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
    outcome.result = evaluation_from_json(evaluations[k], where + ": evaluations[" + std::to_string(k) + "]");
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
