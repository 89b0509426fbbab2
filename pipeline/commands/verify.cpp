#include "pipeline/commands/commands.hpp"

#include "common/error.hpp"

#include <CLI/CLI.hpp>

namespace ligsim::cli {

void add_verify_command(CLI::App& app)
{
  auto* command = app.add_subcommand("verify", "not implemented yet");
  command->callback([] { fail("'verify' is not implemented yet"); });
}

} // namespace ligsim::cli
