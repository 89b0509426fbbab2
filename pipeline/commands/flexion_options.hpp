#pragma once
/// @brief The flags that set up a flexion sweep, shared by the jobs that run or export one
/// (`flexion`, `export febio`, `verify febio`): the config file, then the flags over it.

#include "pipeline/commands/key_flags.hpp"
#include "sim/flexion/flexion_settings.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::cli {

struct FlexionOptions {
  std::filesystem::path config;
  std::vector<std::string> set; ///< --set TABLE.KEY=VALUE over the config
  std::filesystem::path model;
  /// --angles, --axis, --posterior, --in-situ-strain, --ligaments, --without, --contact, --mode,
  /// --speed, --time-step: short names for config keys
  KeyFlags key_flags;
  std::vector<std::string> loads; ///< a free knee's loads, "KEY=VALUE" over [loads]
};

/// Adds --config, --set, --model, --angles, --axis, --posterior, --in-situ-strain and --contact to
/// `command`; with `interactive` also --mode, --speed and --time-step.
void add_flexion_options(CLI::App& command, FlexionOptions& options, bool interactive);

/// The config file (if any), then the flags over it, validated. `job` names the command in
/// errors.
sim::FlexionSettings flexion_settings_from(const FlexionOptions& options, const std::string& job);

} // namespace ligsim::cli
