#pragma once
/// @brief The flags that set up a flexion sweep, shared by the jobs that run or export one
/// (`flexion`, `export febio`, `verify febio`): the config file, then the flags over it.

#include "sim/flexion/flexion_settings.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace ligsim::cli {

struct FlexionOptions {
  std::filesystem::path config;
  std::vector<std::string> set; ///< --set TABLE.KEY=VALUE over the config
  std::filesystem::path model;
  std::vector<double> angles;
  std::string mode;
  std::vector<double> axis_points;
  std::vector<double> posterior;
  std::optional<double> in_situ_strain;
  std::optional<double> speed;
  std::optional<double> time_step;
  std::string contact;                ///< "on", "off" or "" (the config's, by default on)
  std::vector<std::string> ligaments; ///< a knee model's ligaments to sweep (empty: all)
  std::vector<std::string> without;   ///< a knee model's ligaments cut (sectioned)
  std::vector<std::string> loads;     ///< a free knee's loads, "KEY=VALUE" over [loads]
};

/// Adds --config, --set, --model, --angles, --axis, --posterior, --in-situ-strain and --contact to
/// `command`; with `interactive` also --mode, --speed and --time-step.
void add_flexion_options(CLI::App& command, FlexionOptions& options, bool interactive);

/// The config file (if any), then the flags over it, validated. `job` names the command in
/// errors.
sim::FlexionSettings flexion_settings_from(const FlexionOptions& options, const std::string& job);

} // namespace ligsim::cli
