#pragma once
// k-nearest-neighbour classifiers (spec §2.13 presets 8-10, §4.9 baseline).
//
// `knn` parameters:
//   k            neighbours (default 1; more than the training samples -> all of them)
//   metric       euclidean | cosine (1 - x.y / (|x| |y|); a zero vector is at distance 1)
//   weights      equal | inverse (1/d) | squared-inverse (1/d^2); neighbours at distance 0
//                (<= 1e-12) take the whole vote, shared equally, so no weight is infinite
//   standardize  true | false (default false): z-score fitted on the training fold (§6.4)
// Neighbours are the k smallest distances, ties broken by training order. predict() takes
// the class with the most votes under `weights`, a tie between classes going to the class of
// the nearest neighbour among the tied classes (§4.9), not to the lowest class index.
// Scores are distance-weighted votes normalised to sum 1, so that they rank: with
// weights=equal each neighbour counts 1/d in the scores (not in predict(), whose rule the
// spec fixes), with inverse or squared-inverse the weighted votes that decide; neighbours at
// distance 0 take the whole share, divided equally. With k = 1 every score is 1 (one
// neighbour): nothing to rank by. Under equal weights a majority of far neighbours can win
// against a nearer minority, which then has the larger score: the prediction's margin is 0.
//
// Presets (MATLAB Classification Learner, as in issue 5 and spec §2.13; parameters of `knn`
// can still be overridden):
//   cosine-knn    "Cosine KNN": metric=cosine, k=10, weights=equal, standardize=true
//   weighted-knn  "Weighted KNN": metric=euclidean, k=10, weights=squared-inverse, standardize=true
//   subspace-knn  "Subspace KNN": random-subspace ensemble, see SubspaceKnnClassifier.

#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

enum class KnnMetric { kEuclidean, kCosine };
enum class KnnWeights { kEqual, kInverse, kSquaredInverse };

struct KnnSettings {
  int k = 1;
  KnnMetric metric = KnnMetric::kEuclidean;
  KnnWeights weights = KnnWeights::kEqual;
  bool standardize = false;
  // With standardize: scale each feature by its training range onto [0, 1] (Weka's
  // normalisation, parameter standardize=range) instead of by its standard deviation.
  bool range = false;
};

// One neighbour of a query: training row and its distance.
struct Neighbour {
  int64_t row = 0;
  double distance = 0.0;
};

class KnnClassifier : public Classifier {
 public:
  KnnClassifier(std::string name, KnnSettings settings);
  std::string name() const override { return name_; }
  Parameters parameters() const override;
  const KnnSettings& settings() const { return settings_; }
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  Decisions decide(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;
  // The k nearest training rows of each query row, nearest first (ties: training order).
  std::vector<std::vector<Neighbour>> neighbours(const Matrix& x) const;

 private:
  // Votes of `nearest` under `weights`, normalised to sum 1.
  Vector vote(const std::vector<Neighbour>& nearest, KnnWeights weights) const;
  KnnWeights score_weights() const;  // 1/d where the votes are equal
  void prepare();

  std::string name_;
  KnnSettings settings_;
  int class_count_ = 0;
  Standardizer standardizer_;
  Matrix samples_;  // features x training rows (one contiguous column per sample), standardised
  Vector norms_;    // per training sample, for the cosine metric
  // The samples in single precision, transposed (rows = samples): the block search's
  // matrix product ranks candidates in float, twice as fast; exact distances decide.
  Eigen::MatrixXf samples_float_;
  std::vector<int> labels_;
};

// "Subspace KNN": `learners` 1-NN learners (default 30), each on `dimensions` predictors
// drawn without replacement from the seed (default 0 = ceil(P/2), spec §2.13), Euclidean
// distance (or metric=cosine) on features standardised on the training fold
// (standardize=true by default). Scores are the fractions of learners voting each class.
class SubspaceKnnClassifier : public Classifier {
 public:
  SubspaceKnnClassifier(int learners, int dimensions, KnnMetric metric, bool standardize);
  std::string name() const override { return "subspace-knn"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;
  // The predictor indices of each learner, ascending.
  const std::vector<std::vector<int64_t>>& subspaces() const { return subspaces_; }

 private:
  int learners_ = 30;
  int dimensions_ = 0;
  KnnMetric metric_ = KnnMetric::kEuclidean;
  bool standardize_ = true;
  int class_count_ = 0;
  Standardizer standardizer_;
  Matrix samples_;  // standardised training samples, rows = samples
  std::vector<int> labels_;
  std::vector<std::vector<int64_t>> subspaces_;  // one 1-NN learner each, made as it votes
};

std::unique_ptr<Classifier> make_knn_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_cosine_knn_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_weighted_knn_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_subspace_knn_classifier(const Parameters& parameters);

}  // namespace tactile::ml
