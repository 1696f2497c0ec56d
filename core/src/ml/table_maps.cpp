#include "tactile/ml/table_maps.h"

#include <algorithm>

#include "tactile/ml/pca.h"
#include "tactile/parameters.h"

namespace tactile::ml {

TableScatter scatter_of(const Matrix& features, const std::function<void(double)>& step) {
  if (step) step(0.0);
  PcaOptions options;
  options.components = std::min<int>(2, static_cast<int>(features.cols()));
  const Pca pca = fit_pca(features, options);
  if (step) step(0.9);
  TableScatter scatter;
  scatter.points = pca.transform(features);
  if (scatter.points.cols() < 2) {
    scatter.points.conservativeResize(Eigen::NoChange, 2);
    scatter.points.col(1).setZero();
  }
  scatter.explained = pca.cumulative_ratio()(std::min<Eigen::Index>(1, pca.kept - 1));
  return scatter;
}

std::vector<int> som_winners(const SomClassifier& som, const Matrix& features) {
  std::vector<int> winners;
  if (features.cols() != som.map().weights.cols()) return winners;
  const Matrix scaled = som.scale(features);
  for (Eigen::Index row = 0; row < scaled.rows(); ++row)
    winners.push_back(som_winner(som.map(), scaled.row(row).transpose()));
  return winners;
}

TableSom som_of(const Dataset& table, const std::function<void(double)>& step) {
  TableSom fit;
  fit.classes = table.class_names();
  std::vector<int> labels;
  for (const std::string& name : table.classes)
    labels.push_back(static_cast<int>(std::find(fit.classes.begin(), fit.classes.end(), name) -
                                      fit.classes.begin()));
  fit.som = std::make_unique<SomClassifier>(Parameters::parse("epochs=200", "som"));
  if (step)
    fit.som->set_epoch_observer(
        [&step](int epoch, int epochs) { step(static_cast<double>(epoch) / epochs); });
  fit.som->fit(table.features, labels, static_cast<int>(fit.classes.size()), 1);
  fit.som->set_epoch_observer(nullptr);
  fit.winners = som_winners(*fit.som, table.features);
  fit.quality = fit.som->quality(table.features);
  return fit;
}

}  // namespace tactile::ml
