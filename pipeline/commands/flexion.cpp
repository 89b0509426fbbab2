#include "pipeline/commands/commands.hpp"
#include "pipeline/commands/flexion_options.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "common/run_summary.hpp"
#include "pipeline/render/flexion_pictures.hpp"
#include "pipeline/render/knee_pictures.hpp"
#include "pipeline/render/offscreen_display.hpp"
#include "pipeline/reports/config_json.hpp"
#include "pipeline/reports/knee_reports.hpp"
#include "pipeline/stage_graph/build_config.hpp"
#include "sim/flexion/error_estimate.hpp"
#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/free_flexion.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_sweep.hpp"
#include "sim/flexion/ligament_pairs.hpp"
#include "sim/flexion/plausibility.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
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
  bool no_error_estimate = false;
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
                        {"fit", reports::to_json(axis.figures)}};
  parameters["motion"] = reports::to_json(motion.figures);
  parameters["motion"]["joint_coordinate_system"] = {
      {"origin_mm", json_vector3(motion.jcs.origin_mm)},
      {"flexion_axis", json_vector3(motion.jcs.flexion_axis)},
      {"tibial_axis", json_vector3(motion.jcs.tibial_axis)},
      {"reference", "Grood & Suntay, J Biomech Eng 1983;105:136"}};
  // Unless the config or a flag sets them, each ligament keeps the material and in-situ strain
  // it was built with (results.material, or results.ligaments.<name>.material, say which).
  const char* built = "each ligament's own, as built (results)";
  parameters["material"] = settings.given.count("material")
                               ? pipeline::material_json(settings.material)
                               : nlohmann::json(built);
  parameters["in_situ_strain"] = settings.given.count("in_situ_strain")
                                     ? nlohmann::json(settings.in_situ_strain)
                                     : nlohmann::json(built);
  const sim::ContactConfig& contact = settings.contact;
  if (contact.enabled.value_or(true))
    parameters["contact"] = {
        {"model", "IPC barrier on the ligament's free surface nodes, frictionless"},
        {"bones", contact.bones.empty() ? std::vector<std::string>{"every bone of the model"}
                                        : contact.bones}};
  else
    parameters["contact"] = "off: the ligament may pass through the bones";
  // Every key of the flexion config with the value this run used.
  parameters["config"] = reports::to_json(settings);
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
  if (const std::optional<sim::OtherAxis>& other = motion.figures.other_axis) {
    if (other->found)
      log_info(fmt::format("flexion axis: the {} axis lies {:.1f} degrees from it", other->method,
                           other->angle_deg));
    else
      log_info(fmt::format("flexion axis: no {} axis to compare ({})", other->method,
                           other->not_available));
  }
  log_info(fmt::format("knee motion: {} ({} knee)", motion.figures.path, motion.figures.side));
}

/// One ligament's results for summary.json.
nlohmann::json ligament_results(const sim::LigamentSweep& sweep)
{
  const sim::SweepResult& result = sweep.result;
  nlohmann::json entries = nlohmann::json::array();
  for (const sim::AngleResult& angle : result.angles)
    entries.push_back(reports::to_json(angle));
  const sim::LigamentSettings& ligament = sweep.settings.ligament;
  nlohmann::json json = {{"angles", entries},
                         {"setup", reports::to_json(sweep.setup)},
                         {"unrelaxed_prestretch_energy_mj", result.unrelaxed_energy_mj},
                         {"initial_overlap", reports::to_json(result.overlap)},
                         {"footprints", reports::footprints_json(sweep.footprints, ligament.name)},
                         {"plausibility",
                          {{"ligament", ligament.name},
                           {"failure_strain", ligament.failure_strain},
                           {"failure_load_n", ligament.failure_load_n},
                           {"warnings", reports::to_json(sweep.warnings)}}},
                         {"material", pipeline::material_json(sweep.settings.material)},
                         {"in_situ_strain", sweep.settings.in_situ_strain},
                         {"success", result.success}};
  if (sweep.thickness)
    json["cross_section"] = reports::thickness_json(*sweep.thickness, ligament.name);
  if (sweep.settings.mode == sim::FlexionMode::interactive)
    json["frames_per_second"] = result.frames_per_second;
  if (!result.success)
    json["failure"] = result.failure;
  return json;
}

/// "+-0.6", or "-" where there is no estimate.
std::string plus_minus(double error, double scale, int digits)
{
  return std::isnan(error) ? std::string("-") : fmt::format("+-{:.{}f}", scale * error, digits);
}

/// The table on stdout: a row per ligament and angle, with each figure's estimated
/// discretisation error (+-) where the flexion estimated it.
void print_table(const std::vector<sim::LigamentSweep>& sweeps,
                 const std::vector<sim::LigamentModel>& ligaments)
{
  fmt::print("{:<8} {:>6} {:>9} {:>7} {:>9} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8} {:>6} {:>8} "
             "{:>9} {:>4}\n",
             "ligament", "angle", "femur_N", "+-N", "net_N", "distal_N", "contact_N", "energy_mJ",
             "mean_%", "max_%", "region_%", "+-%", "dL_mm", "dL_%", "conv");
  for (std::size_t l = 0; l < sweeps.size(); ++l)
    for (const sim::AngleResult& a : sweeps[l].result.angles) {
      double contact = 0.0;
      for (const sim::BoneContact& bone : a.contact)
        contact += bone.in_solve ? bone.force_n.norm() : 0.0;
      fmt::print("{:<8} {:>6} {:>9.1f} {:>7} {:>9.1f} {:>9.1f} {:>9.1f} {:>9.3f} {:>8.2f} "
                 "{:>8.2f} {:>8.2f} {:>6} {:>8.2f} {:>9.2f} {:>4}\n",
                 sweeps[l].name, sim::angle_label(a.angle_deg), a.femur_force_n.norm(),
                 plus_minus(a.error.femur_force_n, 1.0, 1), sim::femur_net_force(a).norm(),
                 a.tibia_force_n.norm(), contact, a.strain_energy_mj,
                 100.0 * (a.mean_fiber_stretch - 1.0), 100.0 * (a.max_fiber_stretch - 1.0),
                 100.0 * (a.max_regional_fiber_stretch - 1.0),
                 plus_minus(a.error.regional_fiber_strain, 100.0, 2), a.length_change_mm,
                 a.length_change_pct, a.converged ? "yes" : "no");
    }
  fmt::print("(femur_N: the femoral footprint's reaction; net_N: with the femur's contact, the "
             "ligament's whole pull on the femur)\n");
  if (std::any_of(sweeps.begin(), sweeps.end(), [](const sim::LigamentSweep& sweep) {
        return std::any_of(
            sweep.result.angles.begin(), sweep.result.angles.end(),
            [](const sim::AngleResult& a) { return !std::isnan(a.error.femur_force_n); });
      }))
    fmt::print("(+-: the estimated discretisation error, from the companion model meshed coarser: "
               "Roache's grid convergence index)\n");
  if (ligaments.size() > 1)
    fmt::print("(distal_N: the force on the bone of the distal footprint: {})\n", [&] {
      std::string text;
      for (const sim::LigamentModel& l : ligaments)
        text += (text.empty() ? "" : ", ") + l.name + " " + l.model.distal_bone;
      return text;
    }());
}

/// The knee's free path, one line per angle.
void log_free_path(const sim::FreeFemurResult& found)
{
  for (const sim::FreeAngle& at : found.angles)
    log_info(fmt::format(
        "free knee at {} deg: varus {:.2f} deg, internal rotation {:.2f} deg, "
        "anterior {:.2f} mm, medial {:.2f} mm, proximal {:.2f} mm; contact {:.1f} N "
        "medial, {:.1f} N lateral; residual {:.2g} N, {:.2g} N mm ({} iterations, "
        "{:.1f} s)",
        sim::angle_label(at.angle_deg), at.pose.varus_deg, at.pose.internal_rotation_deg,
        at.pose.anterior_mm, -at.pose.lateral_mm, at.pose.proximal_mm,
        at.articular.medial_force_n.norm(), at.articular.lateral_force_n.norm(),
        at.residual_force_n, at.residual_moment_nmm, at.iterations, at.wall_s));
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
  if (!options.flexion.set.empty())
    summary.inputs()["set"] = options.flexion.set;
  const std::vector<sim::LigamentModel> whole =
      sim::load_knee(settings.model_dir, settings.ligament.name);
  std::vector<sim::LigamentModel> ligaments = sim::chosen_ligaments(whole, settings);
  const std::string element_note = settings.mode == sim::FlexionMode::interactive
                                       ? sim::linear_tets_for_frames(ligaments)
                                       : std::string();
  if (!element_note.empty())
    log_info(element_note);
  const bool knee = ligaments.front().manifest.has_value();
  std::vector<std::string> names;
  for (const sim::LigamentModel& ligament : ligaments)
    names.push_back(ligament.name);
  // The ligaments share the bones and the anatomy: the motion comes from any of them.
  const sim::KneeModel& bones = ligaments.front().model;
  // A knee tested with a ligament cut still finds its own path: the default follows the knee.
  const bool free_path = sim::choose_free_path(settings, whole);
  sim::KneeMotion motion = sim::resolve_knee_motion(bones, settings);
  // The knee finds its own path first; the sweep then follows it as any path.
  std::optional<sim::FreeFlexion> free;
  if (free_path) {
    StageMeter free_meter;
    free = sim::find_free_flexion(sim::free_path_ligaments(whole, settings), motion, settings,
                                  settings.model_dir / "contact");
    summary.add_stage("free_path", free_meter, {{"success", free->found.success}});
    if (!free->found.success && free->motion.angles_deg == motion.angles_deg)
      fail<SolverError>("flexion with the femur free: {}", free->found.failure);
    if (!free->found.success)
      log_info("flexion with the femur free stopped: " + free->found.failure +
               "; the sweep covers the angles it reached");
    motion = free->motion;
  }
  record_parameters(settings, motion, summary);
  summary.parameters()["ligaments"] = names;
  if (!element_note.empty())
    summary.parameters()["elements"] = element_note;
  log_motion(motion);
  const sim::RigidMotion femur_motion = sim::femur_rigid_motion(motion);
  for (const sim::LigamentModel& ligament : ligaments)
    log_footprints(sim::footprints(ligament.model, motion.axis.axis), ligament.name);
  // Before anything is written: a display for the pictures, or the reason there is none.
  std::optional<render::OffscreenDisplay> display;
  if (settings.images)
    display.emplace();
  summary.add_stage("setup", setup_meter, {{"ligaments", names}});

  ensure_directory(options.out);
  if (free) {
    sim::write_kinematics_csv(free->found, motion.jcs, options.out / "kinematics.csv");
    sim::write_kinematics_plot(free->found, options.out / "kinematics.svg");
    summary.results()["free"] = reports::to_json(free->found, motion.jcs);
    if (free->seat) {
      const sim::ArticularContact::Seat& seat = *free->seat;
      const auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nullptr; };
      summary.results()["free"]["articular_seat"] = {
          {"medial_gap_mm", seat.medial_gap_mm},
          {"lateral_gap_mm", seat.lateral_gap_mm},
          {"medial_built_separation_mm", finite(seat.medial_built_mm)},
          {"lateral_built_separation_mm", finite(seat.lateral_built_mm)}};
      log_info(fmt::format("articular contact: the layers meet at {:.2f} mm medially and {:.2f} "
                           "mm laterally (the bones' separation as built: {:.2f} and {:.2f} mm)",
                           seat.medial_gap_mm, seat.lateral_gap_mm, seat.medial_built_mm,
                           seat.lateral_built_mm));
    }
    log_free_path(free->found);
  }
  std::vector<sim::OutputLigament> parts;
  for (const sim::LigamentModel& ligament : ligaments)
    parts.push_back({ligament.name, knee ? ligament.name : "", ligament.model.distal_bone});
  sim::FlexionOutput output(parts, bones, femur_motion, options.out);
  // Every ligament's own pictures (coloured by strain energy, with fibers) in its folder.
  std::vector<render::FlexionPictures> ligament_pictures;
  ligament_pictures.reserve(ligaments.size());
  for (std::size_t l = 0; l < ligaments.size(); ++l)
    ligament_pictures.emplace_back(ligaments[l].model, output, motion.axis.axis,
                                   settings.image_angles_deg, options.out / parts[l].folder);
  render::KneePictures knee_pictures(bones, output, sim::effective_anatomy(bones, settings),
                                     motion.axis.axis, names, settings.image_angles_deg,
                                     options.out);
  std::map<double, std::vector<Eigen::VectorXd>> states; // per angle, per ligament
  StageMeter sweep_meter;
  std::vector<sim::LigamentSweep> sweeps = sim::run_knee_sweep(
      ligaments, motion, settings, settings.model_dir / "contact",
      [&](std::size_t l, const sim::HyperelasticBody& body, const sim::AngleResult& angle,
          const Eigen::VectorXd& x) {
        const fs::path written = output.write_angle(l, body, angle, x);
        if (settings.images) {
          knee_pictures.keep(l, angle, written);
          ligament_pictures[l].keep(angle, x, written);
        }
        if (ligaments.size() > 1) {
          states[angle.angle_deg].resize(ligaments.size());
          states[angle.angle_deg][l] = x;
        }
      },
      free ? free->equilibria : sim::EquilibriumGuesses{});
  std::vector<sim::CompanionSweep> companions;
  if (!options.no_error_estimate) {
    StageMeter estimate_meter;
    companions = sim::estimate_sweep_errors(ligaments, motion, settings,
                                            settings.model_dir / "contact", sweeps);
    summary.add_stage("error_estimate", estimate_meter,
                      {{"companions_swept",
                        std::count_if(companions.begin(), companions.end(),
                                      [](const sim::CompanionSweep& c) { return c.swept; })}});
  }
  std::vector<std::vector<sim::AngleResult>> angles;
  bool success = true;
  std::string failure;
  for (const sim::LigamentSweep& sweep : sweeps) {
    angles.push_back(sweep.result.angles);
    if (!sweep.result.success) {
      success = false;
      failure += (failure.empty() ? "" : "; ") +
                 (knee ? sweep.name + ": " + sweep.result.failure : sweep.result.failure);
    }
  }
  output.finish(angles);
  nlohmann::json sweep_figures = {{"success", success}};
  if (settings.mode == sim::FlexionMode::interactive) {
    const sim::SweepResult& first = sweeps.front().result;
    sweep_figures.update({{"frames", first.frames},
                          {"time_step_s", first.time_step_s},
                          {"frames_per_second", sim::knee_frames_per_second(sweeps)}});
  }
  if (sweeps.size() == 1)
    sweep_figures["angles_reached"] = sweeps.front().result.angles.size();
  summary.add_stage("sweep", sweep_meter, sweep_figures);

  nlohmann::json& results = summary.results();
  for (const sim::LigamentSweep& sweep : sweeps)
    results["ligaments"][sweep.name] = ligament_results(sweep);
  for (const sim::CompanionSweep& companion : companions)
    results["ligaments"][companion.ligament]["error_estimate"] = reports::to_json(companion);
  if (ligaments.size() > 1)
    results["pairs"] = reports::to_json(sim::pairs_over_sweep(ligaments, states, options.out));
  results["success"] = success;
  if (settings.mode == sim::FlexionMode::interactive)
    results["frames_per_second"] = sim::knee_frames_per_second(sweeps);
  if (!success)
    results["failure"] = failure;

  std::vector<fs::path> images;
  if (settings.images) {
    StageMeter picture_meter;
    images = knee_pictures.render();
    for (std::size_t l = 0; l < ligament_pictures.size(); ++l) {
      const std::vector<fs::path> own = ligament_pictures[l].render(sweeps[l].result.angles);
      images.insert(images.end(), own.begin(), own.end());
    }
    summary.add_stage("pictures", picture_meter, {{"files", images.size()}});
  }
  summary.write(options.out);
  print_table(sweeps, ligaments);
  if (!success)
    fail<SolverError>("{} (the angles reached are in {})", failure, options.out.string());

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
  command->add_flag("--no-error-estimate", options->no_error_estimate,
                    "no companion solve on the coarser mesh, so no estimate of the figures' "
                    "discretisation error");
  command->callback([options] { run_flexion(*options); });
}

} // namespace ligsim::cli
