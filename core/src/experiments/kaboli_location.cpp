#include <nlohmann/json.hpp>

#include "kaboli_common.h"
#include "tactile/experiments/kaboli.h"

namespace tactile::experiments {

using namespace kaboli;

namespace {
// Kaboli et al., Table 5 (E1, spec §1.18): rows true, columns predicted.
constexpr PaperMatrix kTable5 = {{{24, 0, 0, 0, 0, 0, 0, 0, 0},
                                  {0, 23, 0, 1, 0, 0, 0, 0, 0},
                                  {0, 0, 24, 0, 0, 0, 0, 0, 0},
                                  {0, 0, 0, 24, 0, 0, 0, 0, 0},
                                  {0, 0, 0, 0, 22, 0, 0, 2, 0},
                                  {0, 0, 0, 0, 0, 23, 0, 0, 1},
                                  {1, 0, 1, 0, 0, 0, 22, 0, 0},
                                  {0, 0, 0, 0, 0, 0, 0, 24, 0},
                                  {0, 0, 0, 0, 0, 1, 0, 0, 23}}};
// Kaboli et al., abstract and Sec. 7.1.1: 96.79 % (the matrix itself gives 96.76 %).
constexpr double kTable5Accuracy = 0.9679;
}  // namespace

ExperimentReport run_kaboli_location(const ExperimentOptions& options) {
  Corpus corpus(options);
  const Dataset train = corpus.dataset(Set::kBackStationary, "kaboli");
  const Dataset test = corpus.dataset(Set::kFrontStationary, "kaboli");
  if (options.progress) options.progress("svm", 0, 1);
  const Scored scored = train_and_test(train, test, svm_specification(options.quick), options.seed);
  if (options.progress) options.progress("svm", 1, 1);

  ExperimentReport report;
  report.name = "kaboli-location";
  report.paper = "Kaboli et al., Table 5";
  const std::string title = "Table 5: trained on the back, tested on the front (stationary), SVM";
  report.tables.push_back(confusion_table(
      title, scored, kTable5, kTable5Accuracy,
      "Linear SVM, C by cross-validation on the training set (spec 1.14). " + corpus.notes()));
  report.json["tables"] =
      nlohmann::json::array({confusion_json(title, scored, kTable5, kTable5Accuracy)});
  report.json["accuracy"] = scored.accuracy;
  report.json["paper_accuracy"] = kTable5Accuracy;
  report.json["seed"] = options.seed;
  report.json["quick"] = options.quick;
  return report;
}

}  // namespace tactile::experiments
