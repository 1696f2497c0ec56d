// `tactile features --pipeline NAME --labels DB [--source S] [--params k=v,...]
//  [--recordings DIR] [--threads N] --out FILE.csv|.arff [--json]`
// `tactile features --list` and `tactile features --describe NAME --layout ID`
//
// One row per labelled segment of every recording that has labels of the source; the
// recording file of id R is DIR/R.h5 (DIR: the database's folder unless given). Skipped
// segments are reported on stderr and listed in OUT.log.
#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/features/feature_table.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile::cli {

namespace {

struct FeaturesOptions {
  std::string pipeline, database, source = "ground-truth", params, recordings, out;
  std::string describe, layout;
  int threads = 0;
  bool list = false, json = false;
  ShardArgs shard;
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
  if (const std::string note = extractor->layout_note(layout); !note.empty())
    std::cout << note << "\n";
}

void run_extract(const FeaturesOptions& options) {
  FeatureTableOptions table_options;
  table_options.pipeline = options.pipeline;
  table_options.params = options.params;
  table_options.database = options.database;
  table_options.source = options.source;
  table_options.recordings = options.recordings;
  table_options.out = options.out;
  table_options.threads = options.threads;
  const ShardPlan plan = shard_plan(options.shard, options.out);
  table_options.shard = plan.shard;
  ProgressBar progress("features " + options.pipeline);
  const FeatureTable table = extract_feature_table(
      table_options, [&progress](int64_t done, int64_t total) { progress.update(done, total); });
  progress.finish();
  for (const SkippedSegment& skipped : table.corpus.skipped)
    std::cerr << "skipped: " << skipped.recording << " segment " << skipped.segment_id << ": "
              << skipped.reason << "\n";
  if (plan.shard.active()) {  // its share only: the table is merge's to write
    write_shard_part(plan, feature_table_part(table, table_options));
    return;
  }
  write_feature_table(table, table_options);
  // What the pipeline chose for the table's layout (generic: per channel or whole grid).
  if (const std::string layout = table.corpus.dataset.shared_metadata("layout"); !layout.empty()) {
    const auto extractor =
        make_feature_extractor(options.pipeline, Parameters::parse(options.params, "--params"));
    if (const std::string note = extractor->layout_note(load_layout(layout)); !note.empty())
      std::cerr << note << "\n";
  }
  if (options.json)
    std::cout << feature_table_json(table, table_options);
  else
    std::cout << feature_table_line(table, table_options) << "\n";
}

}  // namespace

void merge_features(const std::vector<Part>& parts, const std::string& out) {
  FeatureTableOptions options;
  options.pipeline = parts.front().inputs.at("--pipeline").get<std::string>();
  options.out = out;
  const FeatureTable table = merge_feature_table_parts(parts);
  write_feature_table(table, options);
  std::cout << feature_table_line(table, options) << " (" << parts.size() << " parts merged)\n";
}

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
  add_shard_options(command, options->shard);
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
