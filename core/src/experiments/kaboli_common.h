#pragma once
// Shared machinery of the Kaboli experiments (spec §1.17): the five recording sets (simulated
// or selected from a data folder by metadata), segmentation, feature extraction, training on
// one set and testing on another, and confusion tables beside the paper's.

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tactile/experiments/experiment.h"
#include "tactile/features/corpus.h"
#include "tactile/features/dataset.h"
#include "tactile/ml/classifier.h"

namespace tactile::experiments::kaboli {

// The paper's class order of every confusion matrix (Tables 5-8).
extern const std::vector<std::string> kClasses;
constexpr int kClassCount = 9;
using PaperMatrix = std::array<std::array<int, kClassCount>, kClassCount>;

enum class Set { kBackStationary, kFrontStationary, kBackMoving, kFrontMoving, kMultiTouch };
std::string set_name(Set set);

// The recordings of each set, segmented once, and their feature datasets per pipeline. Without
// a data folder each set is simulated afresh into work_dir/<set name> (e.g. back-stationary),
// replacing what that folder held.
class Corpus {
 public:
  explicit Corpus(const ExperimentOptions& options);
  // The rows of one set with one pipeline's features, only segments that overlap a
  // ground-truth touch on their body part (the others are counted in notes()).
  Dataset dataset(Set set, const std::string& pipeline);
  // One line per set used: where its data came from and how many segments were left out.
  std::string notes() const;
  const ExperimentOptions& options() const { return options_; }

 private:
  struct Source {
    std::string folder;
    std::vector<CorpusRecording> recordings;
  };
  Source& source(Set set);
  void report(const std::string& stage, int done, int total) const;

  ExperimentOptions options_;
  std::map<std::string, Source> sources_;         // by folder
  std::map<std::string, Dataset> datasets_;       // by folder + pipeline
  std::map<std::string, std::string> set_notes_;  // by set name
};

struct Scored {
  Eigen::MatrixXi confusion;  // 9 x 10: rows true, columns predicted, last column "unknown"
  double accuracy = 0.0;
  int64_t train_rows = 0;
  std::shared_ptr<const ml::Classifier> model;  // as fitted on the training set
};

// Fits `classifier` (a make_classifier specification) on `train` and scores `test`.
Scored train_and_test(const Dataset& train, const Dataset& test, const std::string& classifier,
                      uint64_t seed);

// Spec §1.14: linear C-SVM with C chosen from 20 log-spaced values by 10 x stratified 5-fold
// CV inside the training set (quick: 5 values, one repetition of 3 folds).
std::string svm_specification(bool quick);

// Accuracy of a paper's confusion matrix (correct / all counted).
double paper_accuracy_of(const PaperMatrix& matrix);

// A table shaped like Tables 5-8: one row per true class with our counts per predicted class,
// our recall and the paper's recall, and a total row with both accuracies.
ReportTable confusion_table(const std::string& title, const Scored& ours, const PaperMatrix& paper,
                            double paper_accuracy, const std::string& note);
nlohmann::json confusion_json(const std::string& title, const Scored& ours,
                              const PaperMatrix& paper, double paper_accuracy);

std::string percent(double fraction);

}  // namespace tactile::experiments::kaboli
