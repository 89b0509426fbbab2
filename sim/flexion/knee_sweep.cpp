#include "sim/flexion/knee_sweep.hpp"

#include "common/error.hpp"
#include "common/fields_json.hpp"
#include "common/progress.hpp"
#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/material/material_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// A flexion config's [material] keys from knee.json, which the build wrote from the same list.
MaterialParameters material_from(const nlohmann::json& json, const std::string& where)
{
  MaterialParameters material = mcl_material();
  visit_weiss_material(material, FieldJsonReader{json, where + ": material"});
  validate(material);
  return material;
}

} // namespace

FlexionSettings ligament_settings(const FlexionSettings& settings, const LigamentModel& ligament)
{
  FlexionSettings own = settings;
  if (!ligament.manifest) {
    if (ligament.built && !settings.given.count("material"))
      own.material = ligament.built->material;
    if (ligament.built && !settings.given.count("in_situ_strain"))
      own.in_situ_strain = ligament.built->in_situ_strain;
    return own;
  }
  const KneeLigament& entry = *ligament.manifest;
  const std::string where = fmt::format("knee.json, ligament {}", entry.name);
  own.ligament.name = entry.name;
  const bool named = settings.given.count("ligament.name") && settings.ligament.name == entry.name;
  own.ligament.failure_strain = named && settings.given.count("ligament.failure_strain")
                                    ? settings.ligament.failure_strain
                                    : entry.failure_strain;
  own.ligament.failure_load_n = named && settings.given.count("ligament.failure_load_n")
                                    ? settings.ligament.failure_load_n
                                    : entry.failure_load_n;
  if (!settings.given.count("material"))
    own.material = material_from(entry.material, where);
  if (!settings.given.count("in_situ_strain"))
    own.in_situ_strain = entry.in_situ_strain;
  if (own.contact.bones.empty())
    own.contact.bones = entry.contact_bones;
  own.ligaments.clear();
  validate(own);
  return own;
}

KneeModel load_ligament_as_flexed(FlexionSettings& settings, const std::string& job)
{
  LigamentModel ligament = load_ligament(settings.model_dir, settings.ligament.name, job);
  settings = ligament_settings(settings, ligament);
  return std::move(ligament.model);
}

std::string linear_tets_for_frames(std::vector<LigamentModel>& ligaments)
{
  std::string names;
  for (LigamentModel& ligament : ligaments)
    if (ligament.model.tet10.rows() > 0) {
      ligament.model = with_linear_tets(ligament.model);
      names += (names.empty() ? "" : ", ") + ligament.name;
    }
  if (names.empty())
    return "";
  return fmt::format("implicit Euler frames: {} of 10-node tets run as linear tets on their "
                     "corners (no positive lumped mass for 10-node tets; the quasi-static sweep "
                     "runs them as built)",
                     names);
}

std::vector<LigamentModel> chosen_ligaments(std::vector<LigamentModel> all,
                                            const FlexionSettings& settings)
{
  const std::string names = ligament_names(all);
  const auto known = [&](const std::string& name) {
    return std::any_of(all.begin(), all.end(),
                       [&](const LigamentModel& l) { return l.name == name; });
  };
  const bool knee = all.size() > 1 || all.front().manifest;
  if (knee && settings.given.count("ligament.name") && !known(settings.ligament.name))
    fail("flexion: the config's [ligament] names {}, which this knee does not have (it has {})",
         settings.ligament.name, names);
  for (const std::string& cut : settings.without) {
    if (!known(cut))
      fail("flexion: --without names {}, which the knee does not have (it has {})", cut, names);
    all.erase(std::remove_if(all.begin(), all.end(),
                             [&](const LigamentModel& l) { return l.name == cut; }),
              all.end());
  }
  if (all.empty())
    fail("flexion: --without cuts every ligament of the knee ({})", names);
  if (settings.ligaments.empty())
    return all;
  if (!knee)
    fail("flexion: --ligaments chooses among a knee model's ligaments; {} holds one ligament",
         settings.model_dir.string());
  std::vector<LigamentModel> chosen;
  for (const std::string& name : settings.ligaments) {
    if (!known(name))
      fail("flexion: the knee has no ligament called {} (it has {})", name, names);
    if (std::count(settings.ligaments.begin(), settings.ligaments.end(), name) > 1)
      fail("flexion: --ligaments names {} twice", name);
    for (const LigamentModel& ligament : all)
      if (ligament.name == name)
        chosen.push_back(ligament);
  }
  return chosen;
}

std::vector<LigamentSweep> run_knee_sweep(const std::vector<LigamentModel>& ligaments,
                                          const KneeMotion& motion, const FlexionSettings& settings,
                                          const fs::path& contact_cache,
                                          const KneeAngleCallback& on_angle,
                                          const EquilibriumGuesses& guesses, bool log_warnings)
{
  const RigidMotion femur_motion = femur_rigid_motion(motion);
  const SweepSteps steps = motion_steps(motion);
  std::vector<LigamentSweep> sweeps;
  for (std::size_t l = 0; l < ligaments.size(); ++l) {
    const LigamentModel& ligament = ligaments[l];
    const KneeModel& model = ligament.model;
    LigamentSweep sweep;
    sweep.name = ligament.name;
    SweepSteps own_steps = steps;
    if (const auto guess = guesses.find(ligament.name); guess != guesses.end())
      own_steps.starts = guess->second;
    sweep.settings = ligament_settings(settings, ligament);
    if (ligaments.size() > 1)
      log_info(fmt::format("ligament {}: {} tets", ligament.name, model.mesh.T.rows()));
    const HyperelasticBody body =
        ligament_body(model, sweep.settings.material, sweep.settings.in_situ_strain);
    const BoundaryConditions conditions = knee_conditions(model, femur_motion);
    std::optional<EmbeddedPolyline> centerline;
    if (model.centerline.rows() >= 2)
      centerline.emplace(model.mesh, model.centerline);
    sweep.footprints = footprints(model, motion.axis.axis);
    PlausibilityContext plausibility{sweep.settings.ligament, sweep.footprints,
                                     sweep.settings.in_situ_strain, std::nullopt};
    sweep.thickness = ligament_thickness(model.mesh, model.centerline);
    if (sweep.thickness) {
      plausibility.thin = thin_ligament_finding(ligament.name, *sweep.thickness);
      if (plausibility.thin)
        log_info(fmt::format("warning: {}", *plausibility.thin));
    }
    // Built with contact off as well: it measures how deep the ligament goes into the bones.
    const KneeContact contact(model, conditions, sweep.settings.contact, contact_cache);
    sweep.setup = {body.node_count(), body.element_count(),     model.femur_nodes.size(),
                   model.distal_bone, model.tibia_nodes.size(), body.rest_volume(),
                   contact.figures()};
    sweep.result = run_flexion_sweep(
        body, conditions, sweep.settings,
        [&](const AngleResult& angle, const HyperelasticBody& swept, const Eigen::VectorXd& x) {
          for (const std::string& warning : plausibility_warnings(angle, plausibility)) {
            if (log_warnings)
              log_info(fmt::format("warning at {} deg: {}{}", angle_label(angle.angle_deg),
                                   ligaments.size() > 1 ? ligament.name + ": " : "", warning));
            sweep.warnings.push_back({angle.angle_deg, warning});
          }
          if (on_angle)
            on_angle(l, swept, angle, x);
        },
        &contact, &own_steps, centerline ? &*centerline : nullptr);
    sweeps.push_back(std::move(sweep));
  }
  return sweeps;
}

double knee_frames_per_second(const std::vector<LigamentSweep>& sweeps)
{
  double seconds_per_frame = 0.0;
  for (const LigamentSweep& sweep : sweeps)
    if (sweep.result.frames_per_second > 0.0)
      seconds_per_frame += 1.0 / sweep.result.frames_per_second;
  return seconds_per_frame > 0.0 ? 1.0 / seconds_per_frame : 0.0;
}

} // namespace ligsim::sim
