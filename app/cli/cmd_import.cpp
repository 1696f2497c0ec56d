// `tactile import FILE --layout ID --out FILE.h5|FOLDER [--labels DB]`: a recording from what
// other programs publish (docs/IMPORT.md). The formats and their flags are the importers'
// (tactile/formats/importer.h): every flag an importer declares is added here, with the help
// it gives and the formats that take it; the import itself is core's
// (tactile/formats/import.h), shared with the workbench.
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <vector>

#include "commands.h"
#include "tactile/formats/import.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

// The parsed flags: the fixed ones in `options`, each format flag's value by its kind: text,
// a list's items (given comma-separated or repeated), a switch's state.
struct ImportArguments {
  FileImportOptions options;
  std::map<std::string, std::string> texts;
  std::map<std::string, std::vector<std::string>> lists;
  std::map<std::string, bool> switches;
  std::map<std::string, const CLI::Option*> parsed;
};

void run_import(ImportArguments& arguments) {
  FileImportOptions& options = arguments.options;
  for (const auto& [flag, option] : arguments.parsed) {
    if (option->count() == 0) continue;
    if (arguments.switches.count(flag))
      options.values.set_switch(flag, arguments.switches[flag]);
    else if (arguments.lists.count(flag))
      options.values.set(flag, joined(arguments.lists[flag], ","));
    else
      options.values.set(flag, arguments.texts[flag]);
  }
  const FileImportReport report = import_file(
      options, {}, [](const ImportedFile& file) { std::cout << imported_file_line(file) << "\n"; });
  if (report.labels == 0) return;
  const std::string kind =
      options.annotator.empty() ? "ground-truth labels" : "labels of " + options.annotator;
  if (options.labels.empty()) {
    std::cerr << "tactile import: " << report.labels << " " << kind
              << " not stored: no --labels database given\n";
    return;
  }
  std::cout << "stored " << report.stored << " " << kind << " in " << options.labels << "\n";
}

// "Sampling rate in Hz [CSV, NumPy, ...]": the formats that take an option, each help once
// with the formats that give it.
std::string help_of(const SharedImportOption& shared) {
  std::vector<std::string> helps;
  std::vector<std::vector<std::string>> formats;
  for (size_t k = 0; k < shared.helps.size(); ++k) {
    const auto found = std::find(helps.begin(), helps.end(), shared.helps[k]);
    if (found == helps.end()) {
      helps.push_back(shared.helps[k]);
      formats.push_back({shared.formats[k]});
    } else {
      formats[static_cast<size_t>(found - helps.begin())].push_back(shared.formats[k]);
    }
  }
  // Helps that differ in the middle ("Classes ...: a JSON key; names, ...") say their common
  // start (to its last ": ") and end (from its first "; ") once.
  const auto common = [&](auto same) {
    size_t n = 0;
    while (std::all_of(helps.begin(), helps.end(), [&](const std::string& help) {
      return n < help.size() && same(help, n) == same(helps.front(), n);
    }))
      ++n;
    return n;
  };
  size_t start = 0, end = 0;
  if (helps.size() > 1) {
    const size_t prefix = common([](const std::string& help, size_t n) { return help[n]; });
    const size_t colon = helps.front().rfind(": ", prefix < 2 ? 0 : prefix - 2);
    start = colon == std::string::npos || colon + 2 > prefix ? 0 : colon + 2;
    const size_t suffix =
        common([](const std::string& help, size_t n) { return help[help.size() - 1 - n]; });
    const std::string& first = helps.front();
    const size_t semicolon = first.find("; ", first.size() - suffix);
    end = semicolon == std::string::npos ? 0 : first.size() - semicolon;
    for (const std::string& help : helps)
      if (start + end >= help.size()) start = end = 0;  // nothing would be left between
  }
  std::string text = helps.front().substr(0, start);
  for (size_t k = 0; k < helps.size(); ++k)
    text += (k > 0 ? "; " : "") + helps[k].substr(start, helps[k].size() - start - end) + " [" +
            joined(formats[k]) + "]";
  return text + helps.front().substr(helps.front().size() - end);
}

const char* type_name(ImportOption::Kind kind) {
  switch (kind) {
    case ImportOption::Kind::kNumber:
      return "NUMBER";
    case ImportOption::Kind::kCount:
      return "COUNT";
    case ImportOption::Kind::kList:
      return "A,B,...";
    case ImportOption::Kind::kFile:
      return "FILE";
    default:
      return "TEXT";
  }
}

}  // namespace

void register_import(CLI::App& app) {
  auto arguments = std::make_shared<ImportArguments>();
  FileImportOptions* options = &arguments->options;
  CLI::App* command = app.add_subcommand(
      "import", "Convert other programs' data to recordings: " + import_formats_text());
  command->add_option("FILE", options->file, "The file: " + import_formats_text())->required();
  command
      ->add_option("--layout", options->layout,
                   "Layout id: " + joined(known_layout_ids()) + ", grid:RxC, strip:N")
      ->required();
  command
      ->add_option("--out", options->out,
                   "Output recording file (.h5), or a folder when the import makes one recording "
                   "per group")
      ->required();
  command->add_option("--labels", options->labels,
                      "Label database (SQLite) for the file's labels (its ground truth)");
  command->add_option("--recording-id", options->recording_id,
                      "Recording id (default: the output file's stem)");
  command->add_option(
      "--annotator", options->annotator,
      "Store the file's labels as this annotator's (replacing theirs of the recording) "
      "instead of the ground truth");
  // The formats' own flags, each once; which format takes which is checked at the import.
  for (const SharedImportOption& shared : all_import_options()) {
    const std::string& flag = shared.option.flag;
    switch (shared.option.kind) {
      case ImportOption::Kind::kSwitch:
        arguments->switches[flag] = false;
        arguments->parsed[flag] =
            command->add_flag(flag, arguments->switches[flag], help_of(shared));
        break;
      case ImportOption::Kind::kList:
        arguments->parsed[flag] = command->add_option(flag, arguments->lists[flag], help_of(shared))
                                      ->delimiter(',')
                                      ->type_name(type_name(shared.option.kind));
        break;
      default:
        arguments->parsed[flag] = command->add_option(flag, arguments->texts[flag], help_of(shared))
                                      ->type_name(type_name(shared.option.kind));
        break;
    }
  }
  command->callback([arguments] { run_import(*arguments); });
}

}  // namespace tactile::cli
