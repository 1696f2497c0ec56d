// evaluate(): folds on worker threads, a fresh classifier per fold, confusion matrices
// summed over folds (spec §6.7), the misclassified segments, timings, progress and cancel.
#include "tactile/ml/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "evaluation_folds.h"
#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/grid_search.h"
#include "tactile/ml/train_all.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void check_dataset(const Dataset& dataset) {
  if (dataset.rows() == 0) throw Error("evaluation", "the dataset has no rows");
  if (dataset.features.cols() == 0) throw Error("evaluation", "the dataset has no feature columns");
  if (static_cast<int64_t>(dataset.classes.size()) != dataset.rows())
    throw Error("evaluation", "the dataset has " + std::to_string(dataset.classes.size()) +
                                  " classes for " + std::to_string(dataset.rows()) + " rows");
  if (dataset.features.allFinite()) return;
  for (Eigen::Index column = 0; column < dataset.features.cols(); ++column)
    for (Eigen::Index row = 0; row < dataset.rows(); ++row)
      if (!std::isfinite(dataset.features(row, column))) {
        const std::string name = column < static_cast<Eigen::Index>(dataset.columns.size())
                                     ? dataset.columns[static_cast<size_t>(column)].name
                                     : "column " + std::to_string(column);
        throw Error("evaluation",
                    "row " + std::to_string(row) + ", feature " + name + " is not a finite number");
      }
}

Matrix rows_of(const Matrix& features, const std::vector<int64_t>& rows) {
  return features(rows, Eigen::all);
}

FoldOutcome run_fold(const Dataset& dataset, const std::vector<int>& classes, int class_count,
                     const std::string& specification, const Fold& fold, uint64_t seed,
                     bool with_scores, const std::vector<std::string>& groups) {
  FoldOutcome outcome;
  std::unique_ptr<Classifier> classifier = make_classifier(specification);
  std::vector<int> train_classes;
  train_classes.reserve(fold.train.size());
  for (int64_t row : fold.train) train_classes.push_back(classes[static_cast<size_t>(row)]);
  if (!with_scores) classifier->skip_scores();  // predict() only: no work for scores
  const Clock::time_point fit_start = Clock::now();
  std::vector<std::string> train_groups;
  if (!groups.empty())
    for (int64_t row : fold.train) train_groups.push_back(groups[static_cast<size_t>(row)]);
  {
    const FitGroupsScope scope(groups.empty() ? nullptr : &train_groups);
    classifier->fit(rows_of(dataset.features, fold.train), train_classes, class_count, seed);
  }
  outcome.fit_seconds = seconds_since(fit_start);
  outcome.importances = classifier->feature_importances();
  const Clock::time_point predict_start = Clock::now();
  if (with_scores) {
    Classifier::Decisions decisions = classifier->decide(rows_of(dataset.features, fold.test));
    outcome.predicted = std::move(decisions.classes);
    outcome.scores = std::move(decisions.scores);
  } else {
    outcome.predicted = classifier->predict(rows_of(dataset.features, fold.test));
  }
  outcome.predict_seconds = seconds_since(predict_start);
  if (outcome.predicted.size() != fold.test.size())
    throw Error("classifier " + classifier->name(),
                "predicted " + std::to_string(outcome.predicted.size()) + " classes for " +
                    std::to_string(fold.test.size()) + " rows");
  const auto* grid = dynamic_cast<const GridSearchClassifier*>(classifier.get());
  outcome.model = grid ? grid->chosen_specification() : specification_of(*classifier);
  return outcome;
}

double metadata_number(const Metadata& metadata, const char* key) {
  const auto found = metadata.find(key);
  if (found == metadata.end()) return 0.0;
  char* end = nullptr;
  const double value = std::strtod(found->second.c_str(), &end);
  return end != found->second.c_str() && std::isfinite(value) ? value : 0.0;
}

// The folds' importances averaged (a fold without them counts as all zero), named by column,
// non-zero ones only, largest first.
std::vector<FeatureImportance> mean_importances(const Dataset& dataset,
                                                const std::vector<FoldOutcome>& outcomes) {
  const auto columns = static_cast<size_t>(dataset.features.cols());
  std::vector<double> sum(columns, 0.0);
  bool any = false;
  for (const FoldOutcome& outcome : outcomes) {
    if (outcome.importances.size() != columns) continue;
    any = true;
    for (size_t column = 0; column < columns; ++column) sum[column] += outcome.importances[column];
  }
  std::vector<FeatureImportance> importances;
  if (!any) return importances;
  for (size_t column = 0; column < columns; ++column) {
    if (!(sum[column] > 0.0)) continue;
    const std::string name = column < dataset.columns.size() ? dataset.columns[column].name
                                                             : "column " + std::to_string(column);
    importances.push_back({name, sum[column] / static_cast<double>(outcomes.size())});
  }
  std::stable_sort(importances.begin(), importances.end(),
                   [](const FeatureImportance& a, const FeatureImportance& b) {
                     return a.importance > b.importance;
                   });
  return importances;
}

RowPrediction row_prediction(const Dataset& dataset, size_t row, int truth, int answer, int fold) {
  RowPrediction prediction = row_place(dataset, static_cast<int64_t>(row));
  prediction.truth = truth;
  prediction.predicted = answer;
  prediction.fold = fold;
  return prediction;
}

}  // namespace

RowPrediction row_place(const Dataset& dataset, int64_t row) {
  const auto index = static_cast<size_t>(row);
  RowPrediction place;
  place.row = row;
  place.segment_id = index < dataset.segment_ids.size() ? dataset.segment_ids[index] : row;
  place.recording = index < dataset.recordings.size() ? dataset.recordings[index] : "";
  if (index < dataset.metadata.size()) {
    const Metadata& metadata = dataset.metadata[index];
    place.t0 = metadata_number(metadata, "t0");
    place.t1 = metadata_number(metadata, "t1");
    const auto region = metadata.find("region");
    if (region != metadata.end()) place.region = region->second;
  }
  return place;
}

//---- Figures --------------------------------------------------------------------------------

double accuracy_of(const Eigen::MatrixXi& confusion) {
  const Eigen::Index classes = confusion.rows();
  const int64_t total = confusion.cast<int64_t>().sum();
  if (total == 0) return 0.0;
  return static_cast<double>(confusion.leftCols(classes).cast<int64_t>().trace()) /
         static_cast<double>(total);
}

std::vector<ClassFigures> class_figures(const Eigen::MatrixXi& confusion) {
  const Eigen::Index classes = confusion.rows();
  std::vector<ClassFigures> figures(static_cast<size_t>(classes));
  for (Eigen::Index k = 0; k < classes; ++k) {
    const auto correct = static_cast<double>(confusion(k, k));
    const int64_t row = confusion.row(k).cast<int64_t>().sum();
    const int64_t column = confusion.col(k).cast<int64_t>().sum();
    ClassFigures& figure = figures[static_cast<size_t>(k)];
    figure.support = row;
    figure.recall = row > 0 ? correct / static_cast<double>(row) : 0.0;
    figure.precision = column > 0 ? correct / static_cast<double>(column) : 0.0;
    // Spec §6.7 (Robovie): false alarm = (column_k - M[k][k]) / row_k.
    figure.false_alarm =
        row > 0 ? (static_cast<double>(column) - correct) / static_cast<double>(row) : 0.0;
  }
  return figures;
}

//---- Evaluation -----------------------------------------------------------------------------

namespace {

// fit_groups() of this thread; null: none.
thread_local const std::vector<std::string>* tl_fit_groups = nullptr;

}  // namespace

const std::vector<std::string>& fit_groups() {
  static const std::vector<std::string> kNone;
  return tl_fit_groups ? *tl_fit_groups : kNone;
}

FitGroupsScope::FitGroupsScope(const std::vector<std::string>* groups) : previous_(tl_fit_groups) {
  tl_fit_groups = groups;
}

FitGroupsScope::~FitGroupsScope() { tl_fit_groups = previous_; }

EvaluationSetup prepare_evaluation(const Dataset& dataset, const std::string& given_specification,
                                   const Protocol& protocol, uint64_t seed) {
  check_dataset(dataset);
  EvaluationSetup setup;
  // auto on a stacked table searches its pipelines too.
  setup.specification = searched_specification(given_specification, dataset.columns);
  make_classifier(setup.specification);  // a bad name or parameter fails before any fold
  setup.given_specification = given_specification;
  setup.protocol = protocol;
  setup.seed = seed;
  setup.class_names = dataset.class_names();
  std::map<std::string, int> index;
  for (size_t k = 0; k < setup.class_names.size(); ++k)
    index[setup.class_names[k]] = static_cast<int>(k);
  setup.classes.reserve(dataset.classes.size());
  for (const std::string& name : dataset.classes) setup.classes.push_back(index.at(name));
  setup.folds = make_folds(dataset, protocol, seed);
  setup.groups = protocol_groups(dataset, protocol);
  return setup;
}

std::vector<FoldOutcome> run_folds(const Dataset& dataset, const EvaluationSetup& setup,
                                   const std::vector<int>& which,
                                   const EvaluationControl& control) {
  const int class_count = static_cast<int>(setup.class_names.size());
  const int fold_count = static_cast<int>(which.size());
  std::vector<FoldOutcome> outcomes(which.size());
  if (which.empty()) return outcomes;

  // The threads given (else this thread's budget: an evaluation inside a fold of another, a
  // search's inner cross-validation, has its fold's share), the folds side by side, each
  // with its share for the classifier's own loops.
  const int given = control.threads > 0 ? control.threads : thread_budget();
  const int threads = std::min(given, fold_count);
  const int each_fold = std::max(1, given / threads);
  std::atomic<int> next_fold{0};
  std::atomic<bool> failed{false};
  std::mutex progress_mutex;
  int done = 0;
  // The job's flag reaches nested evaluations through the thread's cancel scope.
  const std::atomic<bool>* cancel = control.cancel ? control.cancel : current_cancel_flag();
  const auto cancelled = [&] { return cancel && cancel->load(); };
  const auto work = [&] {
    // The folds' threads work for the same job: a classifier's fit polls its flag.
    const CancelScope scope(cancel);
    const ThreadBudget budget(each_fold);
    while (!failed.load() && !cancelled()) {
      const int next = next_fold.fetch_add(1);
      if (next >= fold_count) return;
      const int fold = which[static_cast<size_t>(next)];
      FoldOutcome& outcome = outcomes[static_cast<size_t>(next)];
      const Clock::time_point fold_start = Clock::now();
      try {
        outcome = run_fold(dataset, setup.classes, class_count, setup.specification,
                           setup.folds[static_cast<size_t>(fold)],
                           derive_seed(setup.seed, static_cast<uint64_t>(fold)), control.scores,
                           setup.groups);
      } catch (...) {
        outcome.failure = std::current_exception();
        failed.store(true);
        return;
      }
      outcome.seconds = seconds_since(fold_start);
      outcome.ran = true;
      if (control.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        control.progress(++done, fold_count);
      }
    }
  };
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> workers;
    for (int i = 0; i < threads; ++i) workers.emplace_back(work);
    for (std::thread& worker : workers) worker.join();
  }
  if (cancelled()) throw Error("evaluation", "cancelled");
  return outcomes;
}

void rethrow_first_failure(const std::vector<FoldOutcome>& outcomes) {
  for (const FoldOutcome& outcome : outcomes)
    if (outcome.failure) std::rethrow_exception(outcome.failure);
}

EvaluationResult assemble_evaluation(const Dataset& dataset, const EvaluationSetup& setup,
                                     const std::vector<FoldOutcome>& outcomes) {
  EvaluationResult result;
  result.classifier = setup.given_specification;
  result.protocol = setup.protocol.to_string();
  result.seed = setup.seed;
  result.classes = setup.class_names;
  const int class_count = static_cast<int>(result.classes.size());
  const int fold_count = static_cast<int>(setup.folds.size());
  const std::vector<int>& classes = setup.classes;
  const std::string& classifier_specification = setup.specification;
  result.confusion = Eigen::MatrixXi::Zero(class_count, class_count + 1);
  for (int fold = 0; fold < fold_count; ++fold) {
    const Fold& split = setup.folds[static_cast<size_t>(fold)];
    const FoldOutcome& outcome = outcomes[static_cast<size_t>(fold)];
    result.fit_seconds += outcome.fit_seconds;
    result.predict_seconds += outcome.predict_seconds;
    result.fold_models.push_back(outcome.model);
    if (outcome.predicted.size() != split.test.size())
      throw Error("classifier " + classifier_specification,
                  "fold " + std::to_string(fold) + ": " + std::to_string(outcome.predicted.size()) +
                      " predictions for " + std::to_string(split.test.size()) + " test rows");
    for (size_t i = 0; i < split.test.size(); ++i) {
      const auto row = static_cast<size_t>(split.test[i]);
      const int truth = classes[row];
      const int answer = outcome.predicted[i];
      if (answer != kUnknownClass && (answer < 0 || answer >= class_count))
        throw Error("classifier " + classifier_specification,
                    "predicted class " + std::to_string(answer) + ", outside 0.." +
                        std::to_string(class_count - 1));
      result.confusion(truth, answer == kUnknownClass ? class_count : answer) += 1;
      ++result.predictions;
      RowPrediction prediction = row_prediction(dataset, row, truth, answer, fold);
      if (outcome.scores.rows() == static_cast<Eigen::Index>(split.test.size())) {
        const Confidence confidence =
            confidence_of(outcome.scores.row(static_cast<Eigen::Index>(i)).transpose(), answer);
        prediction.score = confidence.score;
        prediction.margin = confidence.margin;
      }
      result.rows.push_back(std::move(prediction));
      if (answer == truth) continue;
      Misclassified wrong;
      wrong.row = static_cast<int64_t>(row);
      wrong.segment_id = row < dataset.segment_ids.size() ? dataset.segment_ids[row] : wrong.row;
      wrong.recording = row < dataset.recordings.size() ? dataset.recordings[row] : "";
      wrong.true_class = result.classes[static_cast<size_t>(truth)];
      wrong.predicted_class =
          answer == kUnknownClass ? "unknown" : result.classes[static_cast<size_t>(answer)];
      wrong.fold = fold;
      result.misclassified.push_back(std::move(wrong));
    }
  }
  result.accuracy = accuracy_of(result.confusion);
  result.per_class = class_figures(result.confusion);
  result.importances = mean_importances(dataset, outcomes);
  return result;
}

EvaluationResult evaluate(const Dataset& dataset, const std::string& given_specification,
                          const Protocol& protocol, uint64_t seed,
                          const EvaluationControl& control) {
  const Clock::time_point start = Clock::now();
  const EvaluationSetup setup = prepare_evaluation(dataset, given_specification, protocol, seed);
  std::vector<int> every(setup.folds.size());
  for (size_t fold = 0; fold < every.size(); ++fold) every[fold] = static_cast<int>(fold);
  const std::vector<FoldOutcome> outcomes = run_folds(dataset, setup, every, control);
  rethrow_first_failure(outcomes);
  EvaluationResult result = assemble_evaluation(dataset, setup, outcomes);
  result.seconds = seconds_since(start);
  return result;
}

//---- JSON -----------------------------------------------------------------------------------

nlohmann::json to_json(const EvaluationResult& result, bool with_rows) {
  const Eigen::Index classes = static_cast<Eigen::Index>(result.classes.size());
  nlohmann::json confusion = nlohmann::json::array();
  nlohmann::json unknown = nlohmann::json::array();
  for (Eigen::Index row = 0; row < result.confusion.rows(); ++row) {
    nlohmann::json counts = nlohmann::json::array();
    for (Eigen::Index column = 0; column < classes; ++column)
      counts.push_back(result.confusion(row, column));
    confusion.push_back(counts);
    unknown.push_back(result.confusion.cols() > classes ? result.confusion(row, classes) : 0);
  }
  nlohmann::json per_class = nlohmann::json::array();
  for (size_t k = 0; k < result.per_class.size(); ++k) {
    const ClassFigures& figure = result.per_class[k];
    per_class.push_back({{"class", k < result.classes.size() ? result.classes[k] : ""},
                         {"precision", figure.precision},
                         {"recall", figure.recall},
                         {"false_alarm", figure.false_alarm},
                         {"support", figure.support}});
  }
  // Distinct segment ids in dataset row order; every wrong answer is in the details.
  std::map<int64_t, int64_t> segment_of_row;
  nlohmann::json details = nlohmann::json::array();
  for (const Misclassified& wrong : result.misclassified) {
    segment_of_row.emplace(wrong.row, wrong.segment_id);
    details.push_back({{"row", wrong.row},
                       {"segment_id", wrong.segment_id},
                       {"recording", wrong.recording},
                       {"true", wrong.true_class},
                       {"predicted", wrong.predicted_class},
                       {"fold", wrong.fold}});
  }
  nlohmann::json misclassified = nlohmann::json::array();
  for (const auto& [row, segment] : segment_of_row) misclassified.push_back(segment);
  nlohmann::json document = {{"classifier", result.classifier},
                             {"protocol", result.protocol},
                             {"seed", result.seed},
                             {"accuracy", result.accuracy},
                             {"classes", result.classes},
                             {"confusion", confusion},
                             {"unknown", unknown},
                             {"per_class", per_class},
                             {"misclassified", misclassified},
                             {"misclassified_predictions", details},
                             {"predictions", result.predictions},
                             {"folds", result.fold_models.size()},
                             {"fold_models", result.fold_models},
                             {"seconds", result.seconds},
                             {"fit_seconds", result.fit_seconds},
                             {"predict_seconds", result.predict_seconds}};
  document["mean_recall"] = mean_recall(result);
  if (!result.importances.empty()) {
    nlohmann::json importances = nlohmann::json::array();
    for (const FeatureImportance& entry : result.importances)
      importances.push_back({{"feature", entry.feature}, {"importance", entry.importance}});
    document["importances"] = std::move(importances);
  }
  if (!with_rows) return document;
  const auto class_name = [&](int index) {
    return index >= 0 && index < static_cast<int>(result.classes.size())
               ? result.classes[static_cast<size_t>(index)]
               : std::string("unknown");
  };
  nlohmann::json rows = nlohmann::json::array();
  for (const RowPrediction& row : result.rows)
    rows.push_back({{"recording", row.recording},
                    {"t0", row.t0},
                    {"t1", row.t1},
                    {"region", row.region},
                    {"true", class_name(row.truth)},
                    {"predicted", class_name(row.predicted)},
                    {"score", row.score},
                    {"margin", row.margin},
                    {"segment_id", row.segment_id},
                    {"row", row.row},
                    {"fold", row.fold}});
  document["rows"] = std::move(rows);
  return document;
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const ClassifierEntry& entry : classifier_catalog())
    if (entry.preset) names.push_back(entry.name);
  return names;
}

std::vector<PresetOutcome> evaluate_all(
    const Dataset& dataset, const Protocol& protocol, uint64_t seed,
    const EvaluationControl& control,
    const std::function<void(const PresetOutcome&, int, int)>& each) {
  check_dataset(dataset);
  const std::vector<TrainAllStep> plan = train_all_plan(
      dataset.rows(), dataset.features.cols(), static_cast<int>(dataset.class_names().size()));
  const auto total = static_cast<int>(plan.size());
  double total_cost = 0.0;
  for (const TrainAllStep& step : plan) total_cost += step.cost;
  // The bar in thousandths, each preset weighed by its share of the estimated work.
  constexpr int kBar = 1000;
  double cost_before = 0.0;
  std::vector<PresetOutcome> outcomes;
  for (int index = 0; index < total; ++index) {
    const TrainAllStep& step = plan[static_cast<size_t>(index)];
    PresetOutcome outcome;
    outcome.classifier = step.classifier;
    EvaluationControl preset_control = control;
    if (control.progress)
      preset_control.progress = [&](int done, int folds) {
        const double cost = cost_before + step.cost * done / std::max(1, folds);
        control.progress(static_cast<int>(std::lround(kBar * cost / total_cost)), kBar);
      };
    try {
      outcome.result = evaluate(dataset, outcome.classifier, protocol, seed, preset_control);
    } catch (const Error& error) {
      if (control.cancel && control.cancel->load()) throw;
      outcome.skipped = error.what();
    }
    cost_before += step.cost;
    outcomes.push_back(outcome);
    if (each) each(outcomes.back(), index, total);
  }
  return outcomes;
}

nlohmann::json summary_json(const PresetOutcome& outcome) {
  nlohmann::json line = {{"classifier", outcome.classifier}};
  if (outcome.result) {
    line["accuracy"] = outcome.result->accuracy;
    line["mean_recall"] = mean_recall(*outcome.result);
    line["seconds"] = outcome.result->seconds;
  } else {
    line["skipped"] = outcome.skipped;
  }
  return line;
}

double mean_recall(const EvaluationResult& result) {
  if (result.per_class.empty()) return 0.0;
  double sum = 0.0;
  for (const ClassFigures& figure : result.per_class) sum += figure.recall;
  return sum / static_cast<double>(result.per_class.size());
}

std::vector<const RowPrediction*> rows_in_cell(const EvaluationResult& result, int truth,
                                               int predicted) {
  std::vector<const RowPrediction*> cell;
  for (const RowPrediction& row : result.rows)
    if (row.truth == truth && row.predicted == predicted) cell.push_back(&row);
  return cell;
}

namespace {

template <typename T>
T field(const nlohmann::json& object, const char* key, const std::string& where) {
  if (!object.is_object() || !object.contains(key))
    throw Error(where, std::string("missing field '") + key + "'");
  try {
    return object.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error(where, std::string("field '") + key + "' has the wrong type");
  }
}

}  // namespace

EvaluationResult evaluation_from_json(const nlohmann::json& document, const std::string& where) {
  if (!document.is_object()) throw Error(where, "not an evaluation result (expected an object)");
  EvaluationResult result;
  result.classifier = field<std::string>(document, "classifier", where);
  result.protocol = field<std::string>(document, "protocol", where);
  result.classes = field<std::vector<std::string>>(document, "classes", where);
  result.accuracy = field<double>(document, "accuracy", where);
  if (document.contains("seconds")) result.seconds = field<double>(document, "seconds", where);
  if (document.contains("seed")) result.seed = field<uint64_t>(document, "seed", where);
  const auto classes = static_cast<int>(result.classes.size());
  if (classes == 0) throw Error(where, "'classes' is empty");
  std::map<std::string, int> index;
  for (int k = 0; k < classes; ++k) index[result.classes[static_cast<size_t>(k)]] = k;
  const auto confusion = field<std::vector<std::vector<int64_t>>>(document, "confusion", where);
  std::vector<int64_t> unknown(static_cast<size_t>(classes), 0);
  if (document.contains("unknown"))
    unknown = field<std::vector<int64_t>>(document, "unknown", where);
  if (static_cast<int>(confusion.size()) != classes || static_cast<int>(unknown.size()) != classes)
    throw Error(where, "'confusion' has " + std::to_string(confusion.size()) + " rows for " +
                           std::to_string(classes) + " classes");
  result.confusion = Eigen::MatrixXi::Zero(classes, classes + 1);
  for (int row = 0; row < classes; ++row) {
    const auto& counts = confusion[static_cast<size_t>(row)];
    if (static_cast<int>(counts.size()) != classes)
      throw Error(where, "confusion row " + std::to_string(row) + " has " +
                             std::to_string(counts.size()) + " counts for " +
                             std::to_string(classes) + " classes");
    for (int column = 0; column <= classes; ++column) {
      const int64_t count = column < classes ? counts[static_cast<size_t>(column)]
                                             : unknown[static_cast<size_t>(row)];
      if (count < 0 || count > std::numeric_limits<int>::max())
        throw Error(where, "confusion count " + std::to_string(count) + " out of range");
      result.confusion(row, column) = static_cast<int>(count);
    }
  }
  result.predictions = result.confusion.cast<int64_t>().sum();
  result.per_class = class_figures(result.confusion);
  if (document.contains("importances")) {
    const nlohmann::json& importances = document.at("importances");
    if (!importances.is_array()) throw Error(where, "'importances' is not an array");
    for (size_t i = 0; i < importances.size(); ++i) {
      const std::string at = where + ": importances[" + std::to_string(i) + "]";
      result.importances.push_back({field<std::string>(importances[i], "feature", at),
                                    field<double>(importances[i], "importance", at)});
    }
  }
  if (document.contains("rows")) {
    const nlohmann::json& rows = document.at("rows");
    if (!rows.is_array()) throw Error(where, "'rows' is not an array");
    for (size_t i = 0; i < rows.size(); ++i) {
      const std::string at = where + ": rows[" + std::to_string(i) + "]";
      const nlohmann::json& item = rows[i];
      RowPrediction row;
      row.recording = field<std::string>(item, "recording", at);
      row.t0 = field<double>(item, "t0", at);
      row.t1 = field<double>(item, "t1", at);
      row.region = field<std::string>(item, "region", at);
      const auto truth = index.find(field<std::string>(item, "true", at));
      if (truth == index.end()) throw Error(at, "'true' is not one of the classes");
      row.truth = truth->second;
      const std::string predicted = field<std::string>(item, "predicted", at);
      const auto answer = index.find(predicted);
      if (answer == index.end() && predicted != "unknown")
        throw Error(at, "'predicted' is not one of the classes");
      row.predicted = answer == index.end() ? kUnknownClass : answer->second;
      row.score = field<double>(item, "score", at);
      if (item.contains("margin")) row.margin = field<double>(item, "margin", at);
      if (item.contains("segment_id")) row.segment_id = field<int64_t>(item, "segment_id", at);
      if (item.contains("row")) row.row = field<int64_t>(item, "row", at);
      if (item.contains("fold")) row.fold = field<int>(item, "fold", at);
      result.rows.push_back(std::move(row));
    }
  }
  return result;
}

}  // namespace tactile::ml
