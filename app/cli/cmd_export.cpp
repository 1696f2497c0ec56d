// `tactile export FILE.h5 --csv OUT.csv [--stream NAME]`: one stream as a long CSV,
// read from the file block by block.
#include <iostream>
#include <memory>

#include "commands.h"
#include "tactile/formats/csv_files.h"
#include "tactile/io/hdf5_file.h"

namespace tactile::cli {

namespace {

struct ExportOptions {
  std::string file;
  std::string csv;
  std::string stream;
};

void run_export(const ExportOptions& options) {
  const RecordingFile file(options.file);
  export_csv_long(options.csv, file, options.stream);
  const StreamInfo& stream = options.stream.empty() && !file.streams().empty()
                                 ? file.streams().front()
                                 : file.stream(options.stream);
  std::cout << "wrote " << options.csv << ": stream " << stream.name << ", " << stream.sample_count
            << " samples x " << stream.channels.size() << " channels\n";
}

}  // namespace

void register_export(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand("export", "Write one stream of a recording as CSV");
  command->add_option("FILE", options->file, "Recording file (.h5)")->required();
  command->add_option("--csv", options->csv, "Output CSV: time_s, then one column per channel")
      ->required();
  command->add_option("--stream", options->stream, "Stream to export (default: the first)");
  command->callback([options] { run_export(*options); });
}

}  // namespace tactile::cli
