#pragma once
// Kohonen self-organising map with neuron-to-class region labelling (silicone flux sensor
// paper, spec §5.9-5.12, test vector X4).
//
// Command-line name `som`, parameters (defaults in brackets):
//   rows=7, columns=7   grid; neuron k sits at (x = k mod columns, y = k / columns)
//   epochs=1000         each epoch visits every training input once, freshly shuffled
//   radius_start=max(rows, columns), radius_end=0.5
//                       r(e) = r0 - (r0 - r1) e/(E-1), linear (spec §5.10; R_MAX = 7 on 7 x 7)
//   rate_start=0.5, rate_end=0.01    alpha(e) = a0 (a1/a0)^(e/(E-1)), exponential
//   initial=uniform     weights ~ U(0.1, 0.9); `normal` draws N(0.5, 0.2^2) redrawn until
//                       inside [0.1, 0.9] (spec §5.10 ambiguity)
//   scale=true          min-max scale every feature to [0, 1] with the training minima and
//                       maxima, no clipping of test values (spec §5.9); a constant feature -> 0
//   empty=nearest       a neuron that wins no training input takes the label of the nearest
//                       labelled neuron on the grid (spec §5.11); `unknown` leaves it unlabelled
//                       so an input it wins is answered kUnknownClass
// Preset reproduced: `som` is the paper's 7 x 7 map with R_MAX = 7. The paper's pipeline puts
// standardisation and PCA to 90 % variance (spec §5.8) in front of it; that belongs to the
// flux-som experiment, the classifier scales whatever features it is given.
//   subspace=true       a table with more columns than rows is trained in the span of its
//                       rows: exactly the same map (weights equal to rounding), a fraction of
//                       the work (183 x 37,401: each step 49 x 183 numbers, not 49 x 37,401);
//                       false trains on every column as written
// With epochs=1 the schedules stay at their start values.
//
// Scores: for class c, minus the Euclidean distance from the scaled input to the nearest neuron
// labelled c (so the argmax is the winner's label); a class that owns no neuron scores
// std::numeric_limits<double>::lowest().

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// The trained map, for drawing the region map (Fig 8B).
struct SomMap {
  int rows = 0, columns = 0;
  Matrix weights;                 // one row per neuron k = columns * y + x, in scaled input space
  std::vector<int> neuron_class;  // per neuron; kUnknownClass when unlabelled
  std::vector<int> hits;          // training inputs each neuron wins after training
};

struct SomSchedule {
  int epochs = 1000;
  double radius_start = 7.0, radius_end = 0.5;
  double rate_start = 0.5, rate_end = 0.01;
  double radius(int epoch) const;
  double rate(int epoch) const;
};

// Quantisation error ||x - w_winner|| over one epoch (Fig 8A).
struct SomEpochError {
  double mean = 0.0;
  double max = 0.0;
};

// Nearest neuron in weight space (Euclidean, first on ties).
int som_winner(const SomMap& map, const Vector& x);
// Spec eq 1 as printed: theta_k = exp(-d^2 / r) for grid distance d < r, else 0.
Vector som_neighbourhood(const SomMap& map, int winner, double radius);
// How well a trained map fits inputs (already scaled as the map sees them).
struct SomQuality {
  double quantisation_error = 0.0;  // mean distance of an input to its winner
  double topographic_error = 0.0;   // share whose two nearest neurons are not grid neighbours
};
SomQuality som_quality(const SomMap& map, const Matrix& inputs);
// The U-matrix: each neuron's mean weight distance to its (up to four) grid neighbours.
std::vector<double> som_u_matrix(const SomMap& map);
// One online step, spec eq 2: w_k += alpha theta_k (x - w_k). Returns the winner.
int som_step(SomMap& map, const Vector& x, double radius, double rate);

class SomClassifier : public Classifier {
 public:
  explicit SomClassifier(const Parameters& parameters = {});

  std::string name() const override { return "som"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  const SomMap& map() const { return map_; }
  // Mean and max quantisation error per training epoch.
  const std::vector<SomEpochError>& training_errors() const { return training_errors_; }
  // The inputs as the map sees them (min-max scaled when scale=true).
  Matrix scale(const Matrix& x) const;
  // The map's quality on unscaled inputs `x` (the training table, or another).
  SomQuality quality(const Matrix& x) const;
  // Called by fit after each epoch with (epochs done, epochs): for progress, and to stop a
  // fit by throwing (a cancelled job). Not saved with the model.
  void set_epoch_observer(std::function<void(int, int)> observer) {
    epoch_observer_ = std::move(observer);
  }

 private:
  void label_neurons(const Matrix& scaled, const std::vector<int>& y, int class_count);

  SomMap map_;
  SomSchedule schedule_;
  bool normal_initial_ = false;
  bool scale_inputs_ = true;
  bool empty_unknown_ = false;
  bool subspace_ = true;
  int class_count_ = 0;
  Vector minimum_;
  Vector range_;
  std::vector<SomEpochError> training_errors_;
  std::function<void(int, int)> epoch_observer_;
};

// The registry's factory for `som`.
std::unique_ptr<Classifier> make_som_classifier(const Parameters& parameters);

}  // namespace tactile::ml
