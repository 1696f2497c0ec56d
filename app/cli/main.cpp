// `tactile`: the command line for every headless job.
#include <CLI/CLI.hpp>
#include <iostream>

#include "tactile/error.h"

int main(int argc, char** argv) {
  CLI::App app{"tactile: headless jobs on touch recordings from robot skins"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const tactile::Error& error) {
    std::cerr << "tactile: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
