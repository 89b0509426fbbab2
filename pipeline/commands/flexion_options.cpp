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

} // namespace

void add_flexion_options(CLI::App& command, FlexionOptions& options, bool interactive)
{
  command.add_option("--config", options.config, "flexion config (.toml); flags override it")
      ->check(CLI::ExistingFile);
  command.add_option("--set", options.set, kSetHelp)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command.add_option("--model", options.model, "output folder of `ligsim build`");
  command.add_option("--angles", options.angles, "flexion angles, deg (default 0,15,...,90)")
      ->delimiter(',');
  auto* axis = command
                   .add_option("--axis", options.axis_points,
                               "flexion axis through two points x1,y1,z1,x2,y2,z2 (mm)")
                   ->delimiter(',')
                   ->expected(6);
  command
      .add_option("--posterior", options.posterior,
                  "posterior direction x,y,z: fit the axis to the posterior condyles")
      ->delimiter(',')
      ->expected(3)
      ->excludes(axis);
  command.add_option("--in-situ-strain", options.in_situ_strain,
                     "fiber pre-strain of the built pose (default: each ligament's own, as "
                     "built; this sets them all)");
  command
      .add_option("--ligaments", options.ligaments,
                  "a knee model: the ligaments to sweep, by name (default: all)")
      ->delimiter(',');
  command
      .add_option("--without", options.without,
                  "a knee model: ligaments cut, by name (sectioning: the knee without them)")
      ->delimiter(',');
  command
      .add_option("--load", options.loads,
                  "a free knee: a load on the joint over [loads], KEY=VALUE (compression_n, "
                  "anterior_n, valgus_nm, internal_nm), e.g. --load anterior_n=134 (a laxity "
                  "test)")
      ->delimiter(',');
  command
      .add_option("--contact", options.contact,
                  "ligament-bone contact: on (default) or off (the ligament may cross the bones)")
      ->check(CLI::IsMember({"on", "off"}));
  if (!interactive)
    return;
  command.add_option("--mode", options.mode, "static (default) or interactive")
      ->check(CLI::IsMember({"static", "interactive"}));
  command.add_option("--speed", options.speed, "interactive: femur speed, deg/s (default 45)");
  command.add_option("--time-step", options.time_step,
                     "interactive: frame time step, s (default 0.01)");
}

sim::FlexionSettings flexion_settings_from(const FlexionOptions& options, const std::string& job)
{
  sim::FlexionSettings settings;
  std::vector<std::string> overrides = options.set;
  for (const std::string& load : load_overrides(options.loads))
    overrides.push_back(load);
  if (!options.config.empty() || !overrides.empty())
    sim::read_flexion_config(options.config, settings, overrides);
  if (!options.model.empty())
    settings.model_dir = options.model;
  if (settings.model_dir.empty())
    fail("{}: no model folder: pass --model DIR (the output folder of `ligsim build`) or set "
         "`model` in the config",
         job);
  if (!options.angles.empty())
    settings.angles_deg = options.angles;
  if (options.mode == "static")
    settings.mode = sim::FlexionMode::quasi_static;
  else if (options.mode == "interactive")
    settings.mode = sim::FlexionMode::interactive;
  if (!options.axis_points.empty()) {
    settings.axis.source = sim::AxisSettings::Source::points;
    settings.axis.first_mm = Eigen::Vector3d(options.axis_points.data());
    settings.axis.second_mm = Eigen::Vector3d(options.axis_points.data() + 3);
  }
  if (!options.posterior.empty()) {
    settings.axis.source = sim::AxisSettings::Source::condyles;
    settings.axis.posterior = Eigen::Vector3d(options.posterior.data());
  }
  if (options.in_situ_strain) {
    settings.in_situ_strain = *options.in_situ_strain;
    settings.given.insert("in_situ_strain");
  }
  if (!options.ligaments.empty())
    settings.ligaments = options.ligaments;
  if (!options.without.empty())
    settings.without = options.without;
  if (options.speed)
    settings.interactive.angular_speed_deg_s = *options.speed;
  if (options.time_step)
    settings.interactive.time_step_s = *options.time_step;
  if (!options.contact.empty())
    settings.contact.enabled = options.contact == "on";
  if (job != "flexion" && settings.motion.path == sim::MotionSettings::Path::free)
    fail("{}: a free knee's path is found by `ligsim flexion`, which writes it as "
         "kinematics.csv; give that path here as a table: [motion] path = \"table\", table = "
         "\"<the flexion's output>/kinematics.csv\"",
         job);
  sim::validate(settings);
  return settings;
}

} // namespace ligsim::cli
