// `auto` at the size of a published capture set's feature table (issue 26): 1100 rows x 345
// columns, 11 classes, 10 stratified 85/15 hold-outs, both cores. The table is synthetic and
// deterministic: a few informative columns in mixed units, columns correlated with them and
// pure noise, as a generic descriptor table of a 12-electrode skin is. Prints the wall time,
// the accuracy, the candidates each hold-out chose, and (with --each) every candidate alone
// on the same hold-outs, for comparison.
// --grouped: at the size of the inflatable robot's grid table instead (issue 42): 330 rows x
// 26,000 columns, 7 classes, 37 recordings, leave one recording out (group:recording), so
// that auto's inner folds keep recordings whole.
//   auto_bench [--each] [--grouped] [--classifier SPEC]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "tactile/features/dataset.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/grid_search.h"

namespace {

tactile::Dataset capture_table(int rows, int columns, int classes, uint64_t seed,
                               int recordings = 0) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int informative = 24;
  Eigen::MatrixXd centres(classes, informative);
  for (int k = 0; k < classes; ++k)
    for (int j = 0; j < informative; ++j) centres(k, j) = normal(engine);
  Eigen::VectorXd units(columns);
  for (int j = 0; j < columns; ++j) units(j) = std::exp(-2.0 + 5.0 * unit(engine));
  // Each other column mixes two informative ones with noise, or is noise alone.
  std::vector<int> mix_a(static_cast<size_t>(columns)), mix_b(static_cast<size_t>(columns));
  std::vector<double> weight(static_cast<size_t>(columns));
  for (int j = 0; j < columns; ++j) {
    mix_a[static_cast<size_t>(j)] = static_cast<int>(unit(engine) * informative);
    mix_b[static_cast<size_t>(j)] = static_cast<int>(unit(engine) * informative);
    weight[static_cast<size_t>(j)] =
        j < informative ? 1.0 : (unit(engine) < 0.5 ? unit(engine) : 0.0);
  }
  tactile::Dataset dataset;
  dataset.features.resize(rows, columns);
  for (int r = 0; r < rows; ++r) {
    const int label = r % classes;
    Eigen::VectorXd latent(informative);
    for (int j = 0; j < informative; ++j) latent(j) = centres(label, j) + 1.3 * normal(engine);
    for (int j = 0; j < columns; ++j) {
      const size_t s = static_cast<size_t>(j);
      const double signal =
          j < informative ? latent(j) : 0.5 * (latent(mix_a[s]) + latent(mix_b[s]));
      dataset.features(r, j) =
          units(j) * (weight[s] * signal + (1.0 - 0.5 * weight[s]) * normal(engine));
    }
    dataset.classes.push_back("c" + std::to_string(label));
    dataset.subjects.push_back("s" + std::to_string(r % 10));
    dataset.recordings.push_back("r" + std::to_string(recordings > 0 ? r % recordings : r / 20));
    dataset.segment_ids.push_back(r + 1);
    dataset.metadata.emplace_back();
  }
  for (int j = 0; j < columns; ++j) dataset.columns.push_back({"f" + std::to_string(j), ""});
  return dataset;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  bool each = false, grouped = false;
  std::string specification = "auto";
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--each") {
      each = true;
    } else if (argument == "--grouped") {
      grouped = true;
    } else if (argument == "--classifier" && i + 1 < argc) {
      specification = argv[++i];
    } else {
      std::fprintf(stderr, "usage: auto_bench [--each] [--grouped] [--classifier SPEC]\n");
      return 2;
    }
  }
  const tactile::Dataset dataset =
      grouped ? capture_table(330, 26000, 7, 7, 37) : capture_table(1100, 345, 11, 7);
  const tactile::ml::Protocol protocol =
      tactile::ml::Protocol::parse(grouped ? "group:recording" : "holdout:0.15x10");
  const std::string shape = grouped ? "330 x 26000, 7 classes, 37 recordings, group:recording"
                                    : "1100 x 345, 11 classes, holdout:0.15x10";
  if (each) {
    std::printf("| candidate | accuracy %% | seconds (%s, 2 cores) |\n|---|---:|---:|\n",
                shape.c_str());
    for (const std::string& candidate : tactile::ml::auto_candidates()) {
      const auto start = std::chrono::steady_clock::now();
      try {
        const auto result = tactile::ml::evaluate(dataset, candidate, protocol, 1);
        std::printf("| %s | %.2f | %.2f |\n", candidate.c_str(), 100.0 * result.accuracy,
                    seconds_since(start));
      } catch (const std::exception& error) {
        std::printf("| %s | failed: %s | %.2f |\n", candidate.c_str(), error.what(),
                    seconds_since(start));
      }
      std::fflush(stdout);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const auto result = tactile::ml::evaluate(dataset, specification, protocol, 1);
  std::printf("%s on %s, both cores: %.2f %% in %.1f s\n", specification.c_str(), shape.c_str(),
              100.0 * result.accuracy, seconds_since(start));
  std::map<std::string, int> chosen;
  for (const std::string& model : result.fold_models) ++chosen[model];
  for (const auto& [model, count] : chosen)
    std::printf("  chosen %d x: %s\n", count, model.c_str());
  return 0;
}
