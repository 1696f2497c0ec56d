// The cost of SVM class probabilities: every SVM preset fitted on all rows of one feature
// table with `probability=true` (a Platt sigmoid per pair from libsvm's 5-fold
// cross-validation: five more trainings per pair on 4/5 of its rows) against
// `probability=false` (votes only). One thread; the median of `repeats` fits each way.
//   svm_probability_bench FEATURES.csv [REPEATS]
// e.g. the fur skin's table: tactile simulate --skin fur --subjects 10 --trials 2 --out fur,
// then tactile features --labels fur/labels.db --pipeline fur --out fur.csv (600 rows).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/ml/svm.h"

namespace {

using Clock = std::chrono::steady_clock;

double median_fit_seconds(const std::string& preset, const std::string& parameters,
                          const tactile::Dataset& table, const std::vector<int>& y, int class_count,
                          int repeats) {
  std::vector<double> seconds;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    tactile::ml::SupportVectorMachine svm(preset, tactile::Parameters::parse(parameters, preset));
    const auto begin = Clock::now();
    svm.fit(table.features, y, class_count, 1);
    seconds.push_back(std::chrono::duration<double>(Clock::now() - begin).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: svm_probability_bench FEATURES.csv [REPEATS]\n");
    return 2;
  }
  try {
    const tactile::Dataset table = tactile::read_dataset_csv(argv[1]);
    const int repeats = argc == 3 ? std::max(1, std::atoi(argv[2])) : 5;
    const std::vector<std::string> names = table.class_names();
    std::vector<int> y;
    for (const std::string& name : table.classes)
      y.push_back(static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin()));
    const int class_count = static_cast<int>(names.size());
    std::printf("%lld rows x %lld features, %d classes (%d pairs), median of %d fits\n",
                static_cast<long long>(table.rows()), static_cast<long long>(table.features.cols()),
                class_count, class_count * (class_count - 1) / 2, repeats);
    std::printf("%-22s %12s %12s %7s\n", "preset", "votes (s)", "probab. (s)", "ratio");
    for (const std::string& preset : tactile::ml::svm_preset_names()) {
      const double votes =
          median_fit_seconds(preset, "probability=false", table, y, class_count, repeats);
      const double probabilities =
          median_fit_seconds(preset, "probability=true", table, y, class_count, repeats);
      std::printf("%-22s %12.4f %12.4f %7.2f\n", preset.c_str(), votes, probabilities,
                  probabilities / votes);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "svm_probability_bench: %s\n", error.what());
    return 1;
  }
  return 0;
}
