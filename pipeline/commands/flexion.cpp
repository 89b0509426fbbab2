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
#include "sim/flexion/plausibility.hpp"
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

void record_parameters(const sim::FlexionSettings& settings, const sim::KneeMotion& motion,
                       RunSummary& summary)
{
  const sim::ResolvedAxis& axis = motion.axis;
  nlohmann::json& parameters = summary.parameters();
  parameters["angles_deg"] = motion.angles_deg;
  if (!motion.times_s.empty())
    parameters["times_s"] = motion.times_s;
  parameters["mode"] = to_string(settings.mode);
  parameters["axis"] = {{"method", axis.method},
                        {"point_mm", json_vector3(axis.axis.point_mm)},
                        {"direction", json_vector3(axis.axis.direction)},
                        {"fit", axis.figures}};
  parameters["motion"] = motion.figures;
  parameters["motion"]["joint_coordinate_system"] = {
      {"origin_mm", json_vector3(motion.jcs.origin_mm)},
      {"flexion_axis", json_vector3(motion.jcs.flexion_axis)},
      {"tibial_axis", json_vector3(motion.jcs.tibial_axis)},
      {"reference", "Grood & Suntay, J Biomech Eng 1983;105:136"}};
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

/// Each footprint's area, beside the published one, and its reach from the flexion axis.
void log_footprints(const std::vector<sim::Footprint>& prints, const std::string& ligament)
{
  for (const sim::Footprint& print : prints) {
    std::string published;
    if (const auto area = sim::published_footprint_area(ligament, print.bone))
      published = area->sd_mm2 > 0.0
                      ? fmt::format(" (published {:.0f} +- {:.0f} mm^2, {})", area->mean_mm2,
                                    area->sd_mm2, area->source)
                      : fmt::format(" (published {:.0f} mm^2, {})", area->mean_mm2, area->source);
    log_info(fmt::format("{} footprint: {} nodes, {:.0f} mm^2{}, up to {:.1f} mm from the "
                         "flexion axis (mean {:.1f})",
                         print.bone, print.nodes, print.area_mm2, published,
                         print.max_axis_distance_mm, print.mean_axis_distance_mm));
  }
}

/// The axis, the other anatomical axis and the path, one line each on stderr.
void log_motion(const sim::KneeMotion& motion)
{
  const Eigen::Vector3d& d = motion.axis.axis.direction;
  log_info(fmt::format("flexion axis: {} (direction {:.3f}, {:.3f}, {:.3f})", motion.axis.method,
                       d.x(), d.y(), d.z()));
  if (motion.figures.contains("other_axis")) {
    const nlohmann::json& other = motion.figures["other_axis"];
    if (other.contains("angle_deg"))
      log_info(fmt::format("flexion axis: the {} axis lies {:.1f} degrees from it",
                           other["method"].get<std::string>(), other["angle_deg"].get<double>()));
    else
      log_info(fmt::format("flexion axis: no {} axis to compare ({})",
                           other["method"].get<std::string>(),
                           other["not_available"].get<std::string>()));
  }
  log_info(fmt::format("knee motion: {} ({} knee)", motion.figures["path"].get<std::string>(),
                       motion.figures["side"].get<std::string>()));
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
  const sim::KneeMotion motion = sim::resolve_knee_motion(model, settings);
  record_parameters(settings, motion, summary);
  log_motion(motion);
  const sim::HyperelasticBody body(model.mesh, settings.material,
                                   sim::prestretched_fibers(model, settings.in_situ_strain));
  const sim::RigidMotion femur_motion = sim::femur_rigid_motion(motion);
  const sim::BoundaryConditions conditions = sim::knee_conditions(model, femur_motion);
  const sim::SweepSteps steps = sim::motion_steps(motion);
  std::optional<sim::EmbeddedPolyline> centerline;
  if (model.centerline.rows() >= 2)
    centerline.emplace(model.mesh, model.centerline);
  sim::PlausibilityContext plausibility{settings.ligament, sim::footprints(model, motion.axis.axis),
                                        settings.in_situ_strain, 0.0};
  log_footprints(plausibility.footprints, settings.ligament.name);
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
  sim::FlexionOutput output(body, model, femur_motion, options.out);
  sim::FlexionPictures pictures(model, output, motion.axis.axis, settings.image_angles_deg,
                                options.out);
  StageMeter sweep_meter;
  nlohmann::json warnings = nlohmann::json::array();
  const sim::SweepResult sweep = sim::run_flexion_sweep(
      body, conditions, settings,
      [&](const sim::AngleResult& angle, const Eigen::VectorXd& x) {
        for (const std::string& warning : sim::plausibility_warnings(angle, plausibility)) {
          log_info(
              fmt::format("warning at {} deg: {}", sim::angle_label(angle.angle_deg), warning));
          warnings.push_back({{"angle_deg", angle.angle_deg}, {"warning", warning}});
        }
        const auto ligament = output.write_angle(angle, x);
        if (settings.images)
          pictures.keep(angle, x, ligament);
      },
      &contact, &steps, centerline ? &*centerline : nullptr);
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
  results["initial_overlap"] = sweep.overlap.to_json();
  results["footprints"] = sim::footprints_json(plausibility.footprints, settings.ligament.name);
  results["plausibility"] = {{"ligament", settings.ligament.name},
                             {"failure_strain", settings.ligament.failure_strain},
                             {"failure_load_n", settings.ligament.failure_load_n},
                             {"warnings", warnings}};
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
