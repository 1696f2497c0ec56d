#pragma once
// Repeats of one experiment (`tactile experiment NAME --repeats R`): R runs with the seeds
// S, S+1, ..., S+R-1, each simulating into its own folder WORK/seed-S, and a summary of the
// figures they give (mean, standard deviation, min and max over the runs) beside the
// paper's. The runs are the items of `--shard I/N` (tactile/shards/shard.h) in seed order; a run
// is kept as JSON (report_to_json) so the summary and the text assembled from every shard's
// runs are the ones a single process gives.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tactile/experiments/experiment.h"
#include "tactile/shards/shard.h"

namespace tactile::experiments {

struct RepeatsJob {
  std::string name;  // the experiment
  uint64_t first_seed = 1;
  int repeats = 1;
  bool quick = false;
};

struct RepeatRun {
  uint64_t seed = 0;
  ExperimentReport report;
};

// One figure of the report over the runs: an accuracy of the report JSON (the headline, an
// entry of its "tables" or a row such an entry lists), in the report's order.
struct RepeatFigure {
  std::string table;            // "headline", or the report table's title
  std::string title;            // "accuracy" (the table's own), or the row's name
  std::optional<double> paper;  // the paper's figure, when it reports one
  std::vector<double> values;   // one per run that gives it, in seed order
  double mean = 0;
  double sd = 0;  // sample standard deviation (1/(n-1)); 0 for one run
  double min = 0;
  double max = 0;
};

// The seeds of a job: first_seed + k for k = 0..repeats-1. Throws tactile::Error naming
// --repeats when it is below 1.
std::vector<uint64_t> repeat_seeds(const RepeatsJob& job);
// The item keys of a job in seed order, "NAME#seed-S" (the shards' plan).
std::vector<std::string> repeats_plan(const RepeatsJob& job);
// Where run `seed` simulates: WORK/seed-S.
std::string repeat_work_dir(const std::string& work_dir, uint64_t seed);

// Runs the shard's repeats (all of them when the shard is not active) in seed order, each
// with `options` but its own seed and work folder (options.work_dir/seed-S). When
// remove_work is true each run's folder is removed once the run ends (or fails).
// `options.progress` sees each run's stages, prefixed "seed S: " when there is more than one.
std::vector<RepeatRun> run_repeats(const RepeatsJob& job, const ExperimentOptions& options,
                                   const Shard& shard = {}, bool remove_work = false);

// A report as JSON and back: {"name", "paper", "json", "tables": [{title, columns, rows,
// note}]}; report_from_json(report_to_json(r)) formats as r does. Throws tactile::Error on a
// document that is not one.
nlohmann::json report_to_json(const ExperimentReport& report);
ExperimentReport report_from_json(const nlohmann::json& document);

// The figures of the runs (in seed order), each over the runs that give it; figures of one
// table follow each other.
std::vector<RepeatFigure> summarise_repeats(const std::vector<RepeatRun>& runs);

// The repeats as one JSON document: {"name", "paper", "quick", "seed", "repeats", "runs":
// [{"seed", "report": the report JSON as --json prints one run, "tables": its text tables}],
// "summary": [{"table", "figure", "paper_accuracy", "runs", "mean", "sd", "min", "max",
// "values"}]}. It holds no time and no path, so a job's document has the same bytes wherever it
// runs.
nlohmann::json repeats_document(const RepeatsJob& job, const std::vector<RepeatRun>& runs);
// Writes repeats_document atomically (2-space indent). Throws tactile::Error naming the path.
void write_repeats_file(const std::string& path, const nlohmann::json& document);

// Each run's tables as format_report prints them under a "seed S" line, then the summary:
// a table per report table, a row per figure, ours as mean, sd, min and max in % beside the
// paper's.
std::string format_repeats(const RepeatsJob& job, const std::vector<RepeatRun>& runs);

// `tactile experiment all --repeats R`: every experiment's figures that the paper reports too,
// over the same seeds, as one table.
struct PaperRow {
  std::string experiment;
  RepeatFigure figure;  // figure.paper is set
};
// The rows of one experiment's runs (summarise_repeats), those with a paper's figure.
std::vector<PaperRow> paper_rows(const std::string& experiment, const std::vector<RepeatRun>& runs);
// "| experiment | figure | ours %, mean (sd) over N runs | paper % | ours - paper |" in Markdown
// (the reports' fractions in percent), the rows more than `flag` points from the paper marked.
std::string format_paper_rows(const std::vector<PaperRow>& rows, int repeats, double flag = 5.0);
nlohmann::json paper_rows_json(const std::vector<PaperRow>& rows, int repeats);

// A shard's `done` entry for a run ({"index", "seed", "report": report_to_json}) and back.
nlohmann::json repeat_item(size_t index, const RepeatRun& run);
RepeatRun repeat_from_item(const nlohmann::json& item);

}  // namespace tactile::experiments
