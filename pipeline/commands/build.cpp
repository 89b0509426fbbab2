#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"

#include <CLI/CLI.hpp>

namespace ligsim::cli {

void add_build_commands(CLI::App& app)
{
  auto* command = app.add_subcommand("build", "not implemented yet");
  command->callback([] { fail("'build' is not implemented yet"); });
}

} // namespace ligsim::cli
