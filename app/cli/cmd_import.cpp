#include "commands.h"

namespace tactile::cli {

// Placeholder until the command is written; it refuses to run.
void register_import(CLI::App& app) {
  app.add_subcommand("import", "(not yet available)")->callback([] {
    throw CLI::RuntimeError("import: not yet available", 2);
  });
}

}  // namespace tactile::cli
