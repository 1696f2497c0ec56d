#include "tactile/formats/importer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

namespace {

std::string trimmed(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// The importers, the built-in ones made on first use. Registration happens at start-up
// (register_importer's contract); the lock keeps a late one from tearing the list.
struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<RecordingImporter>> importers;
};

Registry& registry() {
  static Registry* instance = [] {
    auto* made = new Registry;  // never destroyed: importers outlive every static user
    made->importers = builtin_importers();
    return made;
  }();
  return *instance;
}

std::string first_bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(512, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return bytes;
}

const char* kind_text(ImportOption::Kind kind) {
  switch (kind) {
    case ImportOption::Kind::kNumber:
      return "a positive number";
    case ImportOption::Kind::kCount:
      return "a positive whole number";
    case ImportOption::Kind::kList:
      return "comma-separated names";
    case ImportOption::Kind::kFile:
      return "a file";
    case ImportOption::Kind::kSwitch:
      return "a switch";
    case ImportOption::Kind::kText:
      break;
  }
  return "text";
}

}  // namespace

//---- Values ---------------------------------------------------------------------------------

std::string ImportValues::text(const std::string& flag) const {
  const auto found = values_.find(flag);
  return found == values_.end() ? std::string() : found->second;
}

std::optional<double> ImportValues::number(const std::string& flag) const {
  if (!has(flag)) return std::nullopt;
  const std::string value = trimmed(text(flag));
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(number) ||
      number <= 0.0)
    throw Error(flag, in_quotes(value) + " is not a positive number");
  return number;
}

std::optional<int64_t> ImportValues::count(const std::string& flag) const {
  const std::optional<double> value = number(flag);
  if (!value) return std::nullopt;
  if (*value != std::floor(*value) || *value > 1e15)
    throw Error(flag, in_quotes(trimmed(text(flag))) + " is not a whole number");
  return static_cast<int64_t>(*value);
}

std::vector<std::string> ImportValues::list(const std::string& flag) const {
  std::vector<std::string> items;
  const std::string value = text(flag);
  size_t start = 0;
  while (start <= value.size()) {
    const size_t comma = std::min(value.find(',', start), value.size());
    std::string item = trimmed(value.substr(start, comma - start));
    if (!item.empty()) items.push_back(std::move(item));
    start = comma + 1;
  }
  return items;
}

//---- The registry ---------------------------------------------------------------------------

bool RecordingImporter::recognises(const std::string&) const { return false; }
std::string RecordingImporter::refusal_of(const std::string&) const { return {}; }
bool RecordingImporter::writes_several(const ImportValues&) const { return false; }

void register_importer(std::unique_ptr<RecordingImporter> importer) {
  if (!importer || importer->name().empty()) throw Error("importer", "needs a name");
  Registry& list = registry();
  const std::lock_guard<std::mutex> lock(list.mutex);
  for (auto& existing : list.importers)
    if (existing->name() == importer->name()) {
      existing = std::move(importer);
      return;
    }
  list.importers.push_back(std::move(importer));
}

std::vector<const RecordingImporter*> importers() {
  Registry& list = registry();
  const std::lock_guard<std::mutex> lock(list.mutex);
  std::vector<const RecordingImporter*> all;
  for (const auto& importer : list.importers) all.push_back(importer.get());
  return all;
}

const RecordingImporter* importer_for(const std::string& path) {
  const std::vector<const RecordingImporter*> all = importers();
  const std::string extension = lower_extension(path);
  for (const RecordingImporter* importer : all) {
    const std::vector<std::string> claimed = importer->extensions();
    if (std::find(claimed.begin(), claimed.end(), extension) != claimed.end()) return importer;
  }
  std::error_code error;
  if (path.empty() || !std::filesystem::is_regular_file(path, error)) return nullptr;
  const std::string bytes = first_bytes_of(path);
  for (const RecordingImporter* importer : all)
    if (importer->recognises(bytes)) return importer;
  return nullptr;
}

std::vector<std::string> import_extensions() {
  std::vector<std::string> extensions;
  for (const RecordingImporter* importer : importers())
    for (const std::string& extension : importer->extensions())
      if (std::find(extensions.begin(), extensions.end(), extension) == extensions.end())
        extensions.push_back(extension);
  return extensions;
}

std::string import_formats_text() {
  std::vector<std::string> formats;
  for (const RecordingImporter* importer : importers())
    formats.push_back(importer->name() + " (" + joined(importer->extensions()) + ")");
  return joined(formats);
}

std::vector<SharedImportOption> all_import_options() {
  std::vector<SharedImportOption> shared;
  for (const RecordingImporter* importer : importers())
    for (const ImportOption& option : importer->options()) {
      auto found = std::find_if(shared.begin(), shared.end(), [&](const SharedImportOption& s) {
        return s.option.flag == option.flag;
      });
      if (found == shared.end()) {
        shared.push_back({option, {importer->name()}, {option.help}});
      } else {
        if (found->option.kind != option.kind)
          throw Error(importer->name(), "declares " + option.flag + " as " +
                                            kind_text(option.kind) + ", another format as " +
                                            kind_text(found->option.kind));
        found->formats.push_back(importer->name());
        found->helps.push_back(option.help);
      }
    }
  return shared;
}

void check_import_values(const RecordingImporter& importer, const ImportValues& values) {
  const std::vector<ImportOption> options = importer.options();
  std::vector<std::string> flags;
  for (const ImportOption& option : options) flags.push_back(option.flag);
  for (const auto& given : values.all()) {
    const std::string& flag = given.first;
    const std::string& text = given.second;
    const auto option = std::find_if(options.begin(), options.end(),
                                     [&flag](const ImportOption& o) { return o.flag == flag; });
    if (option == options.end()) {
      const std::string reason = importer.refusal_of(flag);
      if (!reason.empty()) throw Error(flag, reason);
      throw Error(flag, "is not an option of " + importer.name() + " files (theirs: " +
                            (flags.empty() ? std::string("none") : joined(flags)) + ")");
    }
    switch (option->kind) {
      case ImportOption::Kind::kNumber:
        values.number(flag);
        break;
      case ImportOption::Kind::kCount:
        values.count(flag);
        break;
      case ImportOption::Kind::kSwitch:
        if (text != "1" && text != "0")
          throw Error(flag, "is a switch: it takes no value (" + in_quotes(text) + ")");
        break;
      default:
        break;
    }
    if (!option->only_with.empty() && !values.on(option->only_with))
      throw Error(flag, "only with " + option->only_with);
    if (!option->never_with.empty() && values.on(option->never_with))
      throw Error(flag, "not with " + option->never_with);
  }
}

}  // namespace tactile
