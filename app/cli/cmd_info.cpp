#include "commands.h"

namespace tactile::cli {

// Placeholder until the command is written; it refuses to run.
void register_info(CLI::App& app) {
  app.add_subcommand("info", "(not yet available)")->callback([] {
    throw CLI::RuntimeError("info: not yet available", 2);
  });
}

}  // namespace tactile::cli
