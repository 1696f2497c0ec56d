#include "tactile/features/feature_table.h"

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>

#include "tactile/error.h"
#include "tactile/features/dataset.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/atomic_file.h"
#include "tactile/parameters.h"

namespace tactile {

namespace {

std::string table_extension(const std::string& out) {
  return std::filesystem::path(out).extension().string();
}

}  // namespace

FeatureTable extract_feature_table(const FeatureTableOptions& options,
                                   const std::function<void(int64_t, int64_t)>& progress,
                                   const std::atomic<bool>* cancel) {
  for (const auto& [option, value] :
       {std::pair<const char*, const std::string&>{"--pipeline", options.pipeline},
        {"--labels", options.database},
        {"--out", options.out}})
    if (value.empty()) throw Error(option, "required (or use --list / --describe NAME)");
  const std::string extension = table_extension(options.out);
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
  CorpusQuery query{options.database, source, options.recordings, options.layout};
  query.recording = options.recording;
  const std::vector<CorpusRecording> recordings = corpus_from_store(query);
  CorpusOptions corpus_options;
  corpus_options.threads = options.threads;
  corpus_options.progress = progress;
  corpus_options.cancel = cancel;
  FeatureTable table;
  table.corpus = extract_corpus(*extractor, recordings, corpus_options);
  table.recordings = recordings.size();
  return table;
}

void write_feature_table(const FeatureTable& table, const FeatureTableOptions& options) {
  const CorpusDataset& corpus = table.corpus;
  // The skip log beside the output: written whole to a temporary file, then renamed.
  std::string log = "# tactile features --pipeline " + options.pipeline + ": " +
                    std::to_string(corpus.skipped.size()) + " of " +
                    std::to_string(corpus.segments) + " segments skipped\n";
  log += "recording\tsegment_id\tt0\tt1\treason\n";
  for (const SkippedSegment& skipped : corpus.skipped)
    log += skipped.recording + "\t" + std::to_string(skipped.segment_id) + "\t" +
           std::to_string(skipped.t0) + "\t" + std::to_string(skipped.t1) + "\t" + skipped.reason +
           "\n";
  write_file_atomically(options.out + ".log", log, "log");
  if (corpus.dataset.rows() == 0)
    throw Error(options.out, "no rows: all " + std::to_string(corpus.segments) +
                                 " segments were skipped (see " + options.out + ".log)");
  if (table_extension(options.out) == ".arff")
    write_dataset_arff(options.out, corpus.dataset, options.pipeline);
  else
    write_dataset_csv(options.out, corpus.dataset);
}

std::string feature_table_line(const FeatureTable& table, const FeatureTableOptions& options) {
  return std::to_string(table.corpus.dataset.rows()) + " rows x " +
         std::to_string(table.corpus.dataset.columns.size()) + " features from " +
         std::to_string(table.recordings) + " recordings, " +
         std::to_string(table.corpus.skipped.size()) + " segments skipped -> " + options.out;
}

std::string feature_table_json(const FeatureTable& table, const FeatureTableOptions& options) {
  const Dataset& dataset = table.corpus.dataset;
  nlohmann::json summary;
  summary["pipeline"] = options.pipeline;
  summary["out"] = options.out;
  summary["rows"] = dataset.rows();
  summary["skipped"] = table.corpus.skipped.size();
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
  return summary.dump(2) + "\n";
}

}  // namespace tactile
