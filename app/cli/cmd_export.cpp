#include "commands.h"

namespace tactile::cli {

// Placeholder until the command is written; it refuses to run.
void register_export(CLI::App& app) {
  app.add_subcommand("export", "(not yet available)")->callback([] {
    throw CLI::RuntimeError("export: not yet available", 2);
  });
}

}  // namespace tactile::cli
