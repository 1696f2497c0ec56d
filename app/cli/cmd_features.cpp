// `tactile features --pipeline NAME --labels DB [--source S] [--params k=v,...]
//  [--recordings DIR] [--threads N] --out FILE.csv|.arff [--json]`
// `tactile features --list` and `tactile features --describe NAME --layout ID`
//
// One row per labelled segment of every recording that has labels of the source; the
// recording file of id R is DIR/R.h5 (DIR: the database's folder unless given). Skipped
// segments are reported on stderr and listed in OUT.log.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/dataset.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/atomic_file.h"
#include "tactile/io/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile::cli {

namespace {

struct FeaturesOptions {
  std::string pipeline, database, source = "ground-truth", params, recordings, out;
  std::string describe, layout;
  int threads = 0;
  bool list = false, json = false;
};

void run_list() {
  for (const std::string& name : feature_pipelines())
    std::cout << name << "  " << make_feature_extractor(name)->description() << "\n";
}

void run_describe(const FeaturesOptions& options) {
  if (options.layout.empty())
    throw Error("--layout", "--describe needs the layout its columns are for, e.g. --layout nao");
  const auto extractor =
      make_feature_extractor(options.describe, Parameters::parse(options.params, "--params"));
  const SkinLayout layout = load_layout(options.layout);
  const std::vector<FeatureColumn> columns = extractor->columns(layout);
  size_t width = 0;
  for (const FeatureColumn& column : columns) width = std::max(width, column.name.size());
  for (const FeatureColumn& column : columns)
    std::cout << column.name << std::string(width - column.name.size() + 2, ' ')
              << column.description << "\n";
  std::cout << columns.size() << " columns (" << extractor->name() << " on " << layout.id << ")\n";
}

// The skip log beside the output: written whole to a temporary file, then renamed.
void write_log(const std::string& path, const CorpusDataset& corpus,
               const FeaturesOptions& options) {
  std::string text = "# tactile features --pipeline " + options.pipeline + ": " +
                     std::to_string(corpus.skipped.size()) + " of " +
                     std::to_string(corpus.segments) + " segments skipped\n";
  text += "recording\tsegment_id\tt0\tt1\treason\n";
  for (const SkippedSegment& skipped : corpus.skipped)
    text += skipped.recording + "\t" + std::to_string(skipped.segment_id) + "\t" +
            std::to_string(skipped.t0) + "\t" + std::to_string(skipped.t1) + "\t" + skipped.reason +
            "\n";
  write_file_atomically(path, text, "log");
}

nlohmann::json summary_json(const CorpusDataset& corpus, const FeaturesOptions& options) {
  const Dataset& dataset = corpus.dataset;
  nlohmann::json summary;
  summary["pipeline"] = options.pipeline;
  summary["out"] = options.out;
  summary["rows"] = dataset.rows();
  summary["skipped"] = corpus.skipped.size();
  nlohmann::json columns = nlohmann::json::array();
  for (const FeatureColumn& column : dataset.columns) columns.push_back(column.name);
  summary["columns"] = columns;
  nlohmann::json counts = nlohmann::json::object(), means = nlohmann::json::object();
  for (const std::string& name : dataset.class_names()) {
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(dataset.features.cols());
    int64_t count = 0;
    for (int64_t row = 0; row < dataset.rows(); ++row)
      if (dataset.classes[static_cast<size_t>(row)] == name) {
        sum += dataset.features.row(row);
        ++count;
      }
    counts[name] = count;
    nlohmann::json class_means = nlohmann::json::object();
    for (int64_t column = 0; column < dataset.features.cols(); ++column)
      class_means[dataset.columns[static_cast<size_t>(column)].name] =
          sum(column) / static_cast<double>(count);
    means[name] = class_means;
  }
  summary["class_counts"] = counts;
  summary["class_means"] = means;
  return summary;
}

void run_extract(const FeaturesOptions& options) {
  for (const auto& [option, value] :
       {std::pair<const char*, const std::string&>{"--pipeline", options.pipeline},
        {"--labels", options.database},
        {"--out", options.out}})
    if (value.empty()) throw Error(option, "required (or use --list / --describe NAME)");
  const std::string extension = std::filesystem::path(options.out).extension().string();
  if (extension != ".csv" && extension != ".arff")
    throw Error("--out", "'" + options.out + "': the file name must end in .csv or .arff");
  LabelSource source;
  try {
    source = parse_label_source(options.source);
  } catch (const Error& error) {
    throw Error("--source", error.message());
  }
  const auto extractor =
      make_feature_extractor(options.pipeline, Parameters::parse(options.params, "--params"));
  const std::vector<CorpusRecording> corpus_recordings =
      corpus_from_store({options.database, source, options.recordings, ""});

  ProgressBar progress("features " + options.pipeline);
  CorpusOptions corpus_options;
  corpus_options.threads = options.threads;
  corpus_options.progress = [&progress](int64_t done, int64_t total) {
    progress.update(done, total);
  };
  const CorpusDataset corpus = extract_corpus(*extractor, corpus_recordings, corpus_options);
  progress.finish();

  for (const SkippedSegment& skipped : corpus.skipped)
    std::cerr << "skipped: " << skipped.recording << " segment " << skipped.segment_id << ": "
              << skipped.reason << "\n";
  write_log(options.out + ".log", corpus, options);
  if (corpus.dataset.rows() == 0)
    throw Error(options.out, "no rows: all " + std::to_string(corpus.segments) +
                                 " segments were skipped (see " + options.out + ".log)");
  if (extension == ".arff")
    write_dataset_arff(options.out, corpus.dataset, options.pipeline);
  else
    write_dataset_csv(options.out, corpus.dataset);

  if (options.json) {
    std::cout << summary_json(corpus, options).dump(2) << "\n";
  } else {
    std::cout << corpus.dataset.rows() << " rows x " << corpus.dataset.columns.size()
              << " features from " << corpus_recordings.size() << " recordings, "
              << corpus.skipped.size() << " segments skipped -> " << options.out << "\n";
  }
}

}  // namespace

void register_features(CLI::App& app) {
  auto options = std::make_shared<FeaturesOptions>();
  CLI::App* command = app.add_subcommand(
      "features", "Turn labelled segments into a feature table (CSV for pandas, ARFF for Weka)");
  command->add_option("--pipeline", options->pipeline, "Feature pipeline (see --list)");
  command->add_option("--labels", options->database, "Label database (SQLite)");
  command
      ->add_option("--source", options->source,
                   "Which labels give the segments: ground-truth (default), manual, segmenter")
      ->capture_default_str();
  command->add_option("--params", options->params, "Pipeline parameters as key=value,...");
  command->add_option("--recordings", options->recordings,
                      "Folder of <recording id>.h5 files (default: the database's folder)");
  command->add_option("--threads", options->threads, "Worker threads (default: one per core)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--out", options->out, "Output table: FILE.csv or FILE.arff");
  command->add_flag("--json", options->json,
                    "Print a JSON summary: rows, skipped, columns, per-class counts and means");
  command->add_flag("--list", options->list, "Print the feature pipelines and exit");
  command->add_option("--describe", options->describe,
                      "Print a pipeline's columns with their descriptions (needs --layout)");
  command->add_option("--layout", options->layout, "Layout id for --describe");
  command->callback([options] {
    if (options->list)
      run_list();
    else if (!options->describe.empty())
      run_describe(*options);
    else
      run_extract(*options);
  });
}

}  // namespace tactile::cli
