#include "tactile/ml/em.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "probabilistic_support.h"
#include "tactile/error.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A component whose summed responsibility is below this holds no sample any more.
constexpr double kEmptyComponent = 1e-10;

std::string covariance_name(MixtureCovariance covariance) {
  return covariance == MixtureCovariance::kFull ? "full" : "diagonal";
}

Vector squared_distances(const Matrix& x, const Vector& centre) {
  return (x.rowwise() - centre.transpose()).rowwise().squaredNorm();
}

// k-means++ seeding (Arthur & Vassilvitskii): the first centre uniformly, each next one
// with probability proportional to the squared distance to the nearest chosen centre. One
// uniform draw per centre, so the random stream does not depend on the data's duplicates.
Matrix seed_centres(const Matrix& x, int count, std::mt19937_64& random) {
  const Eigen::Index rows = x.rows();
  auto index_of_draw = [rows](double draw) {
    return std::min(static_cast<Eigen::Index>(draw * static_cast<double>(rows)), rows - 1);
  };
  Matrix centres(count, x.cols());
  centres.row(0) = x.row(index_of_draw(uniform01(random)));
  Vector nearest = squared_distances(x, centres.row(0).transpose());
  for (int centre = 1; centre < count; ++centre) {
    const double draw = uniform01(random);
    const double total = nearest.sum();
    Eigen::Index chosen = index_of_draw(draw);
    if (total > 0.0) {
      const double target = draw * total;
      double cumulative = 0.0;
      for (Eigen::Index row = 0; row < rows; ++row) {
        if (nearest(row) <= 0.0) continue;
        chosen = row;
        cumulative += nearest(row);
        if (cumulative > target) break;
      }
    }
    centres.row(centre) = x.row(chosen);
    nearest = nearest.cwiseMin(squared_distances(x, centres.row(centre).transpose()));
  }
  return centres;
}

// Hard responsibilities: each sample wholly to its nearest centre (lowest index on ties).
Matrix nearest_centre_responsibilities(const Matrix& x, const Matrix& centres) {
  Matrix distances(x.rows(), centres.rows());
  for (Eigen::Index centre = 0; centre < centres.rows(); ++centre)
    distances.col(centre) = squared_distances(x, centres.row(centre).transpose());
  Matrix responsibilities = Matrix::Zero(x.rows(), centres.rows());
  for (Eigen::Index row = 0; row < x.rows(); ++row) {
    Eigen::Index best = 0;
    distances.row(row).minCoeff(&best);
    responsibilities(row, best) = 1.0;
  }
  return responsibilities;
}

// M-step: weights, means and (floored) covariances from the responsibilities. An empty
// component keeps its previous mean, takes the data's variance, and weight 0.
void maximise(const Matrix& x, const Matrix& responsibilities, const MixtureOptions& options,
              const Vector& data_variance, GaussianMixture& model) {
  const Eigen::Index components = responsibilities.cols();
  const Vector mass = responsibilities.colwise().sum().transpose();
  model.weights = mass / static_cast<double>(x.rows());
  if (options.covariance == MixtureCovariance::kDiagonal)
    model.variances.resize(components, x.cols());
  else
    model.full.resize(static_cast<size_t>(components));
  for (Eigen::Index k = 0; k < components; ++k) {
    const bool empty = mass(k) < kEmptyComponent;
    if (empty) {
      model.weights(k) = 0.0;
    } else {
      model.means.row(k) = (responsibilities.col(k).transpose() * x) / mass(k);
    }
    const Matrix centred = x.rowwise() - model.means.row(k);
    if (options.covariance == MixtureCovariance::kDiagonal) {
      const Vector variance =
          empty ? data_variance
                : Vector((centred.array().square().colwise() * responsibilities.col(k).array())
                             .colwise()
                             .sum()
                             .transpose() /
                         mass(k));
      model.variances.row(k) = variance.cwiseMax(options.variance_floor).transpose();
    } else {
      const Matrix covariance =
          empty ? Matrix(data_variance.asDiagonal())
                : Matrix(centred.transpose() * responsibilities.col(k).asDiagonal() * centred /
                         mass(k));
      model.full[static_cast<size_t>(k)].set(model.means.row(k).transpose(), covariance,
                                             options.variance_floor);
    }
  }
  model.weights /= model.weights.sum();
}

void check_options(const MixtureOptions& options) {
  const std::string where = "em";
  if (options.components < 1) throw Error(where, "clusters must be at least 1");
  if (options.restarts < 1) throw Error(where, "restarts must be at least 1");
  if (options.max_iterations < 1) throw Error(where, "iterations must be at least 1");
  if (!(options.tolerance >= 0.0)) throw Error(where, "tolerance must be zero or more");
  if (!(options.variance_floor > 0.0))
    throw Error(where, "variance_floor must be greater than zero");
}

void check_fit(const Matrix& x, const MixtureOptions& options) {
  check_options(options);
  if (x.rows() == 0) throw Error("em", "no samples");
  check_query(x, x.cols(), "em");
  if (x.rows() < options.components)
    throw Error("em", std::to_string(x.rows()) + " samples cannot fill " +
                          std::to_string(options.components) + " clusters");
}

// EM from the given first responsibilities until the relative gain falls below the
// tolerance (spec §1.16) or the iterations run out; `model` holds the last M-step.
void climb(const Matrix& x, Matrix responsibilities, const MixtureOptions& options,
           GaussianMixture& model) {
  const Vector data_mean = x.colwise().mean().transpose();
  const Vector data_variance =
      ((x.rowwise() - data_mean.transpose()).array().square().colwise().sum() /
       static_cast<double>(x.rows()))
          .transpose()
          .cwiseMax(options.variance_floor);
  double previous = kNegativeInfinity;
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    maximise(x, responsibilities, options, data_variance, model);
    const Matrix joint = model.log_joint(x);
    const Vector normaliser = support::log_sum_exp_rows(joint);
    model.log_likelihood = normaliser.sum();
    model.iterations = iteration;
    responsibilities = (joint.colwise() - normaliser).array().exp();
    if (iteration > 1 && model.log_likelihood - previous < options.tolerance * std::abs(previous))
      break;
    previous = model.log_likelihood;
  }
}

}  // namespace

//---- mixture --------------------------------------------------------------------------------

Matrix GaussianMixture::log_joint(const Matrix& x) const {
  const Eigen::Index count = weights.size();
  Matrix result(x.rows(), count);
  const double log_two_pi = std::log(2.0 * std::numbers::pi);
  for (Eigen::Index k = 0; k < count; ++k) {
    if (weights(k) <= 0.0) {
      result.col(k).setConstant(kNegativeInfinity);
      continue;
    }
    Vector log_density;
    if (covariance == MixtureCovariance::kDiagonal) {
      // ln N(x; μ, diag σ²) = -½ [Σ_j (x_j - μ_j)² / σ²_j + Σ_j ln σ²_j + d ln 2π].
      const double constant =
          variances.row(k).array().log().sum() + static_cast<double>(x.cols()) * log_two_pi;
      log_density =
          -0.5 *
          (((x.rowwise() - means.row(k)).array().square().rowwise() / variances.row(k).array())
               .rowwise()
               .sum() +
           constant);
    } else {
      log_density = full[static_cast<size_t>(k)].log_density(x);
    }
    result.col(k) = log_density.array() + std::log(weights(k));
  }
  return result;
}

Matrix GaussianMixture::responsibilities(const Matrix& x) const {
  return support::normalise_log_rows(log_joint(x));
}

std::vector<int> GaussianMixture::assign(const Matrix& x) const {
  const Matrix joint = log_joint(x);
  std::vector<int> clusters(static_cast<size_t>(x.rows()), 0);
  for (Eigen::Index row = 0; row < x.rows(); ++row) {
    Eigen::Index best = 0;
    joint.row(row).maxCoeff(&best);
    clusters[static_cast<size_t>(row)] = static_cast<int>(best);
  }
  return clusters;
}

nlohmann::json GaussianMixture::save() const {
  nlohmann::json model = {{"covariance", covariance_name(covariance)},
                          {"weights", support::vector_to_json(weights)},
                          {"means", support::matrix_to_json(means)},
                          {"log_likelihood", log_likelihood},
                          {"iterations", iterations}};
  if (covariance == MixtureCovariance::kDiagonal) {
    model["variances"] = support::matrix_to_json(variances);
  } else {
    nlohmann::json components = nlohmann::json::array();
    for (const GaussianDensity& density : full) components.push_back(density.save());
    model["components"] = components;
  }
  return model;
}

void GaussianMixture::load(const nlohmann::json& model, const std::string& where) {
  try {
    const std::string kind = model.at("covariance").get<std::string>();
    if (kind != "diagonal" && kind != "full")
      throw Error(where, "covariance '" + kind + "' unknown");
    covariance = kind == "full" ? MixtureCovariance::kFull : MixtureCovariance::kDiagonal;
    weights = support::vector_from_json(model.at("weights"), where + " weights");
    means = support::matrix_from_json(model.at("means"), where + " means");
    log_likelihood = model.at("log_likelihood").get<double>();
    iterations = model.at("iterations").get<int>();
    if (means.rows() != weights.size()) throw Error(where, "weights and means differ in count");
    if (covariance == MixtureCovariance::kDiagonal) {
      variances = support::matrix_from_json(model.at("variances"), where + " variances");
      if (variances.rows() != means.rows() || variances.cols() != means.cols() ||
          (variances.array() <= 0.0).any())
        throw Error(where, "variances do not match the means or are not positive");
    } else {
      full.clear();
      full.resize(static_cast<size_t>(weights.size()));
      const nlohmann::json& components = model.at("components");
      if (static_cast<Eigen::Index>(components.size()) != weights.size())
        throw Error(where, "components and weights differ in count");
      for (size_t k = 0; k < components.size(); ++k)
        full[k].load(components[k], where + " component " + std::to_string(k));
    }
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

GaussianMixture fit_gaussian_mixture(const Matrix& x, const MixtureOptions& options,
                                     uint64_t seed) {
  check_fit(x, options);
  std::mt19937_64 random(seed);
  GaussianMixture best;
  bool have_best = false;
  for (int restart = 0; restart < options.restarts; ++restart) {
    GaussianMixture model;
    model.covariance = options.covariance;
    model.means = seed_centres(x, options.components, random);
    climb(x, nearest_centre_responsibilities(x, model.means), options, model);
    if (!std::isfinite(model.log_likelihood)) continue;
    if (!have_best || model.log_likelihood > best.log_likelihood) {
      best = std::move(model);
      have_best = true;
    }
  }
  if (!have_best) throw Error("em", "every restart ended with a non-finite log-likelihood");
  return best;
}

GaussianMixture fit_gaussian_mixture_from(const Matrix& x, const std::vector<int>& groups,
                                          const MixtureOptions& options) {
  check_fit(x, options);
  if (groups.size() != static_cast<size_t>(x.rows()))
    throw Error("em", std::to_string(groups.size()) + " starting groups for " +
                          std::to_string(x.rows()) + " samples");
  Matrix responsibilities = Matrix::Zero(x.rows(), options.components);
  for (size_t row = 0; row < groups.size(); ++row) {
    if (groups[row] < 0 || groups[row] >= options.components)
      throw Error("em", "sample " + std::to_string(row) + " starts in group " +
                            std::to_string(groups[row]) + ", not one of the " +
                            std::to_string(options.components) + " clusters");
    responsibilities(static_cast<Eigen::Index>(row), groups[row]) = 1.0;
  }
  GaussianMixture model;
  model.covariance = options.covariance;
  model.means = Matrix::Zero(options.components, x.cols());
  climb(x, std::move(responsibilities), options, model);
  if (!std::isfinite(model.log_likelihood))
    throw Error("em", "the fit from the given groups ended with a non-finite log-likelihood");
  return model;
}

//---- classes to clusters --------------------------------------------------------------------

std::vector<int> minimum_cost_assignment(const Matrix& cost) {
  const Eigen::Index rows = cost.rows();
  const Eigen::Index columns = cost.cols();
  if (rows > columns) throw Error("assignment", "more rows than columns");
  // Hungarian method with row and column potentials (1-based; column 0 is a sentinel).
  std::vector<double> row_potential(static_cast<size_t>(rows + 1), 0.0);
  std::vector<double> column_potential(static_cast<size_t>(columns + 1), 0.0);
  std::vector<Eigen::Index> owner(static_cast<size_t>(columns + 1), 0);  // row holding a column
  std::vector<Eigen::Index> previous(static_cast<size_t>(columns + 1), 0);
  for (Eigen::Index row = 1; row <= rows; ++row) {
    owner[0] = row;
    Eigen::Index column = 0;
    std::vector<double> slack(static_cast<size_t>(columns + 1), kInfinity);
    std::vector<bool> visited(static_cast<size_t>(columns + 1), false);
    do {
      visited[static_cast<size_t>(column)] = true;
      const Eigen::Index current_row = owner[static_cast<size_t>(column)];
      double delta = kInfinity;
      Eigen::Index next_column = 0;
      for (Eigen::Index candidate = 1; candidate <= columns; ++candidate) {
        if (visited[static_cast<size_t>(candidate)]) continue;
        const double reduced = cost(current_row - 1, candidate - 1) -
                               row_potential[static_cast<size_t>(current_row)] -
                               column_potential[static_cast<size_t>(candidate)];
        if (reduced < slack[static_cast<size_t>(candidate)]) {
          slack[static_cast<size_t>(candidate)] = reduced;
          previous[static_cast<size_t>(candidate)] = column;
        }
        if (slack[static_cast<size_t>(candidate)] < delta) {
          delta = slack[static_cast<size_t>(candidate)];
          next_column = candidate;
        }
      }
      for (Eigen::Index candidate = 0; candidate <= columns; ++candidate) {
        if (visited[static_cast<size_t>(candidate)]) {
          row_potential[static_cast<size_t>(owner[static_cast<size_t>(candidate)])] += delta;
          column_potential[static_cast<size_t>(candidate)] -= delta;
        } else {
          slack[static_cast<size_t>(candidate)] -= delta;
        }
      }
      column = next_column;
    } while (owner[static_cast<size_t>(column)] != 0);
    // Flip the augmenting path back to the sentinel.
    do {
      const Eigen::Index before = previous[static_cast<size_t>(column)];
      owner[static_cast<size_t>(column)] = owner[static_cast<size_t>(before)];
      column = before;
    } while (column != 0);
  }
  std::vector<int> assignment(static_cast<size_t>(rows), -1);
  for (Eigen::Index column = 1; column <= columns; ++column)
    if (owner[static_cast<size_t>(column)] != 0)
      assignment[static_cast<size_t>(owner[static_cast<size_t>(column)] - 1)] =
          static_cast<int>(column - 1);
  return assignment;
}

std::vector<int> map_clusters_to_classes(const std::vector<int>& clusters,
                                         const std::vector<int>& classes, int cluster_count,
                                         int class_count, ClusterMapping mapping) {
  if (clusters.size() != classes.size()) throw Error("em", "clusters and classes differ in count");
  Eigen::MatrixXi counts = Eigen::MatrixXi::Zero(cluster_count, class_count);
  for (size_t row = 0; row < clusters.size(); ++row) {
    if (clusters[row] < 0 || clusters[row] >= cluster_count || classes[row] < 0 ||
        classes[row] >= class_count)
      throw Error("em", "row " + std::to_string(row) + " has a cluster or class out of range");
    ++counts(clusters[row], classes[row]);
  }
  std::vector<int> cluster_classes(static_cast<size_t>(cluster_count), kUnknownClass);
  if (mapping == ClusterMapping::kMajority) {
    for (int cluster = 0; cluster < cluster_count; ++cluster) {
      if (counts.row(cluster).sum() == 0) continue;  // won no sample: unassigned
      Eigen::Index best = 0;
      counts.row(cluster).maxCoeff(&best);  // first maximum = lowest class on ties
      cluster_classes[static_cast<size_t>(cluster)] = static_cast<int>(best);
    }
    return cluster_classes;
  }
  // Weka's classes-to-clusters: a one-to-one matching that maximises the matched counts.
  const Matrix negative_counts = -counts.cast<double>();
  if (cluster_count <= class_count) {
    const std::vector<int> assignment = minimum_cost_assignment(negative_counts);
    for (int cluster = 0; cluster < cluster_count; ++cluster)
      cluster_classes[static_cast<size_t>(cluster)] = assignment[static_cast<size_t>(cluster)];
  } else {
    const std::vector<int> assignment = minimum_cost_assignment(negative_counts.transpose());
    for (int class_index = 0; class_index < class_count; ++class_index)
      cluster_classes[static_cast<size_t>(assignment[static_cast<size_t>(class_index)])] =
          class_index;
  }
  return cluster_classes;
}

//---- em classifier --------------------------------------------------------------------------

ExpectationMaximization::ExpectationMaximization(const Parameters& parameters) {
  parameters.expect_only({"clusters", "covariance", "restarts", "iterations", "tolerance",
                          "variance_floor", "mapping", "standardize", "init"});
  const auto whole = [&](const std::string& key, int64_t fallback, int64_t minimum) {
    const int64_t value = parameters.integer(key, fallback);
    if (value < minimum || value > 1000000)
      throw Error(parameters.where(), key + "=" + std::to_string(value) + ": must be " +
                                          std::to_string(minimum) + " or more");
    return static_cast<int>(value);
  };
  requested_clusters_ = whole("clusters", 0, 0);
  options_.restarts = whole("restarts", 10, 1);
  options_.max_iterations = whole("iterations", 100, 1);
  options_.tolerance = support::positive_number(parameters, "tolerance", 1e-6, /*allow_zero=*/true);
  options_.variance_floor = support::positive_number(parameters, "variance_floor", 1e-6);
  const std::string covariance = parameters.text("covariance", "diagonal");
  if (covariance != "diagonal" && covariance != "full")
    throw Error(parameters.where(), "covariance=" + covariance + ": expected diagonal or full");
  options_.covariance =
      covariance == "full" ? MixtureCovariance::kFull : MixtureCovariance::kDiagonal;
  const std::string mapping = parameters.text("mapping", "majority");
  if (mapping != "majority" && mapping != "one-to-one")
    throw Error(parameters.where(), "mapping=" + mapping + ": expected majority or one-to-one");
  mapping_ = mapping == "one-to-one" ? ClusterMapping::kOneToOne : ClusterMapping::kMajority;
  standardize_ = parameters.flag("standardize", true);
  const std::string init = parameters.text("init", "kmeans++");
  if (init != "kmeans++" && init != "classes")
    throw Error(parameters.where(), "init=" + init + ": expected kmeans++ or classes");
  start_from_classes_ = init == "classes";
}

Parameters ExpectationMaximization::parameters() const {
  Parameters parameters;
  parameters.set("clusters", std::to_string(requested_clusters_));
  parameters.set("covariance", covariance_name(options_.covariance));
  parameters.set("restarts", std::to_string(options_.restarts));
  parameters.set("iterations", std::to_string(options_.max_iterations));
  parameters.set("tolerance", support::format_number(options_.tolerance));
  parameters.set("variance_floor", support::format_number(options_.variance_floor));
  parameters.set("mapping", mapping_ == ClusterMapping::kOneToOne ? "one-to-one" : "majority");
  parameters.set("standardize", standardize_ ? "true" : "false");
  parameters.set("init", start_from_classes_ ? "classes" : "kmeans++");
  return parameters;
}

void ExpectationMaximization::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                                  uint64_t seed) {
  check_training_set(x, y, class_count, name());
  class_count_ = class_count;
  standardizer_ = Standardizer{};
  if (standardize_) {
    standardizer_.fit(x);
  } else {
    standardizer_.mean = Vector::Zero(x.cols());
    standardizer_.scale = Vector::Ones(x.cols());
  }
  const Matrix z = standardizer_.transform(x);
  MixtureOptions options = options_;
  options.components = requested_clusters_ > 0 ? requested_clusters_ : class_count;
  if (start_from_classes_ && options.components != class_count)
    throw Error(name(), "init=classes starts one cluster per class: clusters=" +
                            std::to_string(options.components) + " but " +
                            std::to_string(class_count) + " classes");
  mixture_ = start_from_classes_ ? fit_gaussian_mixture_from(z, y, options)
                                 : fit_gaussian_mixture(z, options, seed);
  cluster_classes_ =
      map_clusters_to_classes(mixture_.assign(z), y, mixture_.components(), class_count, mapping_);
}

Matrix ExpectationMaximization::scores(const Matrix& x) const {
  if (mixture_.components() == 0) throw Error(name(), "not fitted");
  check_query(x, standardizer_.mean.size(), name());
  const Matrix responsibilities = mixture_.responsibilities(standardizer_.transform(x));
  Matrix membership = Matrix::Zero(mixture_.components(), class_count_);
  for (size_t cluster = 0; cluster < cluster_classes_.size(); ++cluster)
    if (cluster_classes_[cluster] != kUnknownClass)
      membership(static_cast<Eigen::Index>(cluster), cluster_classes_[cluster]) = 1.0;
  return responsibilities * membership;
}

std::vector<int> ExpectationMaximization::predict(const Matrix& x) const {
  if (mixture_.components() == 0) throw Error(name(), "not fitted");
  check_query(x, standardizer_.mean.size(), name());
  std::vector<int> classes = mixture_.assign(standardizer_.transform(x));
  for (int& value : classes) value = cluster_classes_[static_cast<size_t>(value)];
  return classes;
}

nlohmann::json ExpectationMaximization::save() const {
  return {{"parameters", parameters().values()},
          {"class_count", class_count_},
          {"standardizer", standardizer_.save()},
          {"mixture", mixture_.save()},
          {"cluster_classes", cluster_classes_}};
}

void ExpectationMaximization::load(const nlohmann::json& model) {
  const std::string where = name() + " model";
  try {
    Parameters parameters;
    parameters.set_where(where);
    for (const auto& [key, value] : model.at("parameters").items())
      parameters.set(key, value.get<std::string>());
    *this = ExpectationMaximization(parameters);
    class_count_ = model.at("class_count").get<int>();
    standardizer_.load(model.at("standardizer"));
    mixture_.load(model.at("mixture"), where + " mixture");
    cluster_classes_ = model.at("cluster_classes").get<std::vector<int>>();
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  if (static_cast<int>(cluster_classes_.size()) != mixture_.components())
    throw Error(where, "cluster map and mixture differ in size");
  for (int value : cluster_classes_)
    if (value != kUnknownClass && (value < 0 || value >= class_count_))
      throw Error(where, "cluster mapped to class " + std::to_string(value) + " out of range");
  if (standardizer_.mean.size() != mixture_.means.cols())
    throw Error(where, "standardizer and mixture differ in dimension");
}

//---- registry factory ---------------------------------------------------------------------

std::unique_ptr<Classifier> make_em_classifier(const Parameters& parameters) {
  return std::make_unique<ExpectationMaximization>(parameters);
}

}  // namespace tactile::ml
