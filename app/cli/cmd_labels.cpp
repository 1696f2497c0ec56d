// `tactile labels`: read a label database from the command line.
//   tactile labels export DB --csv OUT | --json OUT [--recording R] [--source S]
//   tactile labels list DB [--recording R] [--json]
//   tactile labels classes DB SKIN
// Every subcommand opens an existing database only: a mistyped path must not
// leave a new empty database behind.
#include <algorithm>
#include <charconv>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/label_store.h"

namespace tactile::cli {

namespace {

struct LabelsOptions {
  std::string database, csv, json, recording, source, skin;
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

std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
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
    rows.push_back({std::to_string(label.id), label.recording, number_text(label.t0),
                    number_text(label.t1), label.region, label.class_name, label.annotator,
                    to_string(label.source), number_text(label.confidence), one_line(label.note)});
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

  CLI::App* classes_command =
      labels->add_subcommand("classes", "Print a skin's class vocabulary, one per line");
  classes_command->add_option("db", options->database, "Label database (SQLite)")->required();
  classes_command->add_option("skin", options->skin, "Skin id: nao, tsa, fur, robovie, flux")
      ->required();
  classes_command->callback([options] { run_classes(*options); });
}

}  // namespace tactile::cli
