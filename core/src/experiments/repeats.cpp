// Repeats of one experiment over consecutive seeds, their summary and their JSON, for
// `tactile experiment --repeats R` and its shards.
#include "tactile/experiments/repeats.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <span>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/stats/statistics.h"
#include "tactile/text.h"

namespace tactile::experiments {

namespace {

// Removes a run's folder when the run ends or fails (a folder that cannot be removed is
// left, never an error over the run's own).
class RepeatFolderCleanup {
 public:
  explicit RepeatFolderCleanup(std::string folder) : folder_(std::move(folder)) {}
  ~RepeatFolderCleanup() {
    if (folder_.empty()) return;
    std::error_code error;
    std::filesystem::remove_all(folder_, error);
  }
  RepeatFolderCleanup(const RepeatFolderCleanup&) = delete;
  RepeatFolderCleanup& operator=(const RepeatFolderCleanup&) = delete;

 private:
  std::string folder_;
};

// A summary row's name for an object of the report JSON that holds an accuracy: its title,
// or what names the cell (kaboli-compare's entries are features x classifier, tsa's
// classifiers a classifier), or `fallback`.
std::string repeat_figure_title(const nlohmann::json& entry, const std::string& fallback) {
  if (entry.contains("title") && entry["title"].is_string()) return entry["title"];
  std::vector<std::string> parts;
  for (const char* key : {"features", "classifier"})
    if (entry.contains(key) && entry[key].is_string()) parts.push_back(entry[key]);
  if (!parts.empty()) return joined(parts, " / ");
  return fallback;
}

std::optional<double> repeat_number(const nlohmann::json& object, const char* key) {
  // A figure that is not a finite number (NaN is written as null) is not given.
  if (!object.is_object() || !object.contains(key) || !object[key].is_number()) return {};
  const double value = object[key].get<double>();
  if (!std::isfinite(value)) return {};
  return value;
}

std::string repeat_percent(double fraction, int decimals) {
  return fixed_text(100.0 * fraction, decimals);
}

nlohmann::json repeat_table_json(const ReportTable& table) {
  return {{"title", table.title},
          {"columns", table.columns},
          {"rows", table.rows},
          {"note", table.note}};
}

}  // namespace

std::vector<uint64_t> repeat_seeds(const RepeatsJob& job) {
  if (job.repeats < 1)
    throw Error("--repeats", "must be 1 or more, not " + std::to_string(job.repeats));
  std::vector<uint64_t> seeds;
  for (int run = 0; run < job.repeats; ++run)
    seeds.push_back(job.first_seed + static_cast<uint64_t>(run));
  return seeds;
}

std::vector<std::string> repeats_plan(const RepeatsJob& job) {
  std::vector<std::string> keys;
  for (const uint64_t seed : repeat_seeds(job))
    keys.push_back(job.name + "#seed-" + std::to_string(seed));
  return keys;
}

std::string repeat_work_dir(const std::string& work_dir, uint64_t seed) {
  if (work_dir.empty()) return {};
  return (std::filesystem::path(work_dir) / ("seed-" + std::to_string(seed))).string();
}

std::vector<RepeatRun> run_repeats(const RepeatsJob& job, const ExperimentOptions& options,
                                   const Shard& shard, bool remove_work) {
  const std::vector<uint64_t> seeds = repeat_seeds(job);
  std::vector<RepeatRun> runs;
  for (const size_t item : shard.items_of(seeds.size())) {
    ExperimentOptions run_options = options;
    run_options.seed = seeds[item];
    run_options.quick = job.quick;
    run_options.work_dir = repeat_work_dir(options.work_dir, seeds[item]);
    if (!run_options.work_dir.empty()) {
      std::error_code error;
      std::filesystem::create_directories(run_options.work_dir, error);
      if (error)
        throw Error(run_options.work_dir,
                    "cannot create the run's work folder: " + error.message());
    }
    if (options.progress && seeds.size() > 1) {
      const std::string prefix = "seed " + std::to_string(seeds[item]) + ": ";
      run_options.progress = [prefix, progress = options.progress](const std::string& stage,
                                                                   int done, int total) {
        progress(prefix + stage, done, total);
      };
    }
    const RepeatFolderCleanup cleanup(remove_work ? run_options.work_dir : std::string());
    runs.push_back({seeds[item], run_experiment(job.name, run_options)});
  }
  return runs;
}

nlohmann::json report_to_json(const ExperimentReport& report) {
  nlohmann::json tables = nlohmann::json::array();
  for (const ReportTable& table : report.tables) tables.push_back(repeat_table_json(table));
  return {
      {"name", report.name}, {"paper", report.paper}, {"json", report.json}, {"tables", tables}};
}

ExperimentReport report_from_json(const nlohmann::json& document) {
  try {
    ExperimentReport report;
    report.name = document.at("name").get<std::string>();
    report.paper = document.at("paper").get<std::string>();
    report.json = document.at("json");
    for (const nlohmann::json& table : document.at("tables")) {
      ReportTable entry;
      entry.title = table.at("title").get<std::string>();
      entry.columns = table.at("columns").get<std::vector<std::string>>();
      entry.rows = table.at("rows").get<std::vector<std::vector<std::string>>>();
      entry.note = table.at("note").get<std::string>();
      report.tables.push_back(std::move(entry));
    }
    return report;
  } catch (const nlohmann::json::exception& error) {
    throw Error("experiment report", std::string("not a report: ") + error.what());
  }
}

std::vector<RepeatFigure> summarise_repeats(const std::vector<RepeatRun>& runs) {
  std::vector<RepeatFigure> figures;
  std::map<std::string, size_t> position;  // table + "\n" + title -> index in figures
  const auto add = [&](const std::string& table, const std::string& title,
                       const nlohmann::json& object) {
    const std::optional<double> value = repeat_number(object, "accuracy");
    if (!value) return;
    auto [found, inserted] = position.emplace(table + "\n" + title, figures.size());
    if (inserted) figures.push_back({table, title, repeat_number(object, "paper_accuracy"), {}});
    RepeatFigure& figure = figures[found->second];
    if (!figure.paper) figure.paper = repeat_number(object, "paper_accuracy");
    figure.values.push_back(*value);
  };
  for (const RepeatRun& run : runs) {
    const nlohmann::json& json = run.report.json;
    add("headline", "accuracy", json);
    if (!json.is_object() || !json.contains("tables") || !json["tables"].is_array()) continue;
    // Entries without a title are cells of the report's one table (or of "tables").
    const std::string untitled =
        run.report.tables.size() == 1 ? run.report.tables.front().title : std::string("tables");
    for (size_t index = 0; index < json["tables"].size(); ++index) {
      const nlohmann::json& entry = json["tables"][index];
      const bool titled = entry.contains("title") && entry["title"].is_string();
      const std::string table = titled ? entry["title"].get<std::string>() : untitled;
      add(table,
          titled ? "accuracy" : repeat_figure_title(entry, "entry " + std::to_string(index + 1)),
          entry);
      if (!entry.is_object()) continue;
      // Rows of the table kept as a list of objects (tsa's classifiers).
      for (const auto& [key, value] : entry.items()) {
        if (!value.is_array()) continue;
        for (size_t row = 0; row < value.size(); ++row)
          if (value[row].is_object())
            add(table, repeat_figure_title(value[row], key + " " + std::to_string(row + 1)),
                value[row]);
      }
    }
  }
  for (RepeatFigure& figure : figures) {
    const std::span<const double> values(figure.values);
    figure.mean = stats::mean(values);
    figure.sd = stats::sample_std(values);
    figure.min = *std::min_element(values.begin(), values.end());
    figure.max = *std::max_element(values.begin(), values.end());
  }
  return figures;
}

nlohmann::json repeats_document(const RepeatsJob& job, const std::vector<RepeatRun>& runs) {
  nlohmann::json document;
  document["name"] = job.name;
  document["paper"] = runs.empty() ? std::string() : runs.front().report.paper;
  document["quick"] = job.quick;
  document["seed"] = job.first_seed;
  document["repeats"] = job.repeats;
  nlohmann::json run_list = nlohmann::json::array();
  for (const RepeatRun& run : runs) {
    nlohmann::json tables = nlohmann::json::array();
    for (const ReportTable& table : run.report.tables) tables.push_back(repeat_table_json(table));
    run_list.push_back({{"seed", run.seed}, {"report", run.report.json}, {"tables", tables}});
  }
  document["runs"] = run_list;
  nlohmann::json summary = nlohmann::json::array();
  for (const RepeatFigure& figure : summarise_repeats(runs))
    summary.push_back(
        {{"table", figure.table},
         {"figure", figure.title},
         {"paper_accuracy", figure.paper ? nlohmann::json(*figure.paper) : nlohmann::json(nullptr)},
         {"runs", figure.values.size()},
         {"mean", figure.mean},
         {"sd", figure.sd},
         {"min", figure.min},
         {"max", figure.max},
         {"values", figure.values}});
  document["summary"] = summary;
  return document;
}

void write_repeats_file(const std::string& path, const nlohmann::json& document) {
  write_file_atomically(path, document.dump(2) + "\n", "experiment result");
}

std::string format_repeats(const RepeatsJob& job, const std::vector<RepeatRun>& runs) {
  std::string text;
  for (const RepeatRun& run : runs) {
    text += "==== seed " + std::to_string(run.seed) + " ====\n";
    text += format_report(run.report) + "\n";
  }
  ExperimentReport summary;
  summary.name = job.name + ": " + std::to_string(job.repeats) + " repeats";
  summary.paper = "seeds " + std::to_string(job.first_seed) + ".." +
                  std::to_string(job.first_seed + static_cast<uint64_t>(job.repeats) - 1);
  // One summary table per table of the report, in the order the figures first appear.
  for (const RepeatFigure& figure : summarise_repeats(runs)) {
    const std::string title = "Summary: " + figure.table;
    if (summary.tables.empty() || summary.tables.back().title != title) {
      ReportTable table;
      table.title = title;
      table.columns = {"figure", "runs", "mean %", "sd %", "min %", "max %", "paper %"};
      summary.tables.push_back(std::move(table));
    }
    summary.tables.back().rows.push_back(
        {figure.title, std::to_string(figure.values.size()), repeat_percent(figure.mean, 1),
         repeat_percent(figure.sd, 2), repeat_percent(figure.min, 1), repeat_percent(figure.max, 1),
         figure.paper ? repeat_percent(*figure.paper, 1) : "-"});
  }
  if (!summary.tables.empty())
    summary.tables.back().note =
        "Ours over the repeats: each accuracy of every run's report, over the runs that give "
        "it; sd is the sample standard deviation (n - 1).";
  return text + format_report(summary);
}

nlohmann::json repeat_item(size_t index, const RepeatRun& run) {
  return {{"index", index}, {"seed", run.seed}, {"report", report_to_json(run.report)}};
}

RepeatRun repeat_from_item(const nlohmann::json& item) {
  if (!item.contains("seed") || !item["seed"].is_number_unsigned() || !item.contains("report"))
    throw Error("experiment part", "an item without its seed or report");
  return {item["seed"].get<uint64_t>(), report_from_json(item["report"])};
}

std::vector<PaperRow> paper_rows(const std::string& experiment,
                                 const std::vector<RepeatRun>& runs) {
  std::vector<PaperRow> rows;
  for (RepeatFigure& figure : summarise_repeats(runs))
    if (figure.paper) rows.push_back({experiment, std::move(figure)});
  return rows;
}

std::string format_paper_rows(const std::vector<PaperRow>& rows, int repeats, double flag) {
  // The reports' figures are fractions; the table says them in percent, as the papers do.
  std::string text = "| experiment | figure | ours %, mean (sd) over " + std::to_string(repeats) +
                     " runs | paper % | ours - paper (points) |\n|---|---|---|---|---|\n";
  int far = 0;
  for (const PaperRow& row : rows) {
    const RepeatFigure& figure = row.figure;
    const double difference = 100.0 * (figure.mean - *figure.paper);
    const bool outside = std::abs(difference) > flag;
    far += outside;
    const std::string name =
        figure.table == "headline" ? figure.title : figure.table + ": " + figure.title;
    text += "| " + row.experiment + " | " + name + " | " + fixed_text(100.0 * figure.mean, 1) +
            " (" + fixed_text(100.0 * figure.sd, 1) + ") | " +
            fixed_text(100.0 * *figure.paper, 1) + " | " + (difference >= 0 ? "+" : "") +
            fixed_text(difference, 1) + (outside ? " **" : "") + " |\n";
  }
  text += "\n" + std::to_string(rows.size()) + " figures; " + std::to_string(far) + " more than " +
          fixed_text(flag, 0) + " points from the paper (**)\n";
  return text;
}

nlohmann::json paper_rows_json(const std::vector<PaperRow>& rows, int repeats) {
  nlohmann::json list = nlohmann::json::array();
  for (const PaperRow& row : rows)
    list.push_back({{"experiment", row.experiment},
                    {"table", row.figure.table},
                    {"figure", row.figure.title},
                    {"values", row.figure.values},
                    {"mean", row.figure.mean},
                    {"sd", row.figure.sd},
                    {"paper", *row.figure.paper},
                    {"difference", row.figure.mean - *row.figure.paper}});
  return {{"repeats", repeats}, {"figures", list}};
}

}  // namespace tactile::experiments
