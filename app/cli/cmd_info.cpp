// `tactile info FILE [--labels DB] [--json]`: what a recording holds (its labels: in DB, else in
// labels.db beside it), read from its
// attributes and shapes only (no samples are loaded).
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "commands.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"

namespace tactile::cli {

namespace {

struct InfoOptions {
  std::string file;
  std::string labels;
  bool json = false;
};

nlohmann::json info_json(const RecordingFile& file, std::optional<int64_t> label_count,
                         const std::string& labels_database) {
  nlohmann::json streams = nlohmann::json::array();
  for (const StreamInfo& stream : file.streams())
    streams.push_back({{"name", stream.name},
                       {"rate_hz", stream.rate_hz},
                       {"channels", stream.channels},
                       {"samples", stream.sample_count},
                       {"duration_s", stream.duration()}});
  return {
      {"layout", file.layout_id()},
      {"recording", file.recording_id()},
      {"metadata", file.metadata()},
      {"streams", streams},
      {"labels", label_count ? nlohmann::json(*label_count) : nlohmann::json(nullptr)},
      {"labels_database", label_count ? nlohmann::json(labels_database) : nlohmann::json(nullptr)}};
}

void print_text(const RecordingFile& file, std::optional<int64_t> label_count,
                const std::string& labels_database) {
  std::ostringstream out;
  out << "file:      " << file.path() << "\n"
      << "recording: " << file.recording_id() << "\n"
      << "layout:    " << file.layout_id() << "\n"
      << "metadata:" << (file.metadata().empty() ? "  (none)" : "") << "\n";
  for (const auto& [key, value] : file.metadata()) out << "  " << key << " = " << value << "\n";
  out << "streams:   " << file.streams().size() << "\n";
  for (const StreamInfo& stream : file.streams()) {
    out << "  " << stream.name << ": " << stream.rate_hz << " Hz, " << stream.channels.size()
        << " channels, " << stream.sample_count << " samples, " << std::fixed
        << std::setprecision(3) << stream.duration() << " s"
        << (stream.has_timestamps ? " (irregular, time stamped)" : "") << "\n";
    out.unsetf(std::ios::fixed);
  }
  out << "labels:    ";
  if (label_count)
    out << *label_count << " in " << labels_database << "\n";
  else
    out << "(no database given, and no labels.db beside the recording)\n";
  std::cout << out.str();
}

void run_info(const InfoOptions& options) {
  const RecordingFile file(options.file);
  // The database given, else the one beside the recording, as the workbench finds it.
  std::string database = options.labels;
  if (database.empty()) {
    const std::filesystem::path beside =
        std::filesystem::path(options.file).parent_path() / "labels.db";
    std::error_code error;
    if (std::filesystem::is_regular_file(beside, error)) database = beside.string();
  }
  std::optional<int64_t> label_count;
  if (!database.empty())
    label_count = LabelStore(database, LabelStore::OpenMode::kExisting).count(file.recording_id());
  if (options.json)
    std::cout << info_json(file, label_count, database).dump(2) << "\n";
  else
    print_text(file, label_count, database);
}

}  // namespace

void register_info(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command =
      app.add_subcommand("info", "Show a recording's layout, metadata, streams and label count");
  command->add_option("FILE", options->file, "Recording file (.h5)")->required();
  command->add_option(
      "--labels", options->labels,
      "Label database (SQLite) to count labels in (default: labels.db beside the file)");
  command->add_flag("--json", options->json, "Print JSON instead of text");
  command->callback([options] { run_info(*options); });
}

}  // namespace tactile::cli
