#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"

#include <CLI/CLI.hpp>

namespace ligsim::cli {

void add_simulate_command(CLI::App& app)
{
  auto* command = app.add_subcommand("simulate", "not implemented yet");
  command->callback([] { fail("'simulate' is not implemented yet"); });
}

} // namespace ligsim::cli
