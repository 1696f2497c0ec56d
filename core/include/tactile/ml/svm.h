#pragma once
// Support vector machines trained by libsvm's C-SVC solver, one-vs-one, on features
// standardised with the training fold's statistics (spec §6.4).
//
// Presets (names as on the command line; MATLAB Classification Learner presets as found in
// exported code: BoxConstraint 1, Standardize true, one-vs-one):
//   linear-svm           K(x, z) = x'z / s²,            s = 1 (Kaboli §1.14: linear C-SVM;
//                        MATLAB's Linear SVM with KernelScale 'auto' is `scale=auto`)
//   quadratic-svm        K(x, z) = (1 + x'z / s²)²,     s = 'auto' (MATLAB Quadratic SVM)
//   cubic-svm            K(x, z) = (1 + x'z / s²)³,     s = 'auto' (MATLAB Cubic SVM)
//   fine-gaussian-svm    K(x, z) = exp(-|x - z|² / s²), s = sqrt(P) / 4 (MATLAB Fine Gaussian)
//   medium-gaussian-svm  as above,                      s = sqrt(P)     (MATLAB Medium Gaussian)
//   coarse-gaussian-svm  as above,                      s = 4 sqrt(P)   (MATLAB Coarse Gaussian)
// P = number of features. Parameters: `c` (box constraint, default 1) and `scale`: "auto",
// a positive number, or a multiple of sqrt(P) written "0.25sqrtP", "sqrtP", "4sqrtP"; and
// `probability` (true|false, default true: class probabilities as scores, see below).
//
// One-vs-one: for every pair of classes a < b present in the training set we train one
// two-class libsvm C-SVC on the samples of a (in row order) followed by those of b — the
// same sub-problem libsvm's own multi-class C-SVC solves — so each pair can have its own
// kernel scale, as MATLAB's 'auto' scale is chosen per binary learner. A pair's decision
// value f(x) = Σ coef_i K(sv_i, x) - rho votes for a when f > 0, else for b (libsvm's rule).
// The predicted class is the vote winner: the class with the most pairs won, ties to the
// lowest class index (libsvm's svm_predict rule). A single class in the training set is
// predicted for every sample and scores 1; classes absent from the training set score 0.
//
// Scores are class probabilities, as libsvm's `-b 1` gives them (svm_probability.h): each
// pair also fits Platt's sigmoid P(a | a or b) = 1 / (1 + exp(A f + B)) to the decision
// values of libsvm's 5-fold cross-validation on the pair's rows (the shuffle drawn from the
// fit's seed, so a seed gives the same model on any thread), and the pairwise probabilities
// of a sample are coupled into class probabilities (Wu, Lin & Weng 2004, method 2). They sum
// to 1 and, unlike vote shares, differ between samples whose votes tie, so margins rank. The
// vote winner is almost always the most probable class; where the two rules disagree,
// scores() still gives the probabilities, so the predicted class's margin
// (ml::confidence_of) is 0: the least sure. Parameter `probability` (default true): false
// skips the cross-validation (five more trainings per pair, see CLASSIFIERS.md for the cost)
// and scores are the vote shares (votes / number of pairs), as are those of a model saved
// before the sigmoids were kept (no probability_a/probability_b in its learners).
//
// Parameter `weights` (none|balanced, default none): balanced weights each class's box
// constraint by w_c = n / (k n_c) (n training rows, k classes present, n_c rows of class c),
// scikit-learn's class_weight='balanced'; a pair's rows get C w_a and C w_b (libsvm's
// weight_label/weight), so a rare class's errors cost more. The weights are saved in the
// model ("class_weights") with the parameter.
//
// Save/load keeps the standardiser, and per pair the kernel scale, rho, coefficients and
// support vectors (in standardised units), and the sigmoid's A and B when fitted, in the JSON;
// no libsvm model file is written.

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"
#include "tactile/ml/svm_probability.h"

namespace tactile::ml {

enum class SvmKernel { kLinear, kPolynomial, kGaussian };

// How the kernel scale s is chosen at fit time.
struct KernelScale {
  enum class Mode { kFixed, kAuto, kSqrtFeatures };
  Mode mode = Mode::kFixed;
  double value = 1.0;  // s for kFixed; the multiple of sqrt(P) for kSqrtFeatures
  // "auto" | "2.5" | "0.25sqrtP" | "sqrtP"; throws tactile::Error naming `where`.
  static KernelScale parse(const std::string& text, const std::string& where);
  std::string to_string() const;
};

// One binary learner of the one-vs-one scheme.
struct PairwiseSvm {
  int positive_class = 0;  // wins the vote when the decision value is > 0
  int negative_class = 1;
  double scale = 1.0;
  double rho = 0.0;
  Vector coefficients;  // y_i alpha_i per support vector
  // Its support vectors: rows of SupportVectorMachine::support_vectors(), which every pair
  // shares (a training row serves in up to k - 1 pairs). A linear learner has one: w, with
  // coefficient 1.
  std::vector<Eigen::Index> support;
  PlattSigmoid sigmoid;  // P(positive | f); fitted only with probability=true
};

// MATLAB's 'auto' kernel scale for one binary learner: up to 100 points drawn per class
// (without replacement, from `engine`), s = median over the drawn positive points of the
// distance to the nearest drawn negative point, times sqrt(n_neg/N_neg · n_pos/N_pos)^(1/P).
// When that is not a positive finite number (every positive point on a negative one) s = 1.
double auto_kernel_scale(const Matrix& positive, const Matrix& negative, std::mt19937_64& engine);

class SupportVectorMachine : public Classifier {
 public:
  // `preset` is one of svm_preset_names(); throws tactile::Error on an unknown preset,
  // unknown parameter key, c <= 0 or a bad scale.
  SupportVectorMachine(const std::string& preset, const Parameters& parameters);

  std::string name() const override { return preset_; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  // The vote winner of every row (not the argmax of scores(): see above).
  std::vector<int> predict(const Matrix& x) const override;
  Decisions decide(const Matrix& x) const override;
  // The next fit leaves out the Platt sigmoids (the votes, hence predict(), are the same).
  void skip_scores() override { skip_scores_ = true; }
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // Decision value of every pair, rows = samples, columns = learners() in order.
  Matrix decision_values(const Matrix& x) const;
  const std::vector<PairwiseSvm>& learners() const { return learners_; }
  // The distinct support vectors of every pair, standardised (the linear kernel: each pair's w).
  const Matrix& support_vectors() const { return support_vectors_; }
  // Whether scores() are probabilities (every learner has its sigmoid) or vote shares.
  bool has_probabilities() const { return probabilities_; }
  SvmKernel kernel() const { return kernel_; }
  int degree() const { return degree_; }
  // Per class, the factor of C the fit used (all 1 unless weights=balanced).
  const std::vector<double>& class_weights() const { return class_weights_; }

 private:
  std::vector<int> vote_winners(const Matrix& decision) const;
  Matrix vote_shares(const Matrix& decision) const;
  Matrix probabilities(const Matrix& decision) const;
  // K(a_i, b_j) for every row of a and of b, with kernel scale `scale`.
  Matrix kernel_matrix(const Matrix& a, const Matrix& b, double scale) const;
  // The kernel from the inner products `gram` (rows x columns) and both sides' squared norms.
  Matrix kernel_from_gram(const Matrix& gram, const Vector& row_norms, const Vector& column_norms,
                          double scale) const;

  std::string preset_;
  SvmKernel kernel_ = SvmKernel::kLinear;
  int degree_ = 1;
  double box_constraint_ = 1.0;
  KernelScale scale_;
  bool fit_probabilities_ = true;  // the `probability` parameter
  bool balanced_weights_ = false;  // the `weights` parameter: balanced or none
  bool skip_scores_ = false;       // skip_scores(): no sigmoids whatever `probability` says

  bool fitted_ = false;
  int class_count_ = 0;
  int only_class_ = -1;  // the single class seen in training, else -1
  Standardizer standardizer_;
  std::vector<PairwiseSvm> learners_;
  Matrix support_vectors_;             // rows that learners_' `support` indexes
  bool probabilities_ = false;         // every learner has its sigmoid
  std::vector<double> class_weights_;  // per class: C's factor in training (1 unless balanced)
};

std::vector<std::string> svm_preset_names();

// Registry factories, one per command-line name (they read and check the parameters).
std::unique_ptr<Classifier> make_linear_svm_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_quadratic_svm_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_cubic_svm_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_fine_gaussian_svm_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_medium_gaussian_svm_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_coarse_gaussian_svm_classifier(const Parameters& parameters);

// libsvm's own messages are kept off stdout (they would land in the middle of tables);
// its warnings that training stopped at the iteration limit are counted here instead, so
// a program can say so once. Counted over the whole process.
int64_t svm_iteration_limit_warnings();

}  // namespace tactile::ml
