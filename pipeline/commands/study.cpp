#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/study/convergence_study.hpp"
#include "sim/flexion/flexion_config.hpp"
#include "sim/flexion/render/offscreen_display.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

/// What every study reads: the build config of the model and the flexion config.
struct StudyOptions {
  fs::path model_config;
  fs::path flexion_config;
  fs::path out;
  std::vector<double> angles;
  bool no_png = false;
};

void add_study_options(CLI::App* command, StudyOptions& o)
{
  command
      ->add_option("--model-config", o.model_config,
                   "build config (.toml) of the model, as for `ligsim build --config`")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--config", o.flexion_config,
                   "flexion config (.toml), as for `ligsim flexion --config` (its model is "
                   "ignored: the study builds its own)")
      ->check(CLI::ExistingFile);
  command->add_option("--out", o.out, "output folder")->required();
  command->add_option("--angles", o.angles, "flexion angles, deg (default: the config's)")
      ->delimiter(',');
  command->add_flag("--no-png", o.no_png, "plots as SVG only (no X server needed)");
}

sim::FlexionSettings flexion_settings(const StudyOptions& o)
{
  sim::FlexionSettings settings;
  if (!o.flexion_config.empty())
    sim::read_flexion_config(o.flexion_config, settings);
  if (!o.angles.empty())
    settings.angles_deg = o.angles;
  settings.images = false;
  settings.model_dir = o.out; // checked by validate(); each run sets its own
  sim::validate(settings);
  return settings;
}

void check_ladder(const std::vector<double>& values, const std::string& name, bool allow_empty)
{
  if (values.empty() && !allow_empty)
    fail("study convergence: {} is empty", name);
  for (double v : values)
    if (!(v > 0.0) || !std::isfinite(v))
      fail("study convergence: {} holds {}: every entry must be positive", name, v);
}

struct ConvergenceOptions {
  StudyOptions study;
  study::ConvergenceLadder ladder;
};

void run_convergence(const ConvergenceOptions& o)
{
  RunSummary summary("study convergence");
  const StageMeter meter;
  study::ConvergenceInputs inputs;
  inputs.build = pipeline::load_build_config(o.study.model_config);
  inputs.flexion = flexion_settings(o.study);
  inputs.ladder = o.ladder;
  inputs.out = o.study.out;
  inputs.png = !o.study.no_png;
  check_ladder(inputs.ladder.mesh_scales, "--mesh-scales", false);
  check_ladder(inputs.ladder.voxel_scales, "--voxel-scales", true);
  check_ladder(inputs.ladder.time_steps_s, "--time-steps", true);
  check_ladder(inputs.ladder.interactive_mesh_scales, "--interactive-mesh-scales", true);
  summary.inputs() = {{"model_config", o.study.model_config.string()},
                      {"config", o.study.flexion_config.string()}};
  summary.parameters() = {{"mesh_scales", inputs.ladder.mesh_scales},
                          {"voxel_scales", inputs.ladder.voxel_scales},
                          {"time_steps_s", inputs.ladder.time_steps_s},
                          {"interactive_mesh_scales", inputs.ladder.interactive_mesh_scales},
                          {"angles_deg", inputs.flexion.angles_deg},
                          {"contact", "none: the ligament may pass through the bones"}};
  std::optional<sim::OffscreenDisplay> display;
  if (inputs.png)
    display.emplace();
  ensure_directory(inputs.out);
  summary.results() = study::run_convergence_study(inputs);
  summary.add_stage("study", meter);
  summary.write(inputs.out);
  log_info(fmt::format("table: {}", (inputs.out / "convergence.md").string()));
  log_info(fmt::format(
      "plot: {}", (inputs.out / (inputs.png ? "convergence.png" : "convergence.svg")).string()));
}

} // namespace

void add_study_command(CLI::App& app)
{
  auto* study = app.add_subcommand(
      "study", "studies on the knee flexion: error against run time, segmentation sensitivity, "
               "cohort tables");
  study->require_subcommand(1);

  auto convergence_options = std::make_shared<ConvergenceOptions>();
  auto* convergence = study->add_subcommand(
      "convergence", "mesh, voxel and time-step ladders: error against run time");
  add_study_options(convergence, convergence_options->study);
  study::ConvergenceLadder& ladder = convergence_options->ladder;
  convergence
      ->add_option("--mesh-scales", ladder.mesh_scales,
                   "mesh sizes as factors of the default (h/2): the finest is the reference")
      ->delimiter(',');
  convergence
      ->add_option("--voxel-scales", ladder.voxel_scales,
                   "voxel spacings as factors of the default (h/8), at the default mesh")
      ->delimiter(',');
  convergence->add_option("--time-steps", ladder.time_steps_s, "interactive time steps, s")
      ->delimiter(',');
  convergence
      ->add_option("--interactive-mesh-scales", ladder.interactive_mesh_scales,
                   "the meshes the interactive runs use (factors of the default)")
      ->delimiter(',');
  convergence->callback([convergence_options] { run_convergence(*convergence_options); });
}

} // namespace ligsim::cli
