#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "kaboli_common.h"
#include "tactile/experiments/kaboli.h"
#include "tactile/ml/em.h"
#include "tactile/text.h"

namespace tactile::experiments {

using namespace kaboli;

namespace {
struct Scenario {
  const char* name;
  Set train;
  Set test;
  double paper_accuracy;  // Kaboli et al., Fig. 4 (spec §1.18)
};
constexpr std::array<Scenario, 4> kScenarios = {{
    {"stationary -> stationary", Set::kBackStationary, Set::kFrontStationary, 0.8183},
    {"moving -> moving", Set::kBackMoving, Set::kFrontMoving, 0.7891},
    {"stationary -> moving", Set::kBackStationary, Set::kFrontMoving, 0.7755},
    {"multi-touch", Set::kBackStationary, Set::kMultiTouch, 0.8010},
}};

double log_likelihood_per_sample(const Scored& scored) {
  const auto& em = dynamic_cast<const ml::ExpectationMaximization&>(*scored.model);
  return em.mixture().log_likelihood / static_cast<double>(scored.train_rows);
}

}  // namespace

ExperimentReport run_kaboli_em(const ExperimentOptions& options) {
  Corpus corpus(options);
  ExperimentReport report;
  report.name = "kaboli-em";
  report.paper = "Kaboli et al., Fig. 4";
  ReportTable table;
  table.title = "Fig. 4: EM clusters mapped to classes (9 diagonal Gaussians)";
  table.columns = {"scenario", "train",          "test",        "ours %",
                   "paper %",  "from classes %", "ln L/sample", "from classes"};
  nlohmann::json tables = nlohmann::json::array();
  double correct = 0.0, tested = 0.0, paper_sum = 0.0;
  int done = 0;
  // Spec §1.16: 10 restarts; the quick corpus keeps 3 so that a smoke run stays short.
  const std::string classifier = options.quick ? "em:restarts=3" : "em";
  const std::string from_classes_classifier =
      classifier + (classifier.find(':') == std::string::npos ? ":" : ",") + "init=classes";
  for (const Scenario& scenario : kScenarios) {
    const Dataset train = corpus.dataset(scenario.train, "kaboli");
    const Dataset test = corpus.dataset(scenario.test, "kaboli");
    // Spec §1.16: fitted without labels on the training set; each cluster takes the majority
    // class of the training samples it wins; an unmapped cluster answers "unknown".
    const Scored scored = train_and_test(train, test, classifier, options.seed);
    // Ours, a diagnostic: the same EM started from the training labels (one cluster per
    // class) instead of k-means++. Both fit the same standardised training set, so their
    // log-likelihoods compare: where the class start ends higher, the restarts missed it.
    const Scored from_classes = train_and_test(train, test, from_classes_classifier, options.seed);
    const double likelihood = log_likelihood_per_sample(scored);
    const double class_likelihood = log_likelihood_per_sample(from_classes);
    if (options.progress) options.progress("em", ++done, static_cast<int>(kScenarios.size()));
    table.rows.push_back({scenario.name, set_name(scenario.train), set_name(scenario.test),
                          percent(scored.accuracy), percent(scenario.paper_accuracy),
                          percent(from_classes.accuracy), fixed_text(likelihood, 2),
                          fixed_text(class_likelihood, 2)});
    nlohmann::json entry;
    entry["title"] = scenario.name;
    entry["train"] = set_name(scenario.train);
    entry["test"] = set_name(scenario.test);
    entry["accuracy"] = scored.accuracy;
    entry["paper_accuracy"] = scenario.paper_accuracy;
    entry["unknown"] = scored.confusion.col(kClassCount).sum();
    entry["log_likelihood_per_sample"] = likelihood;
    entry["from_classes_accuracy"] = from_classes.accuracy;
    entry["from_classes_log_likelihood_per_sample"] = class_likelihood;
    tables.push_back(entry);
    correct += scored.accuracy * static_cast<double>(test.rows());
    tested += static_cast<double>(test.rows());
    paper_sum += scenario.paper_accuracy;
  }
  table.note =
      "Unlabelled EM on the training set's Kaboli descriptors (standardised), majority "
      "class per cluster (spec 1.16); predictions of unmapped clusters count as errors. "
      "'from classes' (ours, a diagnostic, not the paper's method): the same EM started from "
      "the training labels, one cluster per class; ln L/sample is the fit's log-likelihood on "
      "the standardised training set for each start. Where the class start ends higher, the "
      "figure is lost to EM's search (restarts), not to the descriptor (docs/SIMULATION.md). " +
      corpus.notes();
  report.tables.push_back(std::move(table));
  report.json["tables"] = tables;
  report.json["accuracy"] = correct / tested;  // over all test segments of the four scenarios
  report.json["paper_accuracy"] = paper_sum / static_cast<double>(kScenarios.size());
  report.json["seed"] = options.seed;
  report.json["quick"] = options.quick;
  return report;
}

}  // namespace tactile::experiments
