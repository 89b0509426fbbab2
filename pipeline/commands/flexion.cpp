#include "pipeline/commands/commands.hpp"
#include "pipeline/commands/flexion_options.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/flexion_pictures.hpp"
#include "sim/flexion/knee_flexion.hpp"
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

struct FlexionJobOptions {
  FlexionOptions flexion;
  fs::path out;
  bool no_images = false;
};

void record_parameters(const sim::FlexionSettings& settings, const sim::ResolvedAxis& axis,
                       RunSummary& summary)
{
  nlohmann::json& parameters = summary.parameters();
  parameters["angles_deg"] = settings.angles_deg;
  parameters["mode"] = to_string(settings.mode);
  parameters["axis"] = {{"method", axis.method},
                        {"point_mm", json_vector3(axis.axis.point_mm)},
                        {"direction", json_vector3(axis.axis.direction)},
                        {"fit", axis.figures}};
  const sim::MaterialParameters& m = settings.material;
  parameters["material"] = {{"mu_mpa", m.mu_mpa},
                            {"k_mpa", m.bulk_modulus_mpa},
                            {"volumetric", to_string(m.volumetric)},
                            {"c3_mpa", m.fiber->c3_mpa},
                            {"c4", m.fiber->c4},
                            {"c5_mpa", m.fiber->c5_mpa},
                            {"lambda_star", m.fiber->lambda_star},
                            {"convention", to_string(m.fiber->convention)}};
  parameters["in_situ_strain"] = settings.in_situ_strain;
  const sim::ContactConfig& contact = settings.contact;
  if (contact.enabled.value_or(true))
    parameters["contact"] = {
        {"model", "IPC barrier on the ligament's free surface nodes, frictionless"},
        {"bones",
         contact.bones.empty() ? std::vector<std::string>{"femur", "tibia"} : contact.bones},
        {"d_hat_mm", contact.barrier.d_hat_mm},
        {"stiffness_mpa_per_mm", contact.barrier.stiffness_mpa_per_mm},
        {"voxel_mm", contact.grid.voxel_mm},
        {"band_mm", contact.grid.band_mm}};
  else
    parameters["contact"] = "off: the ligament may pass through the bones";
  if (settings.mode == sim::FlexionMode::quasi_static)
    parameters["static"] = {{"residual_tolerance", settings.newton.residual_tolerance},
                            {"max_iterations", settings.newton.max_iterations},
                            {"max_cutbacks", settings.newton.max_cutbacks},
                            {"linear_solver", to_string(settings.newton.linear_solver)}};
  else
    parameters["interactive"] = {{"angular_speed_deg_s", settings.interactive.angular_speed_deg_s},
                                 {"time_step_s", settings.interactive.time_step_s},
                                 {"density_kg_m3", settings.interactive.density_kg_m3},
                                 {"mass_damping_per_s", settings.interactive.mass_damping_per_s},
                                 {"linear_solver", to_string(settings.interactive.linear_solver)}};
}

void run_flexion(const FlexionJobOptions& options)
{
  RunSummary summary("flexion");
  StageMeter setup_meter;
  sim::FlexionSettings settings = flexion_settings_from(options.flexion, "flexion");
  if (options.no_images)
    settings.images = false;
  summary.inputs()["model"] = settings.model_dir.string();
  if (!options.flexion.config.empty())
    summary.inputs()["config"] = options.flexion.config.string();
  const sim::KneeModel model = sim::load_knee_model(settings.model_dir);
  const sim::ResolvedAxis axis = sim::resolve_flexion_axis(model, settings.axis);
  record_parameters(settings, axis, summary);
  const sim::HyperelasticBody body(model.mesh, settings.material,
                                   sim::prestretched_fibers(model, settings.in_situ_strain));
  const sim::BoundaryConditions conditions =
      sim::knee_conditions(model, axis.axis, settings.angles_deg.back());
  // Built with contact off as well: it measures how deep the ligament goes into the bones.
  const sim::KneeContact contact(model, conditions, settings.contact,
                                 settings.model_dir / "contact");
  // Before anything is written: a display for the pictures, or the reason there is none.
  std::optional<sim::OffscreenDisplay> display;
  if (settings.images)
    display.emplace();
  summary.add_stage("setup", setup_meter,
                    {{"nodes", body.node_count()},
                     {"tets", body.element_count()},
                     {"femur_nodes", model.femur_nodes.size()},
                     {"tibia_nodes", model.tibia_nodes.size()},
                     {"rest_volume_mm3", body.rest_volume()},
                     {"contact", contact.figures()}});

  ensure_directory(options.out);
  sim::FlexionOutput output(body, model, axis.axis, options.out);
  sim::FlexionPictures pictures(model, output, axis.axis, settings.image_angles_deg, options.out);
  StageMeter sweep_meter;
  const sim::SweepResult sweep = sim::run_flexion_sweep(
      body, conditions, settings,
      [&](const sim::AngleResult& angle, const Eigen::VectorXd& x) {
        const auto ligament = output.write_angle(angle, x);
        if (settings.images)
          pictures.keep(angle, x, ligament);
      },
      &contact);
  output.finish(sweep.angles);
  nlohmann::json sweep_figures = {{"success", sweep.success},
                                  {"angles_reached", sweep.angles.size()}};
  if (settings.mode == sim::FlexionMode::interactive)
    sweep_figures.update({{"frames", sweep.frames},
                          {"time_step_s", sweep.time_step_s},
                          {"frames_per_second", sweep.frames_per_second}});
  summary.add_stage("sweep", sweep_meter, sweep_figures);

  nlohmann::json& results = summary.results();
  nlohmann::json entries = nlohmann::json::array();
  for (const sim::AngleResult& angle : sweep.angles)
    entries.push_back(sim::angle_json(angle));
  results["angles"] = entries;
  results["unrelaxed_prestretch_energy_mj"] = sweep.unrelaxed_energy_mj;
  results["success"] = sweep.success;
  if (settings.mode == sim::FlexionMode::interactive)
    results["frames_per_second"] = sweep.frames_per_second;
  if (!sweep.success)
    results["failure"] = sweep.failure;

  std::vector<fs::path> images;
  if (settings.images) {
    StageMeter picture_meter;
    images = pictures.render(sweep.angles);
    summary.add_stage("pictures", picture_meter, {{"files", images.size()}});
  }
  summary.write(options.out);
  if (!sweep.success)
    fail<SolverError>("{} (the angles reached are in {})", sweep.failure, options.out.string());

  log_info(fmt::format("table: {}", (options.out / "flexion.csv").string()));
  for (const fs::path& image : images)
    log_info(fmt::format("image: {}", image.string()));
  log_info(fmt::format("ParaView: {}", (options.out / "flexion.pvd").string()));
}

} // namespace

void add_flexion_command(CLI::App& app)
{
  auto options = std::make_shared<FlexionJobOptions>();
  auto* command = app.add_subcommand(
      "flexion", "sweep a built knee model through flexion (tibia fixed, femur turning)");
  add_flexion_options(*command, options->flexion, true);
  command->add_option("--out", options->out, "output folder")->required();
  command->add_flag("--no-images", options->no_images, "no PNG pictures (no X server needed)");
  command->callback([options] { run_flexion(*options); });
}

} // namespace ligsim::cli
