#include <gtest/gtest.h>

#include "tactile/error.h"
#include "tactile/ml/em.h"
#include "tactile/ml/gaussian.h"
#include "tactile/ml/naive_bayes.h"

namespace tactile::ml {
namespace {

struct Factory {
  const char* name;
  std::unique_ptr<Classifier> (*make)(const Parameters&);
};

const Factory kFactories[] = {{"gaussian-ml", make_gaussian_ml_classifier},
                              {"qda", make_qda_classifier},
                              {"gaussian-nb", make_gaussian_nb_classifier},
                              {"kernel-nb", make_kernel_nb_classifier},
                              {"em", make_em_classifier}};

TEST(ProbabilisticFactories, NameMatchesAndEffectiveParametersRebuildTheSameClassifier) {
  for (const Factory& factory : kFactories) {
    const auto classifier = factory.make(Parameters{});
    EXPECT_EQ(classifier->name(), factory.name);
    const Parameters effective = classifier->parameters();
    EXPECT_FALSE(effective.values().empty()) << factory.name;
    EXPECT_EQ(factory.make(effective)->parameters().values(), effective.values()) << factory.name;
  }
}

TEST(ProbabilisticFactories, UnknownParameterNamesTheClassifier) {
  for (const Factory& factory : kFactories) {
    const Parameters parameters =
        Parameters::parse("no_such_key=1", std::string("classifier ") + factory.name);
    try {
      factory.make(parameters);
      ADD_FAILURE() << factory.name << " accepted an unknown key";
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), std::string("classifier ") + factory.name);
      EXPECT_NE(error.message().find("no_such_key"), std::string::npos);
    }
  }
}

TEST(ProbabilisticFactories, EveryClassifierScoresProbabilitiesOnTwoBlobs) {
  Matrix x(8, 2);
  x << 0, 0, 1, 0, 0, 1, 1, 1, 5, 5, 6, 5, 5, 6, 6, 6;
  const std::vector<int> y = {0, 0, 0, 0, 1, 1, 1, 1};
  for (const Factory& factory : kFactories) {
    const auto classifier = factory.make(Parameters{});
    classifier->fit(x, y, 2, 42);
    const Matrix scores = classifier->scores(x);
    ASSERT_EQ(scores.rows(), 8) << factory.name;
    ASSERT_EQ(scores.cols(), 2) << factory.name;
    EXPECT_TRUE(scores.allFinite()) << factory.name;
    EXPECT_LT((scores.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-9) << factory.name;
    EXPECT_EQ(classifier->predict(x), y) << factory.name;
  }
}

}  // namespace
}  // namespace tactile::ml
