// Analysis at a real session's size (issue 41): 30 minutes of Robovie's 274 films, its labelled
// segments turned into the skin's own feature table (one row per segment, 37,401 pair
// correlations), then
//  - the SOM map the workbench draws (7 x 7, 200 epochs) and the `som` preset (1000 epochs),
//    each timed with its quantisation and topographic error; a few epochs trained on every
//    column (subspace=false), as before, give the time per epoch both ways;
//  - Train all as the workbench runs it (every preset, 5-fold, one worker thread beside the
//    window), each preset's seconds in the order they ran and the total.
// The recording and the table are made once in DIR. One run, so compare within it.
//   real_size_bench DIR [som|train]...   (both by default)
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "long_robovie.h"
#include "process_memory.h"
#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/dataset.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/som.h"
#include "tactile/ml/table_maps.h"
#include "tactile/parameters.h"
#include "tactile/skins/skin.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The table Train all makes from the workspace (training_job.cpp's route), cached as CSV.
tactile::Dataset robovie_table(const std::filesystem::path& folder) {
  const std::filesystem::path cached = folder / "robovie-30min-features.csv";
  if (std::filesystem::exists(cached)) return tactile::read_dataset_csv(cached.string());
  if (!std::filesystem::exists(folder / "robovie-30min.h5"))
    tactile::bench::write_long_robovie(folder);
  const auto start = Clock::now();
  const std::vector<tactile::CorpusRecording> corpus =
      tactile::corpus_from_store({(folder / "labels.db").string(),
                                  tactile::LabelSource::kGroundTruth, folder.string(), "robovie"});
  const auto extractor =
      tactile::make_feature_extractor(tactile::default_pipeline("robovie"), tactile::Parameters());
  tactile::CorpusDataset table = tactile::extract_corpus(*extractor, corpus, {});
  std::fprintf(stderr, "real_size_bench: features in %.1f s\n", seconds_since(start));
  tactile::write_dataset_csv(cached.string(), table.dataset);
  return std::move(table.dataset);
}

std::vector<int> class_indices(const tactile::Dataset& table) {
  const std::vector<std::string> names = table.class_names();
  std::vector<int> labels;
  for (const std::string& name : table.classes)
    labels.push_back(static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin()));
  return labels;
}

void som_rows(const tactile::Dataset& table) {
  const std::vector<int> labels = class_indices(table);
  const int classes = static_cast<int>(table.class_names().size());
  auto start = Clock::now();
  const tactile::ml::TableSom map = tactile::ml::som_of(table, {});
  const double map_seconds = seconds_since(start);
  const tactile::ml::SomQuality map_quality = map.som->quality(table.features);
  for (const char* spec : {"epochs=1000", "epochs=3,subspace=false", "epochs=3"}) {
    tactile::ml::SomClassifier som(tactile::Parameters::parse(spec, "som"));
    start = Clock::now();
    som.fit(table.features, labels, classes, 1);
    const double seconds = seconds_since(start);
    const tactile::ml::SomQuality quality = som.quality(table.features);
    std::printf("| som `%s` | %.2f s | %.4f | %.3f |\n", spec, seconds, quality.quantisation_error,
                quality.topographic_error);
  }
  std::printf("| SOM map view (som_of: 7 x 7, 200 epochs) | %.2f s | %.4f | %.3f |\n", map_seconds,
              map_quality.quantisation_error, map_quality.topographic_error);
}

void train_rows(const tactile::Dataset& table) {
  tactile::ml::EvaluationControl control;
  control.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1);
  const auto start = Clock::now();
  double last = 0.0;
  tactile::ml::evaluate_all(
      table, tactile::ml::Protocol::parse("kfold:5"), 1, control,
      [&](const tactile::ml::PresetOutcome& outcome, int index, int total) {
        const double now = seconds_since(start);
        char accuracy[32];
        std::snprintf(accuracy, sizeof accuracy, "%.1f %%",
                      outcome.result ? outcome.result->accuracy * 100.0 : 0.0);
        std::printf("| %d/%d %s | %.2f s | %.2f s | %s |\n", index + 1, total,
                    outcome.classifier.c_str(), now - last, now,
                    outcome.result ? accuracy : ("skipped: " + outcome.skipped).c_str());
        std::fflush(stdout);
        last = now;
      });
  std::printf("| Train all | | %.2f s | |\n", seconds_since(start));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: real_size_bench DIR [som|train]...\n");
    return 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    std::filesystem::create_directories(folder);
    std::vector<std::string> parts(argv + 2, argv + argc);
    if (parts.empty()) parts = {"som", "train"};
    const tactile::Dataset table = robovie_table(folder);
    std::printf("table: %lld rows x %lld columns, %zu classes\n\n",
                static_cast<long long>(table.rows()), static_cast<long long>(table.features.cols()),
                table.class_names().size());
    for (const std::string& part : parts) {
      tactile::bench::reset_peak_memory();
      if (part == "som") {
        std::printf(
            "| SOM | seconds | quantisation error | topographic error |\n|---|---|---|---|\n");
        som_rows(table);
      } else if (part == "train") {
        std::printf(
            "\n| preset (in the order run) | seconds | since the start | accuracy "
            "|\n|---|---|---|---|\n");
        train_rows(table);
      } else {
        throw tactile::Error("real_size_bench", "unknown part '" + part + "' (som, train)");
      }
      std::printf("\n%s: peak resident memory %.0f MB (the table itself %.0f MB)\n\n", part.c_str(),
                  tactile::bench::peak_memory_mb(),
                  static_cast<double>(table.features.size()) * 8.0 / 1e6);
      std::fflush(stdout);
    }
    return 0;
  } catch (const tactile::Error& error) {
    std::fprintf(stderr, "real_size_bench: %s\n", error.what());
    return 1;
  }
}
