#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "ml_prob_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/em.h"

namespace tactile::ml {
namespace {

std::vector<test_data::Blob> separated_blobs() {
  Eigen::Matrix2d tilted;
  tilted << 1.0, 0.8, 0.8, 1.0;
  return {{Eigen::Vector2d(0, 0), tilted},
          {Eigen::Vector2d(8, 6), Eigen::Vector2d(0.5, 2.0).asDiagonal()}};
}

TEST(GaussianMixture, RecoversTwoSeparatedClusters) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(21);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 150, random, x, y);
  MixtureOptions options;
  options.components = 2;
  const GaussianMixture mixture = fit_gaussian_mixture(x, options, 1);
  const std::vector<int> clusters = mixture.assign(x);
  // The partition equals the classes up to a renaming of the clusters.
  const int first = clusters.front();
  for (size_t i = 0; i < y.size(); ++i) EXPECT_EQ(clusters[i] == first, y[i] == 0) << "row " << i;
  const int second = 1 - first;
  EXPECT_NEAR(mixture.means(first, 0), 0.0, 0.25);
  EXPECT_NEAR(mixture.means(second, 0), 8.0, 0.25);
  EXPECT_NEAR(mixture.means(second, 1), 6.0, 0.3);
  EXPECT_NEAR(mixture.variances(second, 1), 2.0, 0.5);
  EXPECT_NEAR(mixture.weights(first), 0.5, 1e-6);
  EXPECT_NEAR(mixture.weights.sum(), 1.0, 1e-12);
  const Matrix responsibilities = mixture.responsibilities(x);
  EXPECT_LT((responsibilities.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
}

TEST(GaussianMixture, SameSeedSameModelAndMoreRestartsNeverLoseLikelihood) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(4);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 60, random, x, y);
  MixtureOptions options;
  options.components = 4;  // more clusters than blobs: local optima differ between restarts
  options.restarts = 1;
  const GaussianMixture once = fit_gaussian_mixture(x, options, 77);
  const GaussianMixture again = fit_gaussian_mixture(x, options, 77);
  EXPECT_EQ(once.means, again.means);
  EXPECT_EQ(once.log_likelihood, again.log_likelihood);
  options.restarts = 8;
  const GaussianMixture many = fit_gaussian_mixture(x, options, 77);
  EXPECT_GE(many.log_likelihood, once.log_likelihood);
  EXPECT_TRUE(std::isfinite(many.log_likelihood));
  EXPECT_GE(many.iterations, 2);
}

TEST(GaussianMixture, FullCovarianceFitsCorrelatedDataBetter) {
  Eigen::Matrix2d correlated;
  correlated << 1.0, 0.95, 0.95, 1.0;
  const std::vector<test_data::Blob> blob = {{Eigen::Vector2d(0, 0), correlated}};
  std::mt19937_64 random(8);
  const Matrix x = test_data::draw(blob.front(), 400, random);
  MixtureOptions options;
  options.components = 1;
  const GaussianMixture diagonal = fit_gaussian_mixture(x, options, 0);
  options.covariance = MixtureCovariance::kFull;
  const GaussianMixture full = fit_gaussian_mixture(x, options, 0);
  EXPECT_GT(full.log_likelihood, diagonal.log_likelihood + 100.0);
  EXPECT_NEAR(full.full[0].covariance(0, 1), 0.95, 0.1);
  GaussianMixture restored;
  restored.load(nlohmann::json::parse(full.save().dump()), "test");
  EXPECT_EQ(restored.log_joint(x), full.log_joint(x));
}

TEST(GaussianMixture, BadInputIsRefused) {
  MixtureOptions options;
  options.components = 3;
  EXPECT_THROW(fit_gaussian_mixture(Matrix::Zero(2, 2), options, 0),
               Error);  // 2 samples, 3 clusters
  EXPECT_THROW(fit_gaussian_mixture(Matrix(0, 2), options, 0), Error);
  Matrix x = Matrix::Random(10, 2);
  x(4, 1) = std::nan("");
  EXPECT_THROW(fit_gaussian_mixture(x, options, 0), Error);
  options.variance_floor = 0.0;
  EXPECT_THROW(fit_gaussian_mixture(Matrix::Random(10, 2), options, 0), Error);
}

TEST(GaussianMixture, IdenticalSamplesStayFinite) {
  // Every sample equal: k-means++ has no distance to draw by, the variance floor keeps the
  // densities finite.
  MixtureOptions options;
  options.components = 3;
  const GaussianMixture mixture = fit_gaussian_mixture(Matrix::Constant(6, 2, 4.0), options, 2);
  EXPECT_TRUE(std::isfinite(mixture.log_likelihood));
  EXPECT_TRUE(mixture.responsibilities(Matrix::Constant(1, 2, 4.0)).allFinite());
}

//---- classes to clusters --------------------------------------------------------------------

TEST(ClassesToClusters, MajorityMapsEachClusterToItsMostFrequentClass) {
  const std::vector<int> clusters = {0, 0, 0, 1, 1, 1, 1, 3};
  const std::vector<int> classes = {2, 2, 1, 0, 1, 1, 0, 2};
  // Cluster 1 ties classes 0 and 1 -> lowest; cluster 2 wins nothing -> unassigned.
  EXPECT_EQ(map_clusters_to_classes(clusters, classes, 4, 3, ClusterMapping::kMajority),
            (std::vector<int>{2, 0, kUnknownClass, 2}));
}

TEST(ClassesToClusters, OneToOneUsesEachClassAtMostOnce) {
  // Counts: cluster 0 = {class 0: 5, class 1: 4}, cluster 1 = {class 0: 6}.
  std::vector<int> clusters, classes;
  for (int i = 0; i < 5; ++i) clusters.push_back(0), classes.push_back(0);
  for (int i = 0; i < 4; ++i) clusters.push_back(0), classes.push_back(1);
  for (int i = 0; i < 6; ++i) clusters.push_back(1), classes.push_back(0);
  EXPECT_EQ(map_clusters_to_classes(clusters, classes, 2, 2, ClusterMapping::kMajority),
            (std::vector<int>{0, 0}));
  EXPECT_EQ(map_clusters_to_classes(clusters, classes, 2, 2, ClusterMapping::kOneToOne),
            (std::vector<int>{1, 0}));
  // Three clusters, two classes: the cluster left out answers unknown.
  clusters.push_back(2), classes.push_back(1);
  EXPECT_EQ(map_clusters_to_classes(clusters, classes, 3, 2, ClusterMapping::kOneToOne),
            (std::vector<int>{1, 0, kUnknownClass}));
}

TEST(ClassesToClusters, HungarianFindsTheMinimumCostAssignment) {
  Matrix cost(3, 3);
  cost << 4, 1, 3, 2, 0, 5, 3, 2, 2;
  EXPECT_EQ(minimum_cost_assignment(cost), (std::vector<int>{1, 0, 2}));
  Matrix wide(2, 4);
  wide << 7, 3, 9, 1, 2, 8, 8, 1;
  EXPECT_EQ(minimum_cost_assignment(wide), (std::vector<int>{3, 0}));
  EXPECT_THROW(minimum_cost_assignment(Matrix::Zero(3, 2)), Error);
}

//---- em classifier --------------------------------------------------------------------------

TEST(ExpectationMaximization, PredictsTheMappedClassOfTheWinningCluster) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(31);
  Matrix train, test;
  std::vector<int> train_labels, test_labels;
  test_data::draw_classes(blobs, 100, random, train, train_labels);
  test_data::draw_classes(blobs, 100, random, test, test_labels);
  ExpectationMaximization classifier;
  classifier.fit(train, train_labels, 2, 5);
  std::vector<int> mapped = classifier.cluster_classes();
  std::sort(mapped.begin(), mapped.end());
  EXPECT_EQ(mapped, (std::vector<int>{0, 1}));
  EXPECT_GE(test_data::agreement(classifier.predict(test), test_labels), 0.99);
  const Matrix scores = classifier.scores(test);
  EXPECT_EQ(scores.cols(), 2);
  EXPECT_LT((scores.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);

  ExpectationMaximization restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  EXPECT_EQ(restored.scores(test), scores);
  EXPECT_EQ(restored.predict(test), classifier.predict(test));
  EXPECT_EQ(restored.parameters().values(), classifier.parameters().values());
}

TEST(ExpectationMaximization, UnmappedClusterAnswersUnknown) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(17);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 80, random, x, y);
  ExpectationMaximization classifier(Parameters::parse("clusters=3,mapping=one-to-one", "test"));
  classifier.fit(x, y, 2, 3);
  const auto& cluster_classes = classifier.cluster_classes();
  ASSERT_EQ(cluster_classes.size(), 3u);
  EXPECT_EQ(std::count(cluster_classes.begin(), cluster_classes.end(), kUnknownClass), 1);
  const std::vector<int> predicted = classifier.predict(x);
  const auto unknown = std::count(predicted.begin(), predicted.end(), kUnknownClass);
  EXPECT_GT(unknown, 0);
  EXPECT_LT(unknown, static_cast<long>(x.rows()));
  // scores carry no mass for the unmapped cluster: rows sum below 1 exactly where unknown.
  const Matrix scores = classifier.scores(x);
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    if (predicted[static_cast<size_t>(row)] == kUnknownClass) {
      EXPECT_LT(scores.row(row).sum(), 0.5);
    }
}

TEST(GaussianMixture, StartedFromALabellingItsFirstStepIsThatLabellingsGaussians) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(8);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 40, random, x, y);
  // Label the two blobs crosswise (half of each in either group): one M-step from that
  // labelling gives each component its group's mean and weight, not a blob's.
  std::vector<int> groups(y.size());
  for (size_t i = 0; i < y.size(); ++i) groups[i] = static_cast<int>(i % 2);
  MixtureOptions options;
  options.components = 2;
  options.max_iterations = 1;
  const GaussianMixture first = fit_gaussian_mixture_from(x, groups, options);
  for (int group = 0; group < 2; ++group) {
    Vector sum = Vector::Zero(2);
    int count = 0;
    for (size_t i = 0; i < y.size(); ++i)
      if (groups[i] == group) sum += x.row(static_cast<Eigen::Index>(i)).transpose(), ++count;
    EXPECT_LT((first.means.row(group).transpose() - sum / count).norm(), 1e-12) << group;
    EXPECT_NEAR(first.weights(group), 0.5, 1e-12);
  }
  EXPECT_EQ(first.iterations, 1);
  // Left to run, EM climbs from there: never below the first step's likelihood.
  options.max_iterations = 100;
  EXPECT_GE(fit_gaussian_mixture_from(x, groups, options).log_likelihood, first.log_likelihood);
  // Started from the blobs themselves it stays on them.
  const GaussianMixture from_blobs = fit_gaussian_mixture_from(x, y, options);
  EXPECT_EQ(from_blobs.assign(x), y);
  EXPECT_THROW(fit_gaussian_mixture_from(x, std::vector<int>(y.size(), 2), options), Error);
  EXPECT_THROW(fit_gaussian_mixture_from(x, std::vector<int>(3, 0), options), Error);
}

TEST(ExpectationMaximization, InitClassesStartsEachClusterOnOneTrainingClass) {
  const auto blobs = separated_blobs();
  std::mt19937_64 random(12);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 60, random, x, y);
  ExpectationMaximization classifier(Parameters::parse("init=classes", "test"));
  classifier.fit(x, y, 2, 0);
  EXPECT_EQ(classifier.cluster_classes(), (std::vector<int>{0, 1}));  // cluster k began as class k
  EXPECT_EQ(classifier.predict(x), y);
  EXPECT_EQ(classifier.parameters().text("init", ""), "classes");
  ExpectationMaximization restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  EXPECT_EQ(restored.parameters().values(), classifier.parameters().values());
  EXPECT_THROW(ExpectationMaximization(Parameters::parse("init=labels", "test")), Error);
  ExpectationMaximization more(Parameters::parse("init=classes,clusters=3", "test"));
  EXPECT_THROW(more.fit(x, y, 2, 0), Error);  // one cluster per class, no more
}

TEST(ExpectationMaximization, RejectsBadParametersAndInput) {
  EXPECT_THROW(ExpectationMaximization(Parameters::parse("k=3", "test")), Error);
  EXPECT_THROW(ExpectationMaximization(Parameters::parse("covariance=spherical", "test")), Error);
  EXPECT_THROW(ExpectationMaximization(Parameters::parse("mapping=best", "test")), Error);
  EXPECT_THROW(ExpectationMaximization(Parameters::parse("restarts=0", "test")), Error);
  ExpectationMaximization classifier;
  Matrix x(2, 1);
  x << 1, 2;
  EXPECT_THROW(classifier.fit(x, {0, 1}, 3, 0), Error);  // 2 samples, 3 clusters
  EXPECT_THROW(classifier.predict(x), Error);            // not fitted
}

}  // namespace
}  // namespace tactile::ml
