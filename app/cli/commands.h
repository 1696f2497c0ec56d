#pragma once
// Each `tactile` subcommand lives in its own file and registers itself here.
// A command's callback throws tactile::Error on bad input; main() prints it as
// one line on stderr and exits non-zero.

#include <CLI/CLI.hpp>

namespace tactile::cli {

void register_info(CLI::App& app);
void register_import(CLI::App& app);
void register_export(CLI::App& app);
void register_labels(CLI::App& app);
void register_segment(CLI::App& app);
void register_features(CLI::App& app);
void register_simulate(CLI::App& app);
void register_stream_sim(CLI::App& app);
void register_stream_listen(CLI::App& app);
void register_evaluate(CLI::App& app);
void register_experiment(CLI::App& app);
void register_verify(CLI::App& app);
void register_predict(CLI::App& app);

// Files as given; folders expanded to their .h5 files, sorted, so runs are repeatable.
// Throws tactile::Error naming an input that is neither, or a folder with no recording.
std::vector<std::string> recording_files(const std::vector<std::string>& inputs);

}  // namespace tactile::cli
