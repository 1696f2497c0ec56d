#include "tactile/ml/svm.h"

#include <svm.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "libsvm_support.h"
#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"
#include "tactile/stats/statistics.h"

namespace tactile::ml {

namespace {

// Pair problems of long rows (many features) and up to this many rows get their kernel
// matrix precomputed: rows² svm_nodes of 16 bytes (3000 rows: 144 MB, freed after the pair
// is trained). With few features libsvm's own kernel (a short dot product) is cheaper
// than a lookup in a large table (measured: 5000 x 16 was 7x slower precomputed, 1000 x
// 1200 3.3x faster).
constexpr Eigen::Index kPrecomputedKernelRows = 3000;
constexpr Eigen::Index kPrecomputedKernelFeatures = 64;
// Training folds of long rows up to this many rows share one Gram matrix (rows² doubles:
// 4000 rows, 128 MB) from which every pair's kernel is read.
constexpr Eigen::Index kSharedGramRows = 4000;

struct Preset {
  const char* name;
  SvmKernel kernel;
  int degree;
  KernelScale scale;
};

const std::vector<Preset>& presets() {
  using Mode = KernelScale::Mode;
  static const std::vector<Preset> table = {
      {"linear-svm", SvmKernel::kLinear, 1, {Mode::kFixed, 1.0}},
      {"quadratic-svm", SvmKernel::kPolynomial, 2, {Mode::kAuto, 1.0}},
      {"cubic-svm", SvmKernel::kPolynomial, 3, {Mode::kAuto, 1.0}},
      {"fine-gaussian-svm", SvmKernel::kGaussian, 1, {Mode::kSqrtFeatures, 0.25}},
      {"medium-gaussian-svm", SvmKernel::kGaussian, 1, {Mode::kSqrtFeatures, 1.0}},
      {"coarse-gaussian-svm", SvmKernel::kGaussian, 1, {Mode::kSqrtFeatures, 4.0}},
  };
  return table;
}

const char* kernel_name(SvmKernel kernel) {
  switch (kernel) {
    case SvmKernel::kLinear:
      return "linear";
    case SvmKernel::kPolynomial:
      return "polynomial";
    case SvmKernel::kGaussian:
      return "gaussian";
  }
  return "linear";
}

// Shortest text that parses back to the same double.
std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

bool parse_positive(const std::string& text, double& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value) &&
         value > 0.0;
}

std::atomic<int64_t> iteration_limit_warnings{0};

// libsvm prints its progress to stdout through one global function pointer: progress is
// dropped, the iteration-limit warning counted.
void silence_libsvm() {
  static std::once_flag once;
  std::call_once(once, [] {
    svm_set_print_string_function([](const char* text) {
      if (std::strstr(text, "max number of iterations")) ++iteration_limit_warnings;
    });
  });
}

Matrix gather_rows(const Matrix& x, const std::vector<int64_t>& rows) {
  Matrix gathered(static_cast<Eigen::Index>(rows.size()), x.cols());
  for (size_t row = 0; row < rows.size(); ++row)
    gathered.row(static_cast<Eigen::Index>(row)) = x.row(rows[row]);
  return gathered;
}

// Up to `limit` rows drawn without replacement (a partial Fisher-Yates shuffle); all rows in
// order when there are no more than `limit`.
Matrix draw_rows(const Matrix& x, int64_t limit, std::mt19937_64& engine) {
  const int64_t count = x.rows();
  if (count <= limit) return x;
  std::vector<int64_t> order(static_cast<size_t>(count));
  for (int64_t row = 0; row < count; ++row) order[static_cast<size_t>(row)] = row;
  for (int64_t slot = 0; slot < limit; ++slot) {
    const auto pick =
        slot + static_cast<int64_t>(uniform_index(engine, static_cast<uint64_t>(count - slot)));
    std::swap(order[static_cast<size_t>(slot)], order[static_cast<size_t>(pick)]);
  }
  order.resize(static_cast<size_t>(limit));
  return gather_rows(x, order);
}

// scikit-learn's class_weight='balanced': w_c = n / (k n_c) over the k classes present in
// the training set; every weight 1 without balancing.
std::vector<double> balanced_class_weights(const std::vector<int64_t>& counts, bool balanced) {
  std::vector<double> weights(counts.size(), 1.0);
  if (!balanced) return weights;
  int64_t total = 0;
  int64_t present = 0;
  for (const int64_t count : counts) {
    total += count;
    if (count > 0) ++present;
  }
  for (size_t label = 0; label < counts.size(); ++label)
    if (counts[label] > 0)
      weights[label] = static_cast<double>(total) /
                       (static_cast<double>(present) * static_cast<double>(counts[label]));
  return weights;
}

}  // namespace

//---- Kernel scale --------------------------------------------------------------------------

KernelScale KernelScale::parse(const std::string& text, const std::string& where) {
  if (text == "auto") return {Mode::kAuto, 1.0};
  const std::string suffix = "sqrtP";
  KernelScale scale;
  std::string number = text;
  if (text.size() >= suffix.size() &&
      text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0) {
    scale.mode = Mode::kSqrtFeatures;
    number = text.substr(0, text.size() - suffix.size());
    if (number.empty()) number = "1";
  }
  if (!parse_positive(number, scale.value))
    throw Error(where,
                "scale=" + text + ": expected auto, a positive number or a multiple like 4sqrtP");
  return scale;
}

std::string KernelScale::to_string() const {
  switch (mode) {
    case Mode::kAuto:
      return "auto";
    case Mode::kSqrtFeatures:
      return (value == 1.0 ? std::string() : format_number(value)) + "sqrtP";
    case Mode::kFixed:
      break;
  }
  return format_number(value);
}

double auto_kernel_scale(const Matrix& positive, const Matrix& negative, std::mt19937_64& engine) {
  constexpr int64_t kPointsPerClass = 100;
  if (positive.rows() == 0 || negative.rows() == 0 || positive.cols() != negative.cols())
    throw Error("kernel scale", "needs points of both classes with the same features");
  const Matrix drawn_positive = draw_rows(positive, kPointsPerClass, engine);
  const Matrix drawn_negative = draw_rows(negative, kPointsPerClass, engine);
  std::vector<double> nearest(static_cast<size_t>(drawn_positive.rows()));
  for (Eigen::Index row = 0; row < drawn_positive.rows(); ++row)
    nearest[static_cast<size_t>(row)] = std::sqrt(
        (drawn_negative.rowwise() - drawn_positive.row(row)).rowwise().squaredNorm().minCoeff());
  // The drawn subset's nearest neighbours lie farther apart than the full set's; the factor
  // shrinks s by the sampled fraction's P-th root (MATLAB's heuristic, as exported).
  const double sampled_fraction =
      static_cast<double>(drawn_negative.rows()) / static_cast<double>(negative.rows()) *
      static_cast<double>(drawn_positive.rows()) / static_cast<double>(positive.rows());
  const double scale =
      stats::median(std::move(nearest)) *
      std::pow(std::sqrt(sampled_fraction), 1.0 / static_cast<double>(positive.cols()));
  return std::isfinite(scale) && scale > 0.0 ? scale : 1.0;
}

//---- Construction and parameters ---------------------------------------------------------------

std::vector<std::string> svm_preset_names() {
  std::vector<std::string> names;
  for (const Preset& preset : presets()) names.emplace_back(preset.name);
  return names;
}

SupportVectorMachine::SupportVectorMachine(const std::string& preset, const Parameters& parameters)
    : preset_(preset) {
  const auto found = std::find_if(presets().begin(), presets().end(), [&](const Preset& candidate) {
    return preset == candidate.name;
  });
  if (found == presets().end())
    throw Error(parameters.where(), "no SVM preset named '" + preset + "'");
  parameters.expect_only({"c", "scale", "probability", "weights"});
  kernel_ = found->kernel;
  degree_ = found->degree;
  scale_ = found->scale;
  box_constraint_ = parameters.number("c", 1.0);
  if (box_constraint_ <= 0.0)
    throw Error(parameters.where(), "c=" + format_number(box_constraint_) + ": must be positive");
  if (parameters.has("scale"))
    scale_ = KernelScale::parse(parameters.text("scale", ""), parameters.where());
  fit_probabilities_ = parameters.flag("probability", true);
  const std::string weights = parameters.text("weights", "none");
  if (weights != "none" && weights != "balanced")
    throw Error(parameters.where(), "weights=" + weights + ": expected none or balanced");
  balanced_weights_ = weights == "balanced";
}

Parameters SupportVectorMachine::parameters() const {
  Parameters parameters;
  parameters.set("c", format_number(box_constraint_));
  parameters.set("scale", scale_.to_string());
  parameters.set("probability", fit_probabilities_ ? "true" : "false");
  parameters.set("weights", balanced_weights_ ? "balanced" : "none");
  return parameters;
}

int64_t svm_iteration_limit_warnings() { return iteration_limit_warnings.load(); }

//---- Training ----------------------------------------------------------------------------------

void SupportVectorMachine::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                               uint64_t seed) {
  const std::vector<int64_t> counts = check_training_set(x, y, class_count, preset_);
  silence_libsvm();
  fitted_ = false;
  learners_.clear();
  support_vectors_ = Matrix();
  class_weights_ = balanced_class_weights(counts, balanced_weights_);
  probabilities_ = false;
  class_count_ = class_count;
  only_class_ = -1;
  standardizer_.fit(x);
  const Matrix z = standardizer_.transform(x);

  std::vector<std::vector<int64_t>> members(static_cast<size_t>(class_count));
  for (size_t row = 0; row < y.size(); ++row)
    members[static_cast<size_t>(y[row])].push_back(static_cast<int64_t>(row));
  std::vector<int> present;
  for (int label = 0; label < class_count; ++label)
    if (counts[static_cast<size_t>(label)] > 0) present.push_back(label);
  if (present.size() == 1) {
    only_class_ = present.front();
    fitted_ = true;
    return;
  }

  const Eigen::Index feature_count = z.cols();
  // Long rows: the training fold's Gram matrix z z' once, each pair's
  // precomputed kernel read from it, rather than a product per pair (each class takes part
  // in k - 1 pairs). 1000 x 1200 rows: the products were over half of a fit's time.
  const bool long_rows = feature_count >= kPrecomputedKernelFeatures;
  Matrix fold_gram;
  Vector fold_norms;
  if (long_rows && z.rows() <= kSharedGramRows) {
    fold_gram = z * z.transpose();
    fold_norms = z.rowwise().squaredNorm();
  }
  // The support vectors of every pair: training rows, each once (a linear kernel: each
  // pair's direction instead).
  std::vector<Eigen::Index> pool_place(static_cast<size_t>(z.rows()), -1);
  std::vector<int64_t> pool_rows;
  std::vector<Vector> directions;
  std::mt19937_64 engine(seed);
  for (size_t first = 0; first < present.size(); ++first) {
    for (size_t second = first + 1; second < present.size(); ++second) {
      // A fit of many classes is many learners (105 for Robovie's 15): a cancelled job stops
      // between two of them rather than after the last.
      if (cancel_requested()) throw Error(preset_, "cancelled");
      PairwiseSvm learner;
      learner.positive_class = present[first];
      learner.negative_class = present[second];
      // The sub-problem libsvm's multi-class C-SVC would solve: class a's rows, then b's.
      const auto& positive_rows = members[static_cast<size_t>(learner.positive_class)];
      const auto& negative_rows = members[static_cast<size_t>(learner.negative_class)];
      std::vector<int64_t> order = positive_rows;
      order.insert(order.end(), negative_rows.begin(), negative_rows.end());
      const auto positive_count = static_cast<Eigen::Index>(positive_rows.size());
      const auto rows = static_cast<Eigen::Index>(order.size());
      switch (scale_.mode) {
        case KernelScale::Mode::kFixed:
          learner.scale = scale_.value;
          break;
        case KernelScale::Mode::kSqrtFeatures:
          learner.scale = scale_.value * std::sqrt(static_cast<double>(feature_count));
          break;
        case KernelScale::Mode::kAuto:
          learner.scale = auto_kernel_scale(gather_rows(z, positive_rows),
                                            gather_rows(z, negative_rows), engine);
          break;
      }
      std::vector<double> targets(static_cast<size_t>(rows));
      for (Eigen::Index row = 0; row < rows; ++row)
        targets[static_cast<size_t>(row)] = row < positive_count ? 1.0 : -1.0;
      // Small enough: the whole kernel matrix at once (one matrix product), handed to
      // libsvm as a precomputed kernel, so its solver never evaluates a kernel itself.
      const bool precomputed = rows <= kPrecomputedKernelRows && long_rows;
      // The pair's rows themselves, unless the kernel comes from the fold's Gram matrix
      // (then only the support vectors are copied, from z).
      const bool shared_gram = precomputed && fold_gram.size() > 0;
      const Matrix pair = shared_gram ? Matrix() : gather_rows(z, order);
      std::vector<svm_node> nodes;
      std::vector<svm_node*> row_nodes(static_cast<size_t>(rows));
      if (precomputed) {
        Matrix kernel;
        if (shared_gram) {
          const Vector norms = fold_norms(order);
          kernel = kernel_from_gram(fold_gram(order, order), norms, norms, learner.scale);
        } else {
          kernel = kernel_matrix(pair, pair, learner.scale);
        }
        const Eigen::Index width = rows + 2;  // serial number, the row, terminator
        nodes.resize(static_cast<size_t>(rows * width));
        for (Eigen::Index row = 0; row < rows; ++row) {
          svm_node* node = &nodes[static_cast<size_t>(row * width)];
          row_nodes[static_cast<size_t>(row)] = node;
          node[0] = {0, static_cast<double>(row + 1)};
          for (Eigen::Index column = 0; column < rows; ++column)
            node[column + 1] = {static_cast<int>(column + 1), kernel(row, column)};
          node[rows + 1] = {-1, 0.0};
        }
      } else {
        nodes.resize(static_cast<size_t>(rows * (feature_count + 1)));
        for (Eigen::Index row = 0; row < rows; ++row) {
          svm_node* node = &nodes[static_cast<size_t>(row * (feature_count + 1))];
          row_nodes[static_cast<size_t>(row)] = node;
          for (Eigen::Index column = 0; column < feature_count; ++column)
            node[column] = {static_cast<int>(column + 1), pair(row, column)};
          node[feature_count] = {-1, 0.0};
        }
      }
      svm_problem problem{static_cast<int>(rows), targets.data(), row_nodes.data()};

      // Kernels in libsvm's form (gamma u'v + coef0)^degree and exp(-gamma |u - v|²) with
      // gamma = 1/s²; the linear kernel is the degree-1 polynomial without offset.
      svm_parameter parameter{};
      parameter.svm_type = C_SVC;
      parameter.kernel_type = precomputed                       ? PRECOMPUTED
                              : kernel_ == SvmKernel::kGaussian ? RBF
                                                                : POLY;
      parameter.degree = degree_;
      parameter.gamma = 1.0 / (learner.scale * learner.scale);
      parameter.coef0 = kernel_ == SvmKernel::kPolynomial ? 1.0 : 0.0;
      parameter.cache_size = 200.0;  // MB, as scikit-learn's SVC
      parameter.eps = 1e-3;
      parameter.C = box_constraint_;
      parameter.nu = 0.5;
      parameter.p = 0.1;
      parameter.shrinking = 1;
      parameter.probability = 0;
      // Per-class C: C w_a for the pair's positive rows, C w_b for its negative ones (libsvm's
      // multi-class C-SVC gives each pair its two classes' weights the same way).
      int weight_labels[2] = {1, -1};
      double pair_weights[2] = {class_weights_[static_cast<size_t>(learner.positive_class)],
                                class_weights_[static_cast<size_t>(learner.negative_class)]};
      if (balanced_weights_) {
        parameter.nr_weight = 2;
        parameter.weight_label = weight_labels;
        parameter.weight = pair_weights;
      }
      if (const char* problem_text = svm_check_parameter(&problem, &parameter))
        throw Error(preset_, std::string("libsvm: ") + problem_text);
      const LibsvmModel model(svm_train(&problem, &parameter));
      if (!model) throw Error(preset_, "libsvm returned no model");
      // The sigmoid's own draws, apart from the kernel scales' so that they stay as they were.
      if (fit_probabilities_ && !skip_scores_)
        learner.sigmoid = cross_validated_sigmoid(
            problem, parameter, std::mt19937_64(derive_seed(seed, learners_.size())), preset_);

      // libsvm's decision value favours its first label; make f > 0 mean the positive class.
      // Its support vectors are the pair's rows sv_indices names (1-based), kept once for
      // every pair: 105 pairs of Robovie's 37,401 features held their own copies, 0.8 GB.
      const double sign = model->label[0] == 1 ? 1.0 : -1.0;
      learner.rho = sign * model->rho[0];
      learner.coefficients.resize(model->l);
      std::vector<int64_t> rows_of_vectors(static_cast<size_t>(model->l));
      for (int vector = 0; vector < model->l; ++vector) {
        learner.coefficients(vector) = sign * model->sv_coef[0][vector];
        rows_of_vectors[static_cast<size_t>(vector)] =
            order[static_cast<size_t>(model->sv_indices[vector] - 1)];
      }
      if (kernel_ == SvmKernel::kLinear) {
        // A linear learner is one direction, w = Σ coef_i sv_i: kept as its only support
        // vector with coefficient 1, the decision z·w - rho is the same sum, at one dot
        // product per learner.
        Vector direction = Vector::Zero(feature_count);
        for (int vector = 0; vector < model->l; ++vector)
          direction += learner.coefficients(vector) *
                       z.row(rows_of_vectors[static_cast<size_t>(vector)]).transpose();
        learner.support = {static_cast<Eigen::Index>(directions.size())};
        learner.coefficients = Vector::Ones(1);
        directions.push_back(std::move(direction));
      } else {
        for (const int64_t row : rows_of_vectors) {
          Eigen::Index& place = pool_place[static_cast<size_t>(row)];
          if (place < 0) {
            place = static_cast<Eigen::Index>(pool_rows.size());
            pool_rows.push_back(row);
          }
          learner.support.push_back(place);
        }
      }
      learners_.push_back(std::move(learner));
    }
  }
  if (kernel_ == SvmKernel::kLinear) {
    support_vectors_.resize(static_cast<Eigen::Index>(directions.size()), feature_count);
    for (size_t at = 0; at < directions.size(); ++at)
      support_vectors_.row(static_cast<Eigen::Index>(at)) = directions[at].transpose();
  } else {
    support_vectors_ = gather_rows(z, pool_rows);
  }
  probabilities_ = fit_probabilities_ && !skip_scores_;
  fitted_ = true;
}

//---- Prediction --------------------------------------------------------------------------------

Matrix SupportVectorMachine::kernel_matrix(const Matrix& a, const Matrix& b, double scale) const {
  return kernel_from_gram(a * b.transpose(), a.rowwise().squaredNorm(), b.rowwise().squaredNorm(),
                          scale);
}

Matrix SupportVectorMachine::kernel_from_gram(const Matrix& gram, const Vector& row_norms,
                                              const Vector& column_norms, double scale) const {
  const double gamma = 1.0 / (scale * scale);
  switch (kernel_) {
    case SvmKernel::kLinear:
      return gamma * gram;
    case SvmKernel::kPolynomial: {
      const Eigen::ArrayXXd base = gamma * gram.array() + 1.0;
      Eigen::ArrayXXd power = base;
      for (int order = 1; order < degree_; ++order) power *= base;
      return power.matrix();
    }
    case SvmKernel::kGaussian: {
      const Eigen::ArrayXXd squared_distance =
          ((-2.0 * gram).colwise() + row_norms).rowwise() + column_norms.transpose();
      return (-gamma * squared_distance.max(0.0)).exp().matrix();
    }
  }
  return gram;
}

Matrix SupportVectorMachine::decision_values(const Matrix& x) const {
  check_fitted(fitted_, preset_);
  check_query(x, standardizer_.mean.size(), preset_);
  const Matrix z = standardizer_.transform(x);
  Matrix decision(x.rows(), static_cast<Eigen::Index>(learners_.size()));
  // A training row is a support vector of up to k - 1 pairs, so one product with the shared
  // support vectors serves every learner.
  const Matrix gram = z * support_vectors_.transpose();
  const Vector query_norms = z.rowwise().squaredNorm();
  const Vector support_norms = support_vectors_.rowwise().squaredNorm();
  for (size_t index = 0; index < learners_.size(); ++index) {
    const PairwiseSvm& learner = learners_[index];
    decision.col(static_cast<Eigen::Index>(index)) =
        (kernel_from_gram(gram(Eigen::all, learner.support), query_norms,
                          support_norms(learner.support), learner.scale) *
         learner.coefficients)
            .array() -
        learner.rho;
  }
  return decision;
}

std::vector<int> SupportVectorMachine::vote_winners(const Matrix& decision) const {
  std::vector<int> winners(static_cast<size_t>(decision.rows()), only_class_);
  if (only_class_ >= 0) return winners;
  const Matrix votes = vote_shares(decision);
  for (Eigen::Index row = 0; row < votes.rows(); ++row) {
    Eigen::Index best = 0;
    votes.row(row).maxCoeff(&best);  // the first of equal counts: the lowest class index
    winners[static_cast<size_t>(row)] = static_cast<int>(best);
  }
  return winners;
}

Matrix SupportVectorMachine::vote_shares(const Matrix& decision) const {
  Matrix votes = Matrix::Zero(decision.rows(), class_count_);
  if (only_class_ >= 0) {
    votes.col(only_class_).setOnes();
    return votes;
  }
  for (size_t index = 0; index < learners_.size(); ++index) {
    const PairwiseSvm& learner = learners_[index];
    for (Eigen::Index row = 0; row < decision.rows(); ++row) {
      const bool positive = decision(row, static_cast<Eigen::Index>(index)) > 0.0;
      votes(row, positive ? learner.positive_class : learner.negative_class) += 1.0;
    }
  }
  return votes / static_cast<double>(learners_.size());
}

Matrix SupportVectorMachine::probabilities(const Matrix& decision) const {
  if (only_class_ >= 0 || !probabilities_) return vote_shares(decision);
  // The classes the learners know, each with its place in the coupling.
  std::vector<int> classes;
  for (const PairwiseSvm& learner : learners_) {
    classes.push_back(learner.positive_class);
    classes.push_back(learner.negative_class);
  }
  std::sort(classes.begin(), classes.end());
  classes.erase(std::unique(classes.begin(), classes.end()), classes.end());
  const auto place = [&](int label) {
    return static_cast<Eigen::Index>(std::lower_bound(classes.begin(), classes.end(), label) -
                                     classes.begin());
  };
  const auto known = static_cast<Eigen::Index>(classes.size());
  Matrix result = Matrix::Zero(decision.rows(), class_count_);
  Matrix pairwise = Matrix::Constant(known, known, 0.5);  // a pair without a learner: even
  for (Eigen::Index row = 0; row < decision.rows(); ++row) {
    for (size_t index = 0; index < learners_.size(); ++index) {
      const PairwiseSvm& learner = learners_[index];
      const double positive =
          learner.sigmoid.probability(decision(row, static_cast<Eigen::Index>(index)));
      pairwise(place(learner.positive_class), place(learner.negative_class)) = positive;
      pairwise(place(learner.negative_class), place(learner.positive_class)) = 1.0 - positive;
    }
    const Vector coupled = couple_pairwise(pairwise);
    for (Eigen::Index k = 0; k < known; ++k)
      result(row, classes[static_cast<size_t>(k)]) = coupled(k);
  }
  return result;
}

Matrix SupportVectorMachine::scores(const Matrix& x) const {
  return probabilities(decision_values(x));
}

std::vector<int> SupportVectorMachine::predict(const Matrix& x) const {
  return vote_winners(decision_values(x));
}

Classifier::Decisions SupportVectorMachine::decide(const Matrix& x) const {
  const Matrix decision = decision_values(x);
  return {vote_winners(decision), probabilities(decision)};
}

//---- Save and load -----------------------------------------------------------------------------

nlohmann::json SupportVectorMachine::save() const {
  if (!fitted_) throw Error(preset_, "save() before fit()");
  nlohmann::json learners = nlohmann::json::array();
  for (const PairwiseSvm& learner : learners_) {
    nlohmann::json saved = {{"positive_class", learner.positive_class},
                            {"negative_class", learner.negative_class},
                            {"scale", learner.scale},
                            {"rho", learner.rho},
                            {"coefficients", std::vector<double>(learner.coefficients.data(),
                                                                 learner.coefficients.data() +
                                                                     learner.coefficients.size())},
                            {"support", learner.support}};
    if (probabilities_) {
      saved["probability_a"] = learner.sigmoid.a;
      saved["probability_b"] = learner.sigmoid.b;
    }
    learners.push_back(std::move(saved));
  }
  nlohmann::json saved = {
      {"kernel", kernel_name(kernel_)},       {"degree", degree_},
      {"class_count", class_count_},          {"only_class", only_class_},
      {"standardizer", standardizer_.save()}, {"learners", std::move(learners)}};
  nlohmann::json support_vectors = nlohmann::json::array();
  for (Eigen::Index row = 0; row < support_vectors_.rows(); ++row) {
    const Vector vector = support_vectors_.row(row).transpose();
    support_vectors.push_back(std::vector<double>(vector.data(), vector.data() + vector.size()));
  }
  saved["support_vectors"] = std::move(support_vectors);
  if (balanced_weights_) saved["class_weights"] = class_weights_;
  return saved;
}

void SupportVectorMachine::load(const nlohmann::json& model) {
  const std::string where = preset_ + " model";
  fitted_ = false;
  try {
    if (model.at("kernel").get<std::string>() != kernel_name(kernel_) ||
        model.at("degree").get<int>() != degree_)
      throw Error(where, "saved with another kernel than " + preset_ + "'s");
    const int class_count = model.at("class_count").get<int>();
    const int only_class = model.at("only_class").get<int>();
    if (class_count < 1 || only_class < -1 || only_class >= class_count)
      throw Error(where, "bad class_count or only_class");
    Standardizer standardizer;
    standardizer.load(model.at("standardizer"));
    const Eigen::Index feature_count = standardizer.mean.size();
    std::vector<PairwiseSvm> learners;
    // The rows of the support vectors where the document holds them, read straight into the
    // matrix below (a copy in between was another 31 MB for Robovie's linear SVM).
    std::vector<const nlohmann::json*> vectors;
    if (model.contains("support_vectors"))
      for (const nlohmann::json& row : model.at("support_vectors")) vectors.push_back(&row);
    size_t with_sigmoid = 0;
    for (const auto& saved : model.at("learners")) {
      PairwiseSvm learner;
      learner.positive_class = saved.at("positive_class").get<int>();
      learner.negative_class = saved.at("negative_class").get<int>();
      learner.scale = saved.at("scale").get<double>();
      learner.rho = saved.at("rho").get<double>();
      const auto coefficients = saved.at("coefficients").get<std::vector<double>>();
      if (learner.positive_class < 0 || learner.positive_class >= class_count ||
          learner.negative_class < 0 || learner.negative_class >= class_count)
        throw Error(where, "learner class out of range");
      if (!std::isfinite(learner.scale) || learner.scale <= 0.0 || !std::isfinite(learner.rho))
        throw Error(where, "learner scale or rho is not a positive finite number");
      learner.coefficients = Eigen::Map<const Vector>(
          coefficients.data(), static_cast<Eigen::Index>(coefficients.size()));
      if (!learner.coefficients.allFinite()) throw Error(where, "non-finite coefficient");
      if (saved.contains("support_vectors")) {
        // A model saved before the pairs shared their support vectors: each pair's own.
        for (const nlohmann::json& row : saved.at("support_vectors")) {
          learner.support.push_back(static_cast<Eigen::Index>(vectors.size()));
          vectors.push_back(&row);
        }
      } else {
        for (const int64_t row : saved.at("support").get<std::vector<int64_t>>())
          learner.support.push_back(static_cast<Eigen::Index>(row));
      }
      if (learner.coefficients.size() != static_cast<Eigen::Index>(learner.support.size()))
        throw Error(where, "coefficient and support vector counts differ");
      // A model saved before the sigmoids were kept has none: its scores are vote shares.
      if (saved.contains("probability_a") || saved.contains("probability_b")) {
        learner.sigmoid = {saved.at("probability_a").get<double>(),
                           saved.at("probability_b").get<double>()};
        if (!std::isfinite(learner.sigmoid.a) || !std::isfinite(learner.sigmoid.b))
          throw Error(where, "non-finite probability_a or probability_b");
        ++with_sigmoid;
      }
      learners.push_back(std::move(learner));
    }
    if (only_class < 0 && learners.empty()) throw Error(where, "no learners");
    Matrix support_vectors(static_cast<Eigen::Index>(vectors.size()), feature_count);
    for (size_t row = 0; row < vectors.size(); ++row) {
      const nlohmann::json& values = *vectors[row];
      if (!values.is_array() || static_cast<Eigen::Index>(values.size()) != feature_count)
        throw Error(where, "support vector " + std::to_string(row) + " has " +
                               std::to_string(values.size()) + " values, expected " +
                               std::to_string(feature_count));
      for (Eigen::Index column = 0; column < feature_count; ++column)
        support_vectors(static_cast<Eigen::Index>(row), column) =
            values[static_cast<size_t>(column)].get<double>();
    }
    if (!support_vectors.allFinite()) throw Error(where, "non-finite support vector");
    for (const PairwiseSvm& learner : learners)
      for (const Eigen::Index row : learner.support)
        if (row < 0 || row >= support_vectors.rows())
          throw Error(where, "a learner names support vector " + std::to_string(row) + " of " +
                                 std::to_string(support_vectors.rows()));
    if (with_sigmoid != 0 && with_sigmoid != learners.size())
      throw Error(where, "some learners have a probability sigmoid and some do not");
    // The weights only shaped the training; kept for the record (a model saved before they
    // existed has none: every weight 1).
    std::vector<double> class_weights(static_cast<size_t>(class_count), 1.0);
    if (model.contains("class_weights")) {
      class_weights = model.at("class_weights").get<std::vector<double>>();
      if (class_weights.size() != static_cast<size_t>(class_count))
        throw Error(where, "class_weights has " + std::to_string(class_weights.size()) +
                               " values, expected " + std::to_string(class_count));
      for (const double weight : class_weights)
        if (!std::isfinite(weight) || weight <= 0.0)
          throw Error(where, "class_weights: not a positive finite number");
    }
    class_count_ = class_count;
    only_class_ = only_class;
    class_weights_ = std::move(class_weights);
    standardizer_ = std::move(standardizer);
    learners_ = std::move(learners);
    support_vectors_ = std::move(support_vectors);
    probabilities_ = with_sigmoid > 0;
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  fitted_ = true;
}

//---- Registry factories ------------------------------------------------------------------------

std::unique_ptr<Classifier> make_linear_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("linear-svm", parameters);
}
std::unique_ptr<Classifier> make_quadratic_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("quadratic-svm", parameters);
}
std::unique_ptr<Classifier> make_cubic_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("cubic-svm", parameters);
}
std::unique_ptr<Classifier> make_fine_gaussian_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("fine-gaussian-svm", parameters);
}
std::unique_ptr<Classifier> make_medium_gaussian_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("medium-gaussian-svm", parameters);
}
std::unique_ptr<Classifier> make_coarse_gaussian_svm_classifier(const Parameters& parameters) {
  return std::make_unique<SupportVectorMachine>("coarse-gaussian-svm", parameters);
}

}  // namespace tactile::ml
