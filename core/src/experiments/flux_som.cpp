// `flux-som`: the silicone flux sensor paper (file 004) — PCA to 90 % variance, a 7 x 7 SOM
// labelled into class regions (Fig 8B) and its confusion matrix (Fig 8C), spec §5.8-5.13.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "experiment_data.h"
#include "tactile/error.h"
#include "tactile/experiments/flux.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/pca.h"
#include "tactile/ml/som.h"
#include "tactile/text.h"

namespace tactile::experiments {

namespace {

constexpr int kPaperComponents = 8;         // §5.13: 8 components explain 90 % of variance
constexpr double kVarianceFraction = 0.90;  // §5.8

}  // namespace

ExperimentReport run_flux_som(const ExperimentOptions& options) {
  // The paper's corpus: 900 presses and caresses, 150 per class.
  SimulationOptions simulation;
  simulation.seed = options.seed;
  simulation.subjects = options.quick ? 2 : 5;
  simulation.trials = options.quick ? 1 : 3;
  simulation.repetitions = options.quick ? 5 : 10;
  const Dataset dataset = experiment_dataset(options, "flux", simulation, "flux", "excitation");
  const std::vector<std::string> classes = ordered_classes(dataset, "flux");
  const std::vector<int> labels = class_indices(dataset, classes);
  const int class_count = static_cast<int>(classes.size());
  // The paper trains for 1000 epochs (§5.10); the quick run trains a tenth as long.
  const int epochs = options.quick ? 100 : 1000;
  const std::string specification = "som:rows=7,columns=7,epochs=" + std::to_string(epochs);

  ml::PcaOptions pca_options;
  pca_options.variance_fraction = kVarianceFraction;
  pca_options.standardize = true;
  const ml::Pca pca = ml::fit_pca(dataset.features, pca_options);
  const Eigen::VectorXd cumulative = pca.cumulative_ratio();

  // §5.12: stratified 5-fold CV repeated with 5 seeds, PCA fitted inside each training fold.
  const ml::Protocol protocol = ml::Protocol::parse(options.quick ? "kfold:5" : "kfold:5x5");
  const std::vector<ml::Fold> folds = ml::make_folds(dataset, protocol, options.seed);
  const Eigen::MatrixXi confusion =
      cross_validate(dataset.features, labels, class_count, folds, specification, options.seed,
                     &pca_options, [&options](int done, int total) {
                       report_progress(options, "cross-validation", done, total);
                     });
  const double accuracy = ml::accuracy_of(confusion);
  const std::vector<ml::ClassFigures> figures = ml::class_figures(confusion);

  // Fig 8B: the map trained on every segment, each neuron's class region.
  report_progress(options, "region map", 0, 1);
  auto model = ml::make_classifier(specification);
  model->fit(pca.transform(dataset.features), labels, class_count, options.seed);
  const auto* som = dynamic_cast<const ml::SomClassifier*>(model.get());
  if (!som) throw Error("flux-som", specification + " is not a SOM");
  const ml::SomMap& map = som->map();
  report_progress(options, "region map", 1, 1);

  ExperimentReport report;
  report.name = "flux-som";
  report.paper = "Silicone tactile flux sensor (file 004), Fig 8";

  ReportTable components;
  components.title = "PCA (standardised): cumulative explained variance";
  components.columns = {"components", "cumulative ours %"};
  for (Eigen::Index k = 0; k < cumulative.size() && k < 12; ++k)
    components.rows.push_back({std::to_string(k + 1), percent_text(cumulative(k))});
  components.rows.push_back({"kept for 90 %", "ours " + std::to_string(pca.kept) + ", paper " +
                                                  std::to_string(kPaperComponents)});
  components.note = "Fitted on all " + std::to_string(dataset.rows()) + " segments x " +
                    std::to_string(dataset.features.cols()) +
                    " features; inside the cross-validation each training fold fits its own.";
  report.tables.push_back(components);

  ReportTable regions;
  regions.title = "Fig 8B: SOM class regions (7 x 7, neuron label / training hits)";
  regions.columns = {"y \\ x"};
  for (int x = 0; x < map.columns; ++x) regions.columns.push_back(std::to_string(x));
  for (int y = 0; y < map.rows; ++y) {
    std::vector<std::string> row = {std::to_string(y)};
    for (int x = 0; x < map.columns; ++x) {
      const size_t neuron = static_cast<size_t>(map.columns * y + x);
      const int label = map.neuron_class[neuron];
      row.push_back(
          (label == ml::kUnknownClass ? std::string("?") : classes[static_cast<size_t>(label)]) +
          " " + std::to_string(map.hits[neuron]));
    }
    regions.rows.push_back(row);
  }
  regions.note = "Trained " + std::to_string(epochs) +
                 " epochs on the PCA scores of all segments; a neuron that wins no input takes "
                 "the label of its nearest labelled neighbour.";
  report.tables.push_back(regions);

  ReportTable matrix;
  matrix.title =
      "Fig 8C: confusion, stratified " + protocol.to_string() + " (rows true, columns predicted)";
  matrix.columns = {"true \\ predicted"};
  for (const std::string& name : classes) matrix.columns.push_back(name);
  matrix.columns.push_back("recall ours %");
  for (int truth = 0; truth < class_count; ++truth) {
    std::vector<std::string> row = {classes[static_cast<size_t>(truth)]};
    for (int answer = 0; answer < class_count; ++answer)
      row.push_back(std::to_string(confusion(truth, answer)));
    row.push_back(percent_text(figures[static_cast<size_t>(truth)].recall));
    matrix.rows.push_back(row);
  }
  std::vector<std::string> total(matrix.columns.size(), "");
  total[0] = "accuracy (paper: none)";
  total.back() = percent_text(accuracy);
  matrix.rows.push_back(total);
  matrix.note =
      "The paper shows Fig 8C without an accuracy (it calls a class correct when its "
      "diagonal cell is non-zero, which is not an accuracy); chance is " +
      fixed_text(100.0 / class_count, 1) + " %. Simulated skins: figures differ.";
  report.tables.push_back(matrix);

  nlohmann::json confusion_json = nlohmann::json::array();
  for (int truth = 0; truth < class_count; ++truth) {
    nlohmann::json line = nlohmann::json::array();
    for (int answer = 0; answer < class_count; ++answer) line.push_back(confusion(truth, answer));
    confusion_json.push_back(line);
  }
  nlohmann::json region_json = nlohmann::json::array();
  for (const int label : map.neuron_class)
    region_json.push_back(label == ml::kUnknownClass ? std::string("unknown")
                                                     : classes[static_cast<size_t>(label)]);
  std::vector<double> cumulative_list(cumulative.data(), cumulative.data() + cumulative.size());
  report.json["classes"] = classes;
  report.json["segments"] = dataset.rows();
  report.json["accuracy"] = accuracy;
  report.json["paper_accuracy"] = nullptr;  // not reported (§5.13)
  report.json["tables"] = nlohmann::json::array({{{"title", components.title},
                                                  {"components", pca.kept},
                                                  {"paper_components", kPaperComponents},
                                                  {"cumulative_ratio", cumulative_list},
                                                  {"accuracy", nullptr},
                                                  {"paper_accuracy", nullptr}},
                                                 {{"title", regions.title},
                                                  {"neuron_class", region_json},
                                                  {"hits", map.hits},
                                                  {"accuracy", nullptr},
                                                  {"paper_accuracy", nullptr}},
                                                 {{"title", matrix.title},
                                                  {"accuracy", accuracy},
                                                  {"paper_accuracy", nullptr},
                                                  {"confusion", confusion_json}}});
  return report;
}

}  // namespace tactile::experiments
