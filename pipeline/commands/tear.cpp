#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"

#include <CLI/CLI.hpp>

namespace ligsim::cli {

void add_tear_command(CLI::App& app)
{
  auto* command = app.add_subcommand("tear", "not implemented yet");
  command->callback([] { fail("'tear' is not implemented yet"); });
}

} // namespace ligsim::cli
