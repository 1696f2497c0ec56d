#include "commands.h"

namespace tactile::cli {

// Placeholder until the command is written; it refuses to run.
void register_labels(CLI::App& app) {
  app.add_subcommand("labels", "(not yet available)")->callback([] {
    throw CLI::RuntimeError("labels: not yet available", 2);
  });
}

}  // namespace tactile::cli
