// `tactile`: the command line for every headless job. Core only, no ImGui.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/ml/svm.h"

int main(int argc, char** argv) {
  CLI::App app{"tactile: headless jobs on touch recordings from robot skins"};
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::help);
  // Registration order is the order `tactile --help` lists the commands.
  tactile::cli::register_info(app);
  tactile::cli::register_import(app);
  tactile::cli::register_export(app);
  tactile::cli::register_labels(app);
  tactile::cli::register_segment(app);
  tactile::cli::register_features(app);
  tactile::cli::register_simulate(app);
  tactile::cli::register_stream_sim(app);
  tactile::cli::register_stream_listen(app);
  tactile::cli::register_evaluate(app);
  tactile::cli::register_experiment(app);
  tactile::cli::register_verify(app);
  tactile::cli::register_predict(app);
  tactile::cli::register_merge(app);
  tactile::cli::register_cluster(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const tactile::Error& error) {
    std::cerr << "tactile: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "tactile: " << error.what() << "\n";
    return 1;
  }
  if (const int64_t warnings = tactile::ml::svm_iteration_limit_warnings())
    std::cerr << "tactile: libsvm stopped at its iteration limit in " << warnings
              << " training run(s); those SVMs may be less accurate\n";
  return 0;
}
