#include "pipeline/commands/commands.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/render/offscreen_display.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "pipeline/study/cohort_table.hpp"
#include "pipeline/study/convergence_study.hpp"
#include "pipeline/study/sensitivity_study.hpp"
#include "pipeline/study/sensitivity_variants.hpp"
#include "pipeline/study/study_model.hpp"
#include "sim/flexion/flexion_config.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <functional>
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
  std::vector<std::string> ligaments;
  bool no_png = false;
};

void add_study_options(CLI::App* command, StudyOptions& o)
{
  command
      ->add_option("--model-config", o.model_config,
                   "build config (.toml) of the model, as for `ligsim build --config`: one "
                   "ligament's or a knee's")
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
  command
      ->add_option("--ligaments", o.ligaments,
                   "a knee config: the ligaments to study, by name (default: the flexion "
                   "config's `ligaments`, else all)")
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

/// The model the study builds: the ligaments --ligaments (else the flexion config) names. The
/// built knee holds only those, so the sweeps take all of it. A flexion config's [ligament]
/// table must name a ligament of the knee (one left out of the study is set aside by the sweeps).
study::StudyModel study_model(const StudyOptions& o, sim::FlexionSettings& settings,
                              const std::string& job)
{
  const std::vector<std::string> chosen = o.ligaments.empty() ? settings.ligaments : o.ligaments;
  study::StudyModel model = study::load_study_model(o.model_config, chosen, job);
  settings.ligaments.clear();
  if (!model.knee || !settings.given.count("ligament.name"))
    return model;
  const auto has = [&](const study::StudyModel& knee) {
    const std::vector<std::string> names = study::ligament_names(knee, "");
    return std::find(names.begin(), names.end(), settings.ligament.name) != names.end();
  };
  if (has(model))
    return model;
  const study::StudyModel whole = study::load_study_model(o.model_config, {}, job);
  if (!has(whole))
    fail("{}: the flexion config's [ligament] names {}, which the knee of {} does not have (it "
         "has {})",
         job, settings.ligament.name, o.model_config.string(),
         fmt::join(study::ligament_names(whole, ""), ", "));
  return model;
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
  bool mesh_only = false;
};

/// What every study job does around its own work: the display for the PNG plots (before
/// anything is computed), the output folder, summary.json, and where the table and plot are.
void run_study_job(const StudyOptions& o, const std::string& name, nlohmann::json parameters,
                   const std::vector<double>& angles_deg, const std::vector<std::string>& ligaments,
                   const std::function<nlohmann::json()>& run)
{
  RunSummary summary("study " + name);
  const StageMeter meter;
  summary.inputs() = {{"model_config", o.model_config.string()},
                      {"config", o.flexion_config.string()}};
  parameters["angles_deg"] = angles_deg;
  parameters["ligaments"] = ligaments;
  parameters["contact"] = "none: the ligament may pass through the bones";
  summary.parameters() = parameters;
  std::optional<render::OffscreenDisplay> display;
  if (!o.no_png)
    display.emplace();
  ensure_directory(o.out);
  summary.results() = run();
  summary.add_stage("study", meter);
  summary.write(o.out);
  log_info(fmt::format("table: {}", (o.out / (name + ".md")).string()));
  log_info(fmt::format("plot: {}", (o.out / (name + (o.no_png ? ".svg" : ".png"))).string()));
}

void run_convergence(const ConvergenceOptions& o)
{
  study::ConvergenceInputs inputs;
  inputs.flexion = flexion_settings(o.study);
  inputs.model = study_model(o.study, inputs.flexion, "study convergence");
  inputs.ladder = o.ladder;
  if (o.mesh_only) {
    inputs.ladder.voxel_scales.clear();
    inputs.ladder.time_steps_s.clear();
    inputs.ladder.interactive_mesh_scales.clear();
  }
  inputs.out = o.study.out;
  inputs.png = !o.study.no_png;
  check_ladder(inputs.ladder.mesh_scales, "--mesh-scales", false);
  check_ladder(inputs.ladder.voxel_scales, "--voxel-scales", true);
  check_ladder(inputs.ladder.time_steps_s, "--time-steps", true);
  check_ladder(inputs.ladder.interactive_mesh_scales, "--interactive-mesh-scales", true);
  for (int order : inputs.ladder.orders)
    if (order != 1 && order != 2)
      fail("--orders: an element order is 1 (linear tets) or 2 (10-node tets), got {}", order);
  run_study_job(o.study, "convergence",
                {{"mesh_scales", inputs.ladder.mesh_scales},
                 {"voxel_scales", inputs.ladder.voxel_scales},
                 {"voxel_mesh_scale", inputs.ladder.voxel_mesh_scale},
                 {"time_steps_s", inputs.ladder.time_steps_s},
                 {"interactive_mesh_scales", inputs.ladder.interactive_mesh_scales},
                 {"orders", inputs.ladder.orders.empty() ? nlohmann::json("the config's")
                                                         : nlohmann::json(inputs.ladder.orders)}},
                inputs.flexion.angles_deg,
                study::ligament_names(inputs.model, inputs.flexion.ligament.name),
                [&] { return study::run_convergence_study(inputs); });
}

struct SensitivityOptions {
  StudyOptions study;
  study::SensitivitySettings settings;
};

void run_sensitivity(const SensitivityOptions& o)
{
  study::SensitivityInputs inputs;
  inputs.flexion = flexion_settings(o.study);
  inputs.model = study_model(o.study, inputs.flexion, "study sensitivity");
  inputs.settings = o.settings;
  inputs.out = o.study.out;
  inputs.png = !o.study.no_png;
  const study::SensitivitySettings& s = inputs.settings;
  if (!(s.offset_mm > 0.0) || !(s.roughness_mm > 0.0) || s.smoothing_iterations < 1 ||
      !(s.tibia_end_length_mm > 0.0))
    fail("study sensitivity: --offset, --roughness, --smoothing-iterations and "
         "--tibia-end-length must be positive");
  for (double alpha : s.alphas)
    if (!(alpha >= 0.0 && alpha <= 1.0))
      fail("study sensitivity: --alphas holds {}: alpha lies in [0, 1]", alpha);
  run_study_job(o.study, "sensitivity",
                {{"offset_mm", s.offset_mm},
                 {"smoothing_iterations", s.smoothing_iterations},
                 {"roughness_mm", s.roughness_mm},
                 {"attachment_changes_mm", s.attachment_changes_mm},
                 {"alphas", s.alphas},
                 {"tibia_end_length_mm", s.tibia_end_length_mm},
                 {"factors", s.factors}},
                inputs.flexion.angles_deg,
                study::ligament_names(inputs.model, inputs.flexion.ligament.name),
                [&] { return study::run_sensitivity_study(inputs); });
}

struct CohortOptions {
  std::vector<std::string> members;
  std::vector<std::string> ligaments;
  fs::path out;
  bool no_png = false;
};

void run_cohort(const CohortOptions& o)
{
  RunSummary summary("study cohort");
  const StageMeter meter;
  std::vector<study::CohortMember> members;
  for (const std::string& text : o.members) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
      fail("study cohort: --member '{}' is not NAME=FLEXION_DIR", text);
    members.push_back({text.substr(0, equals), text.substr(equals + 1)});
    summary.inputs()[members.back().name] = members.back().flexion_dir.string();
  }
  std::optional<render::OffscreenDisplay> display;
  if (!o.no_png)
    display.emplace();
  summary.parameters()["ligaments"] = o.ligaments;
  summary.results() = study::write_cohort_table(members, o.out, !o.no_png, o.ligaments);
  summary.add_stage("cohort", meter);
  summary.write(o.out);
  log_info(fmt::format("table: {}", (o.out / "cohort.md").string()));
}

struct VariantOptions {
  fs::path model_config;
  std::string kind;
  double amount = 0.0;
  fs::path out;
};

void run_variant(const VariantOptions& o)
{
  RunSummary summary("study variant");
  const StageMeter meter;
  const pipeline::BuildConfig config = pipeline::load_build_config(o.model_config);
  const fs::path surface = study::write_surface_variant(config, o.kind, o.amount, o.out);
  summary.inputs() = {{"model_config", o.model_config.string()}};
  summary.parameters() = {{"kind", o.kind}, {"amount", o.amount}};
  summary.results() = {{"surface", surface.string()},
                       {"build_flags", "--surface " + surface.string() +
                                           " --femur-rule array --femur-array study_femur_area "
                                           "--tibia-rule array --tibia-array study_tibia_area"}};
  summary.add_stage("variant", meter);
  summary.write(o.out);
  log_info(fmt::format("surface: {}", surface.string()));
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
      ->add_option(
          "--mesh-scales", ladder.mesh_scales,
          "mesh sizes as factors of the config's (default h/2): the finest is the reference")
      ->delimiter(',');
  convergence
      ->add_option("--voxel-scales", ladder.voxel_scales,
                   "voxel spacings as factors of the config's (default h/8)")
      ->delimiter(',');
  convergence
      ->add_option("--voxel-mesh-scale", ladder.voxel_mesh_scale,
                   "the mesh of the voxel ladder (factor of the default, default 1)")
      ->check(CLI::PositiveNumber);
  convergence->add_option("--time-steps", ladder.time_steps_s, "interactive time steps, s")
      ->delimiter(',');
  convergence
      ->add_option("--interactive-mesh-scales", ladder.interactive_mesh_scales,
                   "the meshes the interactive runs use (factors as --mesh-scales)")
      ->delimiter(',');
  convergence
      ->add_option("--orders", ladder.orders,
                   "element orders of the mesh ladder, each a family: 1 (linear tets), 2 (10-node "
                   "tets); the finest mesh of the highest is the reference (default: the "
                   "config's)")
      ->delimiter(',');
  convergence->add_flag("--mesh-only", convergence_options->mesh_only,
                        "the mesh ladder alone: no voxel or interactive runs");
  convergence->callback([convergence_options] { run_convergence(*convergence_options); });

  auto sensitivity_options = std::make_shared<SensitivityOptions>();
  auto* sensitivity = study->add_subcommand(
      "sensitivity",
      "segmentation variants one factor at a time: the spread of the flexion figures");
  add_study_options(sensitivity, sensitivity_options->study);
  study::SensitivitySettings& s = sensitivity_options->settings;
  sensitivity->add_option(
      "--offset", s.offset_mm,
      "largest surface offset, mm (one voxel of the source image; default 0.5)");
  sensitivity->add_option("--smoothing-iterations", s.smoothing_iterations,
                          "Taubin smoothing iterations (default 10)");
  sensitivity->add_option("--roughness", s.roughness_mm, "roughening rms, mm (default 0.15)");
  sensitivity
      ->add_option("--attachment-changes", s.attachment_changes_mm,
                   "attachment areas grown (+) or shrunk (-), mm (default -2,-1,1,2)")
      ->delimiter(',');
  sensitivity->add_option("--alphas", s.alphas, "centerline alphas (default 0,0.5,1)")
      ->delimiter(',');
  sensitivity->add_option("--tibia-end-length", s.tibia_end_length_mm,
                          "changed rule: the tibial area as the distal end of this length, mm "
                          "(default 10)");
  sensitivity
      ->add_option("--factors", s.factors,
                   "factors to vary (default all): offset, smoothing, attachment-size, "
                   "attachment-rule, alpha")
      ->delimiter(',')
      ->check(CLI::IsMember(study::sensitivity_factor_names()));
  sensitivity->callback([sensitivity_options] { run_sensitivity(*sensitivity_options); });

  auto variant_options = std::make_shared<VariantOptions>();
  auto* variant = study->add_subcommand(
      "variant", "one segmentation variant as a surface file with the attachment areas as flags");
  variant
      ->add_option("--model-config", variant_options->model_config,
                   "one ligament's build config (.toml)")
      ->required()
      ->check(CLI::ExistingFile);
  variant->add_option("--kind", variant_options->kind, "offset, smooth, rough or areas")
      ->required()
      ->check(CLI::IsMember({"offset", "smooth", "rough", "areas"}));
  variant
      ->add_option("--amount", variant_options->amount,
                   "offset: mm along the normals; smooth: iterations; rough: rms mm; areas: mm "
                   "grown (+) or shrunk (-)")
      ->required();
  variant->add_option("--out", variant_options->out, "output folder")->required();
  variant->callback([variant_options] { run_variant(*variant_options); });

  auto cohort_options = std::make_shared<CohortOptions>();
  auto* cohort = study->add_subcommand(
      "cohort", "one table and plot from the flexion sweeps of several subjects or variants");
  cohort
      ->add_option("--member", cohort_options->members,
                   "NAME=FLEXION_DIR: a member and its `ligsim flexion` output folder (repeatable)")
      ->required();
  cohort
      ->add_option("--ligaments", cohort_options->ligaments,
                   "the ligaments to tabulate, by name (default: every member's all)")
      ->delimiter(',');
  cohort->add_option("--out", cohort_options->out, "output folder")->required();
  cohort->add_flag("--no-png", cohort_options->no_png, "plot as SVG only (no X server needed)");
  cohort->callback([cohort_options] { run_cohort(*cohort_options); });
}

} // namespace ligsim::cli
