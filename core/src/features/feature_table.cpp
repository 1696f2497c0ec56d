#include "tactile/features/feature_table.h"

#include <Eigen/Core>
#include <filesystem>
#include <map>
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
  std::vector<CorpusRecording> recordings = corpus_from_store(query);
  FeatureTable table;
  for (size_t index = 0; index < recordings.size(); ++index) {
    table.plan.push_back(recordings[index].id + ":" +
                         std::to_string(recordings[index].segments.size()));
    if (options.shard.owns(index)) table.done.push_back(index);
  }
  if (options.shard.active()) {
    std::vector<CorpusRecording> owned;
    for (size_t index : table.done) owned.push_back(std::move(recordings[index]));
    recordings = std::move(owned);
  }
  CorpusOptions corpus_options;
  corpus_options.threads = options.threads;
  corpus_options.progress = progress;
  corpus_options.cancel = cancel;
  if (!recordings.empty()) table.corpus = extract_corpus(*extractor, recordings, corpus_options);
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

//---- Shards ---------------------------------------------------------------------------------

Part feature_table_part(const FeatureTable& table, const FeatureTableOptions& options) {
  const Dataset& dataset = table.corpus.dataset;
  Part part;
  part.command = "features";
  part.shard = options.shard;
  part.inputs = {{"--pipeline", options.pipeline},
                 {"--params", options.params},
                 {"--labels", options.database},
                 {"--source", options.source},
                 {"--recordings", options.recordings}};
  part.result = options.out;
  part.items = static_cast<int64_t>(table.plan.size());
  part.plan = plan_digest(table.plan);
  nlohmann::json columns = nlohmann::json::array();
  for (const FeatureColumn& column : dataset.columns)
    columns.push_back({column.name, column.description});
  part.shared = {{"columns", columns}};
  // Each recording's rows and skips, gathered in one pass over the table.
  std::map<std::string, nlohmann::json> rows, skipped;
  for (int64_t row = 0; row < dataset.rows(); ++row) {
    const auto at = static_cast<size_t>(row);
    std::vector<double> values(static_cast<size_t>(dataset.features.cols()));
    Eigen::Map<Eigen::RowVectorXd>(values.data(), dataset.features.cols()) =
        dataset.features.row(row);
    rows[dataset.recordings[at]].push_back({{"features", values},
                                            {"class", dataset.classes[at]},
                                            {"subject", dataset.subjects[at]},
                                            {"segment_id", dataset.segment_ids[at]},
                                            {"metadata", dataset.metadata[at]}});
  }
  for (const SkippedSegment& skip : table.corpus.skipped)
    skipped[skip.recording].push_back({{"segment_id", skip.segment_id},
                                       {"t0", skip.t0},
                                       {"t1", skip.t1},
                                       {"reason", skip.reason}});
  part.done = nlohmann::json::array();
  for (size_t index : table.done) {
    const std::string id = table.plan[index].substr(0, table.plan[index].rfind(':'));
    part.done.push_back({{"index", index},
                         {"recording", id},
                         {"rows", rows.count(id) ? rows[id] : nlohmann::json::array()},
                         {"skipped", skipped.count(id) ? skipped[id] : nlohmann::json::array()}});
  }
  return part;
}

FeatureTable merge_feature_table_parts(const std::vector<Part>& parts) {
  FeatureTable table;
  // A shard that read no recording (more shards than recordings) knows no columns.
  const Part* with_columns = nullptr;
  for (const Part& part : parts) {
    if (part.shared.at("columns").empty()) continue;
    if (!with_columns) {
      with_columns = &part;
      for (const nlohmann::json& column : part.shared.at("columns"))
        table.corpus.dataset.columns.push_back(
            {column.at(0).get<std::string>(), column.at(1).get<std::string>()});
    } else if (part.shared.at("columns") != with_columns->shared.at("columns")) {
      throw Error(part.path, "its feature columns differ from " + with_columns->path + "'s");
    }
  }
  Dataset& dataset = table.corpus.dataset;
  std::vector<std::vector<double>> values;
  for (const nlohmann::json& item : items_in_order(parts)) {
    const auto id = item.at("recording").get<std::string>();
    ++table.recordings;
    for (const nlohmann::json& row : item.at("rows")) {
      values.push_back(row.at("features").get<std::vector<double>>());
      if (values.back().size() != dataset.columns.size())
        throw Error("merge", "recording " + id + ": a row of " +
                                 std::to_string(values.back().size()) + " features, not " +
                                 std::to_string(dataset.columns.size()));
      dataset.classes.push_back(row.at("class").get<std::string>());
      dataset.subjects.push_back(row.at("subject").get<std::string>());
      dataset.recordings.push_back(id);
      dataset.segment_ids.push_back(row.at("segment_id").get<int64_t>());
      dataset.metadata.push_back(row.at("metadata").get<Metadata>());
    }
    for (const nlohmann::json& skip : item.at("skipped"))
      table.corpus.skipped.push_back({id, skip.at("segment_id").get<int64_t>(),
                                      skip.at("t0").get<double>(), skip.at("t1").get<double>(),
                                      skip.at("reason").get<std::string>()});
    table.corpus.segments +=
        static_cast<int64_t>(item.at("rows").size() + item.at("skipped").size());
  }
  dataset.features.resize(static_cast<Eigen::Index>(values.size()),
                          static_cast<Eigen::Index>(dataset.columns.size()));
  for (size_t row = 0; row < values.size(); ++row)
    for (size_t column = 0; column < values[row].size(); ++column)
      dataset.features(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column)) =
          values[row][column];
  return table;
}

}  // namespace tactile
