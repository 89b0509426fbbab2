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

/// The --set assignments, then the flags as the config keys they set (--angles 0,90 is
/// angles_deg=[0.0, 90.0]): the flags win, and the config's reader checks them as it checks
/// the file. (--model is a path from here, where the config's `model` is from the config.)
std::vector<std::string> with_flag_assignments(const FlexionOptions& options)
{
  std::vector<std::string> set = options.set;
  for (const std::string& load : load_overrides(options.loads))
    set.push_back(load);
  const auto add_if = [&](const std::string& key, const auto& value) {
    if (value)
      set.push_back(toml_assignment(key, *value));
  };
  const auto add_if_any = [&](const std::string& key, const auto& values) {
    if (!values.empty())
      set.push_back(toml_assignment(key, values));
  };
  add_if_any("angles_deg", options.angles);
  if (!options.mode.empty())
    set.push_back(toml_assignment("mode", options.mode));
  if (!options.axis_points.empty()) {
    set.push_back(toml_assignment("axis.method", std::string("points")));
    set.push_back(
        toml_assignment("axis.first_mm", std::vector<double>(options.axis_points.begin(),
                                                             options.axis_points.begin() + 3)));
    set.push_back(
        toml_assignment("axis.second_mm", std::vector<double>(options.axis_points.begin() + 3,
                                                              options.axis_points.end())));
  }
  if (!options.posterior.empty()) {
    set.push_back(toml_assignment("axis.method", std::string("condyles")));
    set.push_back(toml_assignment("axis.posterior", options.posterior));
  }
  add_if("material.in_situ_strain", options.in_situ_strain);
  add_if_any("ligaments", options.ligaments);
  add_if_any("without", options.without);
  add_if("interactive.angular_speed_deg_s", options.speed);
  add_if("interactive.time_step_s", options.time_step);
  if (!options.contact.empty())
    set.push_back(toml_assignment("contact.enabled", options.contact == "on"));
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
  command
      .add_option("--angles", options.angles,
                  "flexion angles, deg (default 0,15,...,90; --set angles_deg=[...])")
      ->delimiter(',');
  auto* axis =
      command
          .add_option(
              "--axis", options.axis_points,
              "flexion axis through two points x1,y1,z1,x2,y2,z2, mm ([axis] method = \"points\", "
              "first_mm, second_mm)")
          ->delimiter(',')
          ->expected(6);
  command
      .add_option(
          "--posterior", options.posterior,
          "posterior direction x,y,z: fit the axis to the posterior condyles ([axis] method = "
          "\"condyles\", posterior)")
      ->delimiter(',')
      ->expected(3)
      ->excludes(axis);
  command.add_option("--in-situ-strain", options.in_situ_strain,
                     "fiber pre-strain of the built pose (default: each ligament's own, as "
                     "built; this sets them all; --set material.in_situ_strain)");
  command
      .add_option(
          "--ligaments", options.ligaments,
          "a knee model: the ligaments to sweep, by name (default: all; --set ligaments=[...])")
      ->delimiter(',');
  command
      .add_option("--without", options.without,
                  "a knee model: ligaments cut, by name (sectioning: the knee without them; --set "
                  "without=[...])")
      ->delimiter(',');
  command
      .add_option("--load", options.loads,
                  "a free knee: a load on the joint over [loads], KEY=VALUE (compression_n, "
                  "anterior_n, valgus_nm, internal_nm), e.g. --load anterior_n=134 (a laxity "
                  "test)")
      ->delimiter(',');
  command
      .add_option(
          "--contact", options.contact,
          "ligament-bone contact: on (default) or off (the ligament may cross the bones; --set "
          "contact.enabled)")
      ->check(CLI::IsMember({"on", "off"}));
  if (!interactive)
    return;
  command.add_option("--mode", options.mode, "static (default) or interactive (--set mode)")
      ->check(CLI::IsMember({"static", "interactive"}));
  command.add_option(
      "--speed", options.speed,
      "interactive: femur speed, deg/s (default 45; --set interactive.angular_speed_deg_s)");
  command.add_option(
      "--time-step", options.time_step,
      "interactive: frame time step, s (default 0.01; --set interactive.time_step_s)");
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
