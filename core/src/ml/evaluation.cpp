// evaluate(): folds on worker threads, a fresh classifier per fold, confusion matrices
// summed over folds (spec §6.7), the misclassified segments, timings, progress and cancel.
#include "tactile/ml/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "tactile/error.h"
#include "tactile/ml/grid_search.h"
#include "tactile/ml/sampling.h"

namespace tactile::ml {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What one fold hands back; merged in fold order so threads never change the result.
struct FoldOutcome {
  std::vector<int> predicted;  // per test row
  std::string model;
  double fit_seconds = 0.0;
  double predict_seconds = 0.0;
  std::exception_ptr failure;
};

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
                     const std::string& specification, const Fold& fold, uint64_t seed) {
  FoldOutcome outcome;
  std::unique_ptr<Classifier> classifier = make_classifier(specification);
  std::vector<int> train_classes;
  train_classes.reserve(fold.train.size());
  for (int64_t row : fold.train) train_classes.push_back(classes[static_cast<size_t>(row)]);
  const Clock::time_point fit_start = Clock::now();
  classifier->fit(rows_of(dataset.features, fold.train), train_classes, class_count, seed);
  outcome.fit_seconds = seconds_since(fit_start);
  const Clock::time_point predict_start = Clock::now();
  outcome.predicted = classifier->predict(rows_of(dataset.features, fold.test));
  outcome.predict_seconds = seconds_since(predict_start);
  if (outcome.predicted.size() != fold.test.size())
    throw Error("classifier " + classifier->name(),
                "predicted " + std::to_string(outcome.predicted.size()) + " classes for " +
                    std::to_string(fold.test.size()) + " rows");
  const auto* grid = dynamic_cast<const GridSearchClassifier*>(classifier.get());
  outcome.model = grid ? grid->chosen_specification() : specification_of(*classifier);
  return outcome;
}

}  // namespace

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

EvaluationResult evaluate(const Dataset& dataset, const std::string& classifier_specification,
                          const Protocol& protocol, uint64_t seed,
                          const EvaluationControl& control) {
  const Clock::time_point start = Clock::now();
  check_dataset(dataset);
  make_classifier(classifier_specification);  // a bad name or parameter fails before any fold

  EvaluationResult result;
  result.classifier = classifier_specification;
  result.protocol = protocol.to_string();
  result.seed = seed;
  result.classes = dataset.class_names();
  const int class_count = static_cast<int>(result.classes.size());
  std::map<std::string, int> index;
  for (int k = 0; k < class_count; ++k) index[result.classes[static_cast<size_t>(k)]] = k;
  std::vector<int> classes;
  classes.reserve(dataset.classes.size());
  for (const std::string& name : dataset.classes) classes.push_back(index.at(name));

  const std::vector<Fold> folds = make_folds(dataset, protocol, seed);
  const int fold_count = static_cast<int>(folds.size());
  std::vector<FoldOutcome> outcomes(folds.size());

  unsigned threads = control.threads > 0 ? static_cast<unsigned>(control.threads)
                                         : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(fold_count));
  std::atomic<int> next_fold{0};
  std::atomic<bool> failed{false};
  std::mutex progress_mutex;
  int done = 0;
  const auto cancelled = [&] { return control.cancel && control.cancel->load(); };
  const auto work = [&] {
    while (!failed.load() && !cancelled()) {
      const int fold = next_fold.fetch_add(1);
      if (fold >= fold_count) return;
      FoldOutcome& outcome = outcomes[static_cast<size_t>(fold)];
      try {
        outcome = run_fold(dataset, classes, class_count, classifier_specification,
                           folds[static_cast<size_t>(fold)],
                           derive_seed(seed, static_cast<uint64_t>(fold)));
      } catch (...) {
        outcome.failure = std::current_exception();
        failed.store(true);
        return;
      }
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
    for (unsigned i = 0; i < threads; ++i) workers.emplace_back(work);
    for (std::thread& worker : workers) worker.join();
  }
  if (cancelled()) throw Error("evaluation", "cancelled");
  for (const FoldOutcome& outcome : outcomes)
    if (outcome.failure) std::rethrow_exception(outcome.failure);

  result.confusion = Eigen::MatrixXi::Zero(class_count, class_count + 1);
  for (int fold = 0; fold < fold_count; ++fold) {
    const Fold& split = folds[static_cast<size_t>(fold)];
    const FoldOutcome& outcome = outcomes[static_cast<size_t>(fold)];
    result.fit_seconds += outcome.fit_seconds;
    result.predict_seconds += outcome.predict_seconds;
    result.fold_models.push_back(outcome.model);
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
  result.seconds = seconds_since(start);
  return result;
}

//---- JSON -----------------------------------------------------------------------------------

nlohmann::json to_json(const EvaluationResult& result) {
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
  return {{"classifier", result.classifier},
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
}

}  // namespace tactile::ml
