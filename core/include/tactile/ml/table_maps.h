#pragma once
// The feature table drawn as maps (the workbench's scatter and SOM views): its rows on the
// first two principal components, and the flux paper's 7 x 7 SOM fitted on every row with
// each row's winning neuron. Both take a step callback (a job's progress and cancel).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/ml/som.h"

namespace tactile::ml {

struct TableScatter {
  Matrix points;           // rows x 2: each row's scores on the first two components
  double explained = 0.0;  // the share of the variance the two explain
};
// Standardised PCA (spec §6.5) of the table; a one-column table gets a zero second axis.
TableScatter scatter_of(const Matrix& features, const std::function<void(double)>& step = {});

struct TableSom {
  std::unique_ptr<SomClassifier> som;
  std::vector<std::string> classes;  // the map's class order (the table's class names)
  std::vector<int> winners;          // per row
  SomQuality quality;                // on the table's rows
};
// The SOM (200 epochs, seed 1) fitted on every row with its class, and its quality;
// `step(fraction)` after each epoch.
TableSom som_of(const Dataset& table, const std::function<void(double)>& step = {});
// Each row's winning neuron on `som` (a map loaded from a file); none when the table's
// columns are not the map's.
std::vector<int> som_winners(const SomClassifier& som, const Matrix& features);

}  // namespace tactile::ml
