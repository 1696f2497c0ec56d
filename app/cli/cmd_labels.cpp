// `tactile labels`: read a label database from the command line.
//   tactile labels export DB --csv OUT | --json OUT | --eaf OUT | --label-studio OUT
//                            [--recording R] [--source S] [--skin S] [--member NAME=ID|EMAIL]...
//   tactile labels import DB FILE.csv|.json|.eaf [--recording R] [--tier T[=LANE]]...
//                            [--annotator USER=LANE]... [--start-ms MS] [--recordings DIR]
//   tactile labels list DB [--recording R] [--json]
//   tactile labels classes DB SKIN
// Every subcommand opens an existing database only: a mistyped path must not
// leave a new empty database behind.
#include <algorithm>
#include <cmath>
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
#include "tactile/labels/label_file_commands.h"
#include "tactile/labels/label_format.h"
#include "tactile/labels/lanes.h"
#include "tactile/labels/quality.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct LabelsOptions {
  std::string database, recording, source, skin, file;
  std::map<std::string, std::string> outputs;  // `export`: the file of each label format's flag
  std::vector<std::string> tiers, annotators, members;
  std::string a, b, recordings;
  std::string start_ms;
  double iou = 0.5;
  bool as_json = false;
};

LabelFilter filter_from(const LabelsOptions& options) {
  LabelFilter filter;
  if (!options.recording.empty()) filter.recording = options.recording;
  if (!options.source.empty()) filter.source = label_source_option(options.source);
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
void report_damage(const std::string& database, const std::vector<std::string>& damaged) {
  if (damaged.empty()) return;
  for (const std::string& line : damaged) std::cerr << "tactile: " << line << "\n";
  throw Error(database, std::to_string(damaged.size()) +
                            " damaged row(s) or digest(s); the output leaves them out");
}

void report_damage(const LabelStore& store) { report_damage(store.path(), damage_lines(store)); }

void run_export(const LabelsOptions& options) {
  // One of the label formats' flags (labels/label_format.h), with its file.
  std::vector<std::string> flags;
  const LabelFormat* chosen = nullptr;
  std::string out;
  int given = 0;
  for (const LabelFormat* format : label_formats()) {
    flags.push_back(format->flag());
    const std::string& file = options.outputs.at(format->flag());
    if (file.empty()) continue;
    ++given;
    chosen = format;
    out = file;
  }
  if (given != 1)
    throw Error(joined(flags, "/"), "give exactly one of " + joined(flags) + " with its file");
  // --member NAME=ID|EMAIL: Label Studio's completed_by of an annotator.
  InteropExport interop;
  if (!options.members.empty() && chosen->name() != "Label Studio")
    throw Error("--member", "only for --label-studio (Label Studio's project members)");
  for (const std::string& member : options.members) {
    const size_t equals = member.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == member.size())
      throw Error("--member", "expected NAME=ID or NAME=EMAIL, got '" + member + "'");
    interop.members[member.substr(0, equals)] = member.substr(equals + 1);
  }
  std::vector<std::string> vocabulary;
  if (!options.skin.empty()) {
    const LabelStore store(options.database, LabelStore::OpenMode::kExisting);
    vocabulary = store.classes(options.skin);
    if (vocabulary.empty())
      throw Error("--skin",
                  "no class vocabulary for skin '" + options.skin + "' in " + options.database);
  }
  const LabelExport written = export_label_file(options.database, out, chosen->name(),
                                                filter_from(options), vocabulary, interop);
  report_damage(options.database, written.damaged);
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
  InteropImport interop;
  interop.recording = options.recording;
  // --tier NAME or NAME=LANE; --annotator USER=LANE.
  for (const std::string& tier : options.tiers) {
    const size_t equals = tier.find('=');
    interop.tiers[tier.substr(0, equals)] =
        equals == std::string::npos ? std::string() : tier.substr(equals + 1);
  }
  for (const std::string& annotator : options.annotators) {
    const size_t equals = annotator.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == annotator.size())
      throw Error("--annotator", "expected USER=LANE, got '" + annotator + "'");
    interop.annotators[annotator.substr(0, equals)] = annotator.substr(equals + 1);
  }
  if (!options.start_ms.empty()) {
    double start = std::nan("");
    size_t used = 0;
    try {
      start = std::stod(options.start_ms, &used);
    } catch (const std::exception&) {
    }
    if (used != options.start_ms.size() || !std::isfinite(start))
      throw Error("--start-ms",
                  "'" + options.start_ms + "' is not a Unix time in milliseconds (1592250751951)");
    interop.start_ms = start;
  }
  interop.recordings = options.recordings;
  std::cout << imported_labels_line(import_label_file(options.database, options.file, interop),
                                    options.database)
            << "\n";
}

void run_agreement(const LabelsOptions& options) {
  AgreementQuery query;
  query.database = options.database;
  query.a = options.a;
  query.b = options.b;
  query.recording = options.recording;
  query.recordings = options.recordings;
  query.iou = options.iou;
  const AgreementReport report = lane_agreement(query);
  report_damage(options.database, report.damaged);
  std::cout << (options.as_json ? agreement_json(report) : agreement_text(report));
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
  // Each label against its recording, where the recording is beside the store.
  quality.spans =
      recording_spans(labels, std::filesystem::path(options.database).parent_path().string());
  const std::vector<LabelIssue> issues = check_labels(labels, quality);
  if (options.as_json) {
    nlohmann::json list = nlohmann::json::array();
    for (const LabelIssue& issue : issues)
      list.push_back({{"kind", issue.kind},
                      {"recording", issue.recording},
                      {"t0", issue.t0},
                      {"t1", issue.t1},
                      {"label", issue.label},
                      {"what", issue.what}});
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
      labels->add_subcommand("export", "Write labels to a file of one label format");
  export_command->add_option("db", options->database, "Label database (SQLite)")->required();
  for (const LabelFormat* format : label_formats()) {
    options->outputs[format->flag()];
    export_command->add_option(format->flag(), options->outputs[format->flag()],
                               "Write " + format->description() + " to this file");
  }
  export_command->add_option("--skin", options->skin,
                             "ELAN: this skin's class vocabulary as the controlled vocabulary");
  export_command->add_option("--recording", options->recording, "Only this recording's labels");
  export_command->add_option("--source", options->source,
                             "Only labels from manual, segmenter, model or ground-truth");
  export_command->add_option("--member", options->members,
                             "Label Studio: NAME=ID or NAME=EMAIL, the project member whose "
                             "completed_by an annotator's annotations get (unmapped: none); "
                             "repeat");
  export_command->callback([options] { run_export(*options); });

  CLI::App* list_command = labels->add_subcommand("list", "Print labels as a table or as JSON");
  list_command->add_option("db", options->database, "Label database (SQLite)")->required();
  list_command->add_option("--recording", options->recording, "Only this recording's labels");
  list_command->add_option("--source", options->source,
                           "Only labels from manual, segmenter, model or ground-truth");
  list_command->add_flag("--json", options->as_json, "Print the JSON export's document");
  list_command->callback([options] { run_list(*options); });

  CLI::App* import_command = labels->add_subcommand(
      "import",
      "Add the labels of a file `labels export` writes, an ELAN .eaf or a Label Studio "
      "JSON export");
  import_command->add_option("db", options->database, "Label database (created if missing)")
      ->required();
  import_command->add_option("file", options->file, "FILE.csv, FILE.json or FILE.eaf")
      ->required()
      ->check(CLI::ExistingFile);
  import_command->add_option("--recording", options->recording,
                             "The labels' recording (ELAN, Label Studio: when the file does not "
                             "say, or to override it)");
  import_command->add_option("--tier", options->tiers,
                             "ELAN: import this tier (NAME, or NAME=LANE: ground-truth, an "
                             "annotator, segmenter:METHOD, model:NAME); repeat; default every "
                             "top-level tier");
  import_command->add_option("--annotator", options->annotators,
                             "Label Studio: USER=LANE, a user (completed_by id or email; none: "
                             "an annotation without completed_by) or model_version mapped to a "
                             "lane; repeat");
  import_command->add_option("--start-ms", options->start_ms,
                             "Label Studio: the Unix time in milliseconds of the recording's "
                             "first sample, for a TimeSeries whose time column holds dates "
                             "(default: the recording's own start, else the task's first time)");
  import_command->add_option("--recordings", options->recordings,
                             "Label Studio: folder of RECORDING.h5 whose start places epoch "
                             "milliseconds (default: the database's)");
  import_command->callback([options] { run_import(*options); });

  CLI::App* check_command = labels->add_subcommand(
      "check",
      "Labels that overlap in a lane, last implausibly long or short, segmenter events "
      "without a label, classes outside the vocabulary; exit 1 if any");
  check_command->add_option("db", options->database, "Label database (SQLite)")->required();
  check_command->add_option("--recording", options->recording, "Only this recording");
  check_command->add_option("--skin", options->skin,
                            "Check classes against this skin's vocabulary");
  check_command->add_flag("--json", options->as_json, "Print JSON");
  check_command->callback([options] { run_check(*options); });

  CLI::App* agreement_command = labels->add_subcommand(
      "agreement", "Agreement of two lanes: kappa over time, segment F1 at IoU, class confusion");
  agreement_command->add_option("db", options->database, "Label database (SQLite)")->required();
  agreement_command
      ->add_option("--a", options->a,
                   "Reference lane: ground-truth, an annotator, segmenter:METHOD, model:NAME")
      ->required();
  agreement_command->add_option("--b", options->b, "The lane compared with it")->required();
  agreement_command->add_option("--recording", options->recording, "Only this recording");
  agreement_command->add_option(
      "--recordings", options->recordings,
      "Folder of RECORDING.h5 for spans and rates (default: the database's)");
  agreement_command
      ->add_option("--iou", options->iou, "Segments match at IoU >= this (default 0.5)")
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
