#include "tactile/ml/evaluation_shards.h"

#include <cmath>
#include <limits>
#include <map>

#include "evaluation_folds.h"
#include "tactile/error.h"

namespace tactile::ml {

namespace {

// JSON has no NaN or infinity: those travel as text, every other number exactly.
nlohmann::json number_json(double value) {
  if (std::isfinite(value)) return value;
  return std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf";
}

double number_of(const nlohmann::json& value) {
  if (value.is_number()) return value.get<double>();
  const auto text = value.get<std::string>();
  if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (text == "inf") return std::numeric_limits<double>::infinity();
  if (text == "-inf") return -std::numeric_limits<double>::infinity();
  throw Error("merge", "'" + text + "' is not a number");
}

nlohmann::json outcome_json(const FoldOutcome& outcome) {
  nlohmann::json scores = nlohmann::json::array();
  for (Eigen::Index row = 0; row < outcome.scores.rows(); ++row) {
    nlohmann::json values = nlohmann::json::array();
    for (Eigen::Index column = 0; column < outcome.scores.cols(); ++column)
      values.push_back(number_json(outcome.scores(row, column)));
    scores.push_back(std::move(values));
  }
  nlohmann::json importances = nlohmann::json::array();
  for (double value : outcome.importances) importances.push_back(number_json(value));
  return {{"predicted", outcome.predicted},
          {"scores", scores},
          {"model", outcome.model},
          {"importances", importances},
          {"fit_seconds", outcome.fit_seconds},
          {"predict_seconds", outcome.predict_seconds},
          {"seconds", outcome.seconds}};
}

FoldOutcome outcome_of(const nlohmann::json& item) {
  FoldOutcome outcome;
  outcome.predicted = item.at("predicted").get<std::vector<int>>();
  const nlohmann::json& scores = item.at("scores");
  if (!scores.empty()) {
    outcome.scores.resize(static_cast<Eigen::Index>(scores.size()),
                          static_cast<Eigen::Index>(scores.at(0).size()));
    for (size_t row = 0; row < scores.size(); ++row) {
      if (scores[row].size() != static_cast<size_t>(outcome.scores.cols()))
        throw Error("merge", "a fold's scores have rows of different lengths");
      for (size_t column = 0; column < scores[row].size(); ++column)
        outcome.scores(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column)) =
            number_of(scores[row][column]);
    }
  }
  outcome.model = item.at("model").get<std::string>();
  for (const nlohmann::json& value : item.at("importances"))
    outcome.importances.push_back(number_of(value));
  outcome.fit_seconds = item.at("fit_seconds").get<double>();
  outcome.predict_seconds = item.at("predict_seconds").get<double>();
  outcome.seconds = item.at("seconds").get<double>();
  outcome.ran = true;
  return outcome;
}

// What an exception says, for an Error; anything else is no failure of the data: passed on.
std::string failure_text(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const Error& error) {
    return error.what();
  }
}

size_t fold_count(const Dataset& dataset, const EvaluationJob& job) {
  return make_folds(dataset, job.protocol, job.seed).size();
}

}  // namespace

std::vector<std::string> evaluation_plan(const Dataset& dataset, const EvaluationJob& job) {
  const std::vector<Fold> folds = make_folds(dataset, job.protocol, job.seed);
  std::vector<std::string> keys;
  for (const std::string& classifier : job.classifiers)
    for (size_t fold = 0; fold < folds.size(); ++fold)
      keys.push_back(classifier + "#" + std::to_string(fold) + ":" +
                     std::to_string(folds[fold].test.size()));
  return keys;
}

nlohmann::json run_evaluation_items(const Dataset& dataset, const EvaluationJob& job,
                                    const Shard& shard, const EvaluationControl& control) {
  const size_t folds = fold_count(dataset, job);
  const std::vector<size_t> items = shard.items_of(job.classifiers.size() * folds);
  EvaluationControl fold_control = control;
  fold_control.scores = job.scores;
  int done_before = 0;
  nlohmann::json done = nlohmann::json::array();
  for (size_t classifier = 0; classifier < job.classifiers.size(); ++classifier) {
    std::vector<int> which;
    for (size_t item : items)
      if (item / folds == classifier) which.push_back(static_cast<int>(item % folds));
    if (which.empty()) continue;
    const std::string& name = job.classifiers[classifier];
    const auto entry = [&](int fold) {
      return nlohmann::json{{"index", classifier * folds + static_cast<size_t>(fold)},
                            {"classifier", name},
                            {"fold", fold}};
    };
    const auto failed = [&](const std::string& reason) {
      for (int fold : which) {
        nlohmann::json item = entry(fold);
        item["failed"] = reason;
        done.push_back(std::move(item));
      }
    };
    if (control.progress)
      fold_control.progress = [&, before = done_before](int finished, int) {
        control.progress(before + finished, static_cast<int>(items.size()));
      };
    done_before += static_cast<int>(which.size());
    EvaluationSetup setup;
    try {
      setup = prepare_evaluation(dataset, name, job.protocol, job.seed);
    } catch (const Error& error) {
      if (!job.skip_failures) throw;
      failed(error.what());
      continue;
    }
    const std::vector<FoldOutcome> outcomes = run_folds(dataset, setup, which, fold_control);
    if (!job.skip_failures) rethrow_first_failure(outcomes);
    std::string first_failure;
    for (size_t k = 0; k < which.size(); ++k) {
      nlohmann::json item = entry(which[k]);
      const FoldOutcome& outcome = outcomes[k];
      if (outcome.failure) {
        item["failed"] = failure_text(outcome.failure);
        if (first_failure.empty()) first_failure = item["failed"];
      } else if (!outcome.ran) {
        item["failed"] = "not run: " + first_failure;  // after a failure before it
      } else {
        item.update(outcome_json(outcome));
      }
      done.push_back(std::move(item));
    }
  }
  return done;
}

std::vector<PresetOutcome> outcomes_from_items(const Dataset& dataset, const EvaluationJob& job,
                                               const std::vector<nlohmann::json>& items) {
  const size_t folds = fold_count(dataset, job);
  if (items.size() != job.classifiers.size() * folds)
    throw Error("merge", std::to_string(items.size()) + " fold outcomes for " +
                             std::to_string(job.classifiers.size()) + " classifiers x " +
                             std::to_string(folds) + " folds");
  std::vector<PresetOutcome> outcomes;
  for (size_t classifier = 0; classifier < job.classifiers.size(); ++classifier) {
    PresetOutcome outcome;
    outcome.classifier = job.classifiers[classifier];
    std::vector<FoldOutcome> fold_outcomes;
    double seconds = 0.0;
    for (size_t fold = 0; fold < folds && outcome.skipped.empty(); ++fold) {
      const nlohmann::json& item = items[classifier * folds + fold];
      if (item.at("classifier") != outcome.classifier || item.at("fold") != fold)
        throw Error("merge", "item " + item.at("index").dump() + " is not fold " +
                                 std::to_string(fold) + " of " + outcome.classifier);
      if (item.contains("failed")) {
        outcome.skipped = item.at("failed").get<std::string>();
        if (!job.skip_failures) throw Error("", outcome.skipped);  // as one process says it
        break;
      }
      fold_outcomes.push_back(outcome_of(item));
      seconds += fold_outcomes.back().seconds;
    }
    if (outcome.skipped.empty()) {
      const EvaluationSetup setup =
          prepare_evaluation(dataset, outcome.classifier, job.protocol, job.seed);
      outcome.result = assemble_evaluation(dataset, setup, fold_outcomes);
      outcome.result->seconds = seconds;
    }
    outcomes.push_back(std::move(outcome));
  }
  return outcomes;
}

void clear_timings(EvaluationResult& result) {
  result.seconds = 0.0;
  result.fit_seconds = 0.0;
  result.predict_seconds = 0.0;
}

}  // namespace tactile::ml
