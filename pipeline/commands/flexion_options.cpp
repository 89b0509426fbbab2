#include "pipeline/commands/flexion_options.hpp"

#include "common/error.hpp"
#include "common/toml_overrides.hpp"
#include "sim/flexion/flexion_config.hpp"

#include <CLI/CLI.hpp>

namespace ligsim::cli {

namespace {

/// `--load KEY=VALUE`s as settings of [loads], so that they meet the config's checks.
std::vector<std::string> load_overrides(const std::vector<std::string>& loads)
{
  std::vector<std::string> overrides;
  for (const std::string& load : loads) {
    if (load.find('=') == std::string::npos)
      fail("--load {}: expected KEY=VALUE, e.g. --load anterior_n=134", load);
    overrides.push_back("loads." + load);
  }
  return overrides;
}

/// The --set assignments and the loads, then the flags as the config keys they set (--angles 0,90
/// is angles_deg=[0.0, 90.0]): the flags win, and the config's reader checks them as it checks
/// the file. (--model is a path from here, where the config's `model` is from the config.)
std::vector<std::string> with_flag_assignments(const FlexionOptions& options)
{
  std::vector<std::string> set = options.set;
  for (std::string& assignment : load_overrides(options.loads))
    set.push_back(std::move(assignment));
  for (std::string& assignment : options.key_flags.assignments())
    set.push_back(std::move(assignment));
  return set;
}

} // namespace

void add_flexion_options(CLI::App& command, FlexionOptions& options, bool interactive)
{
  command.add_option("--config", options.config, "flexion config (.toml); flags override it")
      ->check(CLI::ExistingFile);
  command.add_option("--set", options.set, kSetHelp)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command.add_option("--model", options.model, "output folder of `ligsim build`");
  auto& keys = options.key_flags;
  keys.add<std::vector<double>>(command, "--angles", "flexion angles, deg (default 0,15,...,90)",
                                {"angles_deg"})
      ->delimiter(',');
  auto* axis =
      keys.add<std::vector<double>>(
              command, "--axis", "flexion axis through two points x1,y1,z1,x2,y2,z2, mm",
              {"axis.method", "axis.first_mm", "axis.second_mm"},
              [](const std::vector<double>& p, const std::vector<std::string>& keys) {
                return std::vector<std::string>{
                    toml_assignment(keys[0], std::string("points")),
                    toml_assignment(keys[1], std::vector<double>(p.begin(), p.begin() + 3)),
                    toml_assignment(keys[2], std::vector<double>(p.begin() + 3, p.end()))};
              })
          ->delimiter(',')
          ->expected(6);
  keys.add<std::vector<double>>(
          command, "--posterior",
          "posterior direction x,y,z: fit the axis to the posterior condyles",
          {"axis.method", "axis.posterior"},
          [](const std::vector<double>& direction, const std::vector<std::string>& keys) {
            return std::vector<std::string>{toml_assignment(keys[0], std::string("condyles")),
                                            toml_assignment(keys[1], direction)};
          })
      ->delimiter(',')
      ->expected(3)
      ->excludes(axis);
  keys.add<double>(command, "--in-situ-strain",
                   "fiber pre-strain of the built pose (default: each ligament's own, as built; "
                   "this sets them all)",
                   {"material.in_situ_strain"});
  keys.add<std::vector<std::string>>(command, "--ligaments",
                                     "a knee model: the ligaments to sweep, by name (default: all)",
                                     {"ligaments"})
      ->delimiter(',');
  keys.add<std::vector<std::string>>(
          command, "--without",
          "a knee model: ligaments cut, by name (sectioning: the knee without them)", {"without"})
      ->delimiter(',');
  command
      .add_option("--load", options.loads,
                  "a free knee: a load on the joint over [loads], KEY=VALUE (compression_n, "
                  "anterior_n, valgus_nm, internal_nm), e.g. --load anterior_n=134 (a laxity "
                  "test)")
      ->delimiter(',');
  keys.add<std::string>(
          command, "--contact",
          "ligament-bone contact: on (default) or off (the ligament may cross the bones)",
          {"contact.enabled"},
          [](const std::string& on, const std::vector<std::string>& keys) {
            return std::vector<std::string>{toml_assignment(keys[0], on == "on")};
          })
      ->check(CLI::IsMember({"on", "off"}));
  if (!interactive)
    return;
  keys.add<std::string>(command, "--mode", "static (default) or interactive", {"mode"})
      ->check(CLI::IsMember({"static", "interactive"}));
  keys.add<double>(command, "--speed", "interactive: femur speed, deg/s (default 45)",
                   {"interactive.angular_speed_deg_s"});
  keys.add<double>(command, "--time-step", "interactive: frame time step, s (default 0.01)",
                   {"interactive.time_step_s"});
}

sim::FlexionSettings flexion_settings_from(const FlexionOptions& options, const std::string& job)
{
  sim::FlexionSettings settings;
  const std::vector<std::string> overrides = with_flag_assignments(options);
  if (!options.config.empty() || !overrides.empty())
    sim::read_flexion_config(options.config, settings, overrides);
  if (!options.model.empty())
    settings.model_dir = options.model;
  if (settings.model_dir.empty())
    fail("{}: no model folder: pass --model DIR (the output folder of `ligsim build`) or set "
         "`model` in the config",
         job);
  if (job != "flexion" && settings.motion.path == sim::MotionSettings::Path::free)
    fail("{}: a free knee's path is found by `ligsim flexion`, which writes it as "
         "kinematics.csv; give that path here as a table: [motion] path = \"table\", table = "
         "\"<the flexion's output>/kinematics.csv\"",
         job);
  sim::validate(settings);
  return settings;
}

} // namespace ligsim::cli
