// `tactile`: the command line for every headless job, as a function, so that a program that adds
// its own formats or skins (tests/cli/seventh_format) runs the same command line. Core only.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/ml/svm.h"

namespace tactile::cli {

int run(int argc, char** argv) {
  CLI::App app{"tactile: headless jobs on touch recordings from robot skins"};
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::help);
  // Registration order is the order `tactile --help` lists the commands.
  register_info(app);
  register_import(app);
  register_export(app);
  register_labels(app);
  register_segment(app);
  register_features(app);
  register_simulate(app);
  register_stream_sim(app);
  register_stream_listen(app);
  register_evaluate(app);
  register_experiment(app);
  register_verify(app);
  register_predict(app);
  register_merge(app);
  register_cluster(app);
  register_video(app);
  register_clip(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const Error& error) {
    std::cerr << "tactile: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "tactile: " << error.what() << "\n";
    return 1;
  }
  if (const int64_t warnings = ml::svm_iteration_limit_warnings())
    std::cerr << "tactile: libsvm stopped at its iteration limit in " << warnings
              << " training run(s); those SVMs may be less accurate\n";
  return 0;
}

}  // namespace tactile::cli
