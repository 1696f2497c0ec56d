// `tactile labels`: read a label database from the command line.
//   tactile labels export DB --csv OUT | --json OUT [--recording R] [--source S]
//   tactile labels list DB [--recording R] [--json]
//   tactile labels classes DB SKIN
// Every subcommand opens an existing database only: a mistyped path must not
// leave a new empty database behind.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_import.h"
#include "tactile/io/label_store.h"
#include "tactile/labels/agreement.h"
#include "tactile/labels/lanes.h"
#include "tactile/labels/quality.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct LabelsOptions {
  std::string database, csv, json, recording, source, skin, file;
  std::string a, b, recordings;
  double iou = 0.5;
  bool as_json = false;
};

LabelFilter filter_from(const LabelsOptions& options) {
  LabelFilter filter;
  if (!options.recording.empty()) filter.recording = options.recording;
  if (!options.source.empty()) {
    try {
      filter.source = parse_label_source(options.source);
    } catch (const Error& error) {
      throw Error("--source", error.message());
    }
  }
  return filter;
}

// A note on one table row: line breaks and tabs shown, not obeyed.
std::string one_line(const std::string& text) {
  std::string line;
  for (char character : text) {
    if (character == '\n')
      line += "\\n";
    else if (character == '\r')
      line += "\\r";
    else if (character == '\t')
      line += "\\t";
    else
      line += character;
  }
  return line;
}

void print_table(const std::vector<Label>& labels, std::ostream& out) {
  std::vector<std::vector<std::string>> rows = {{"id", "recording", "t0", "t1", "region", "class",
                                                 "annotator", "source", "confidence", "note"}};
  for (const Label& label : labels)
    rows.push_back({std::to_string(label.id), label.recording, seconds_text(label.t0),
                    seconds_text(label.t1), label.region, label.class_name, label.annotator,
                    to_string(label.source), shortest_text(label.confidence),
                    one_line(label.note)});
  std::vector<size_t> widths(rows.front().size(), 0);
  for (const auto& row : rows)
    for (size_t column = 0; column < row.size(); ++column)
      widths[column] = std::max(widths[column], row[column].size());
  for (const auto& row : rows) {
    std::string line;
    for (size_t column = 0; column < row.size(); ++column) {
      line += row[column];
      // The last column is not padded, so lines carry no trailing blanks.
      if (column + 1 < row.size())
        line += std::string(widths[column] - row[column].size() + 2, ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << "\n";
  }
  out << labels.size() << (labels.size() == 1 ? " label" : " labels") << "\n";
}

// Damaged rows met by a read were left out of its output: each is named on stderr
// and the command fails, so a script never takes a partial export for the whole.
void report_damage(const LabelStore& store) {
  if (store.problems().empty()) return;
  for (const StoreProblem& problem : store.problems())
    std::cerr << "tactile: " << problem.where(store.path()) << ": " << problem.what << "\n";
  throw Error(store.path(), std::to_string(store.problems().size()) +
                                " damaged row(s) or digest(s); the output leaves them out");
}

void run_export(const LabelsOptions& options) {
  if (options.csv.empty() == options.json.empty())
    throw Error("--csv/--json", "give exactly one of --csv OUT or --json OUT");
  const LabelFilter filter = filter_from(options);
  LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  if (!options.csv.empty())
    store.export_csv(options.csv, filter);
  else
    store.export_json(options.json, filter);
  report_damage(store);
}

void run_list(const LabelsOptions& options) {
  const LabelFilter filter = filter_from(options);
  LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  const std::vector<Label> labels = store.list(filter);
  if (options.as_json)
    std::cout << labels_json(labels);
  else
    print_table(labels, std::cout);
  report_damage(store);
}

// All or nothing: the file is read and checked whole, then added in one transaction.
void run_import(const LabelsOptions& options) {
  const std::vector<Label> labels = read_label_file(options.file);
  LabelStore store(options.database);
  store.add_many(labels);
  std::cout << "imported " << labels.size() << (labels.size() == 1 ? " label" : " labels")
            << " into " << options.database << "\n";
}

// A lane as `--a` / `--b` name it: "ground-truth", "manual:NAME" (or just NAME),
// "segmenter:METHOD", "model:NAME".
std::vector<Label> lane_labels(const LabelStore& store, const LabelsOptions& options,
                               const std::string& lane, const char* option) {
  std::string id = lane;
  if (lane != "ground-truth" && lane.find(':') == std::string::npos) id = "manual:" + lane;
  // The form lane ids had before they followed the documentation.
  if (lane.starts_with("segmenter:segmenter:")) id = lane.substr(10);
  LabelFilter filter;
  if (!options.recording.empty()) filter.recording = options.recording;
  std::vector<Label> labels;
  for (const Label& label : store.list(filter))
    if (lane_of(label).id() == id) labels.push_back(label);
  if (labels.empty())
    throw Error(option, "no labels in lane '" + id + "' of " + store.path());
  return labels;
}

void run_agreement(const LabelsOptions& options) {
  const LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  const std::vector<Label> a = lane_labels(store, options, options.a, "--a");
  const std::vector<Label> b = lane_labels(store, options, options.b, "--b");
  report_damage(store);
  // Each recording's span and rate from its file, when it is in the folder.
  const std::filesystem::path folder =
      options.recordings.empty() ? std::filesystem::path(options.database).parent_path()
                                 : std::filesystem::path(options.recordings);
  std::map<std::string, RecordingTiming> timing;
  for (const auto* labels : {&a, &b})
    for (const Label& label : *labels) {
      if (timing.count(label.recording)) continue;
      const std::filesystem::path file = folder / (label.recording + ".h5");
      std::error_code error;
      if (!std::filesystem::exists(file, error)) continue;
      const RecordingFile recording(file.string());
      if (recording.streams().empty()) continue;
      const StreamInfo& stream = recording.streams().front();
      const double start = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
      timing[label.recording] = {start, start + stream.duration(), stream.rate_hz};
    }
  const Agreement agreement = compute_agreement(a, b, timing, options.iou);
  if (options.as_json) {
    nlohmann::json disagreements = nlohmann::json::array();
    for (const Disagreement& d : agreement.disagreements)
      disagreements.push_back({{"recording", d.recording}, {"t0", d.t0}, {"t1", d.t1},
                               {"a", d.a_class}, {"b", d.b_class}, {"kind", d.kind}});
    std::cout << nlohmann::json{{"a", options.a},
                                {"b", options.b},
                                {"kappa", agreement.kappa},
                                {"observed", agreement.observed},
                                {"expected", agreement.expected},
                                {"samples", agreement.samples},
                                {"iou", options.iou},
                                {"a_segments", agreement.a_segments},
                                {"b_segments", agreement.b_segments},
                                {"matched", agreement.matched},
                                {"precision", agreement.precision},
                                {"recall", agreement.recall},
                                {"f1", agreement.f1},
                                {"classes", agreement.classes},
                                {"confusion", agreement.confusion},
                                {"disagreements", disagreements}}
                     .dump(2)
              << "\n";
    return;
  }
  std::printf("A: %s (%lld labels)   B: %s (%lld labels)\n", options.a.c_str(),
              static_cast<long long>(agreement.a_segments), options.b.c_str(),
              static_cast<long long>(agreement.b_segments));
  std::printf("kappa over time: %.3f (observed %.3f, chance %.3f, %lld samples)\n",
              agreement.kappa, agreement.observed, agreement.expected,
              static_cast<long long>(agreement.samples));
  std::printf("segments at IoU >= %.2f: precision %.3f, recall %.3f, F1 %.3f (%lld matched)\n",
              options.iou, agreement.precision, agreement.recall, agreement.f1,
              static_cast<long long>(agreement.matched));
  std::printf("classes of matched segments (rows A, columns B):\n%12s", "");
  for (const std::string& name : agreement.classes) std::printf(" %10.10s", name.c_str());
  std::printf("\n");
  for (size_t row = 0; row < agreement.classes.size(); ++row) {
    std::printf("%12.12s", agreement.classes[row].c_str());
    for (int64_t count : agreement.confusion[row]) std::printf(" %10lld", static_cast<long long>(count));
    std::printf("\n");
  }
  std::printf("%zu disagreements\n", agreement.disagreements.size());
  for (const Disagreement& d : agreement.disagreements)
    std::printf("  %s %.3f-%.3f s: %s%s%s\n", d.recording.c_str(), d.t0, d.t1,
                d.kind == "class" ? ("class " + d.a_class + " vs " + d.b_class).c_str() : "",
                d.kind == "missed" ? ("only in A: " + d.a_class).c_str() : "",
                d.kind == "extra" ? ("only in B: " + d.b_class).c_str() : "");
}

void run_check(const LabelsOptions& options) {
  const LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  LabelFilter filter;
  if (!options.recording.empty()) filter.recording = options.recording;
  const std::vector<Label> labels = store.list(filter);
  QualityOptions quality;
  // The skin's vocabulary, or every vocabulary the store holds.
  for (const std::string& skin : skin_ids())
    if (options.skin.empty() || options.skin == skin)
      for (const std::string& name : store.classes(skin)) quality.vocabulary.insert(name);
  if (!options.skin.empty())
    for (const std::string& name : store.classes(options.skin)) quality.vocabulary.insert(name);
  const std::vector<LabelIssue> issues = check_labels(labels, quality);
  if (options.as_json) {
    nlohmann::json list = nlohmann::json::array();
    for (const LabelIssue& issue : issues)
      list.push_back({{"kind", issue.kind}, {"recording", issue.recording}, {"t0", issue.t0},
                      {"t1", issue.t1}, {"label", issue.label}, {"what", issue.what}});
    std::cout << nlohmann::json{{"labels", labels.size()}, {"issues", list}}.dump(2) << "\n";
  } else {
    for (const LabelIssue& issue : issues)
      std::printf("%s %.3f-%.3f s: %s: %s\n", issue.recording.c_str(), issue.t0, issue.t1,
                  issue.kind.c_str(), issue.what.c_str());
    std::fprintf(stderr, "checked %zu labels: %zu issue(s)\n", labels.size(), issues.size());
  }
  report_damage(store);
  if (!issues.empty()) {
    std::cout.flush();
    std::exit(1);
  }
}

void run_classes(const LabelsOptions& options) {
  LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  const std::vector<std::string> names = store.classes(options.skin);
  if (names.empty())
    throw Error(options.database, "no class vocabulary for skin '" + options.skin + "'");
  for (const std::string& name : names) std::cout << name << "\n";
}

}  // namespace

void register_labels(CLI::App& app) {
  CLI::App* labels =
      app.add_subcommand("labels", "Export, list and inspect the labels of a label database");
  labels->require_subcommand(1);
  // Shared by the callbacks, which run after parsing, when `app` is still alive.
  auto options = std::make_shared<LabelsOptions>();

  CLI::App* export_command =
      labels->add_subcommand("export", "Write labels to a CSV (RFC 4180) or JSON file");
  export_command->add_option("db", options->database, "Label database (SQLite)")->required();
  export_command->add_option("--csv", options->csv, "Write CSV to this file");
  export_command->add_option("--json", options->json, "Write JSON to this file");
  export_command->add_option("--recording", options->recording, "Only this recording's labels");
  export_command->add_option("--source", options->source,
                             "Only labels from manual, segmenter, model or ground-truth");
  export_command->callback([options] { run_export(*options); });

  CLI::App* list_command = labels->add_subcommand("list", "Print labels as a table or as JSON");
  list_command->add_option("db", options->database, "Label database (SQLite)")->required();
  list_command->add_option("--recording", options->recording, "Only this recording's labels");
  list_command->add_option("--source", options->source,
                           "Only labels from manual, segmenter, model or ground-truth");
  list_command->add_flag("--json", options->as_json, "Print the JSON export's document");
  list_command->callback([options] { run_list(*options); });

  CLI::App* import_command = labels->add_subcommand(
      "import", "Add the labels of a CSV or JSON file as `labels export` writes it");
  import_command->add_option("db", options->database, "Label database (created if missing)")
      ->required();
  import_command->add_option("file", options->file, "FILE.csv or FILE.json")
      ->required()
      ->check(CLI::ExistingFile);
  import_command->callback([options] { run_import(*options); });

  CLI::App* check_command = labels->add_subcommand(
      "check", "Labels that overlap in a lane, last implausibly long or short, segmenter events "
               "without a label, classes outside the vocabulary; exit 1 if any");
  check_command->add_option("db", options->database, "Label database (SQLite)")->required();
  check_command->add_option("--recording", options->recording, "Only this recording");
  check_command->add_option("--skin", options->skin, "Check classes against this skin's vocabulary");
  check_command->add_flag("--json", options->as_json, "Print JSON");
  check_command->callback([options] { run_check(*options); });

  CLI::App* agreement_command = labels->add_subcommand(
      "agreement", "Agreement of two lanes: kappa over time, segment F1 at IoU, class confusion");
  agreement_command->add_option("db", options->database, "Label database (SQLite)")->required();
  agreement_command->add_option("--a", options->a,
                                "Reference lane: ground-truth, an annotator, segmenter:METHOD, model:NAME")
      ->required();
  agreement_command->add_option("--b", options->b, "The lane compared with it")->required();
  agreement_command->add_option("--recording", options->recording, "Only this recording");
  agreement_command->add_option("--recordings", options->recordings,
                                "Folder of RECORDING.h5 for spans and rates (default: the database's)");
  agreement_command->add_option("--iou", options->iou, "Segments match at IoU >= this (default 0.5)")
      ->check(CLI::Range(0.01, 1.0));
  agreement_command->add_flag("--json", options->as_json, "Print JSON");
  agreement_command->callback([options] { run_agreement(*options); });

  CLI::App* classes_command =
      labels->add_subcommand("classes", "Print a skin's class vocabulary, one per line");
  classes_command->add_option("db", options->database, "Label database (SQLite)")->required();
  classes_command->add_option("skin", options->skin, "Skin id: " + joined(skin_ids()))->required();
  classes_command->callback([options] { run_classes(*options); });
}

}  // namespace tactile::cli
