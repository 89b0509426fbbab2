#include "sim/flexion/error_estimate.hpp"

#include "common/knee_manifest.hpp"
#include "common/mesh.hpp"
#include "common/progress.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

constexpr double kSafetyFactor = 3.0; ///< Roache's, for two meshes
constexpr double kOrder = 2.0;

/// The mean element size of the coarse sweep over the fine one's.
double size_ratio(const LigamentSetup& fine, const LigamentSetup& coarse)
{
  return mean_element_size(coarse.rest_volume_mm3, static_cast<double>(coarse.tets)) /
         mean_element_size(fine.rest_volume_mm3, static_cast<double>(fine.tets));
}

/// Each angle of `fine` that `coarse` reached, converged, gets its error.
int attach_errors(std::vector<AngleResult>& fine, const std::vector<AngleResult>& coarse,
                  double ratio)
{
  int matched = 0;
  for (AngleResult& angle : fine)
    for (const AngleResult& other : coarse)
      if (std::abs(other.angle_deg - angle.angle_deg) < 1e-9 && other.converged) {
        angle.error.femur_force_n =
            grid_convergence_index(angle.femur_force_n.norm(), other.femur_force_n.norm(), ratio);
        angle.error.regional_fiber_strain = grid_convergence_index(
            angle.max_regional_fiber_stretch, other.max_regional_fiber_stretch, ratio);
        ++matched;
        break;
      }
  return matched;
}

} // namespace

double grid_convergence_index(double fine, double coarse, double size_ratio)
{
  if (!(size_ratio > 1.0))
    return NAN;
  return kSafetyFactor * std::abs(fine - coarse) / (std::pow(size_ratio, kOrder) - 1.0);
}

std::string locking_warning(const std::vector<AngleResult>& angles, bool linear_tets)
{
  if (!linear_tets)
    return "";
  const AngleResult* worst = nullptr;
  double worst_share = 0.0;
  for (const AngleResult& angle : angles) {
    const double share = angle.error.femur_force_n / angle.femur_force_n.norm();
    if (share > worst_share) { // NaN (no estimate, or no force) never is
      worst_share = share;
      worst = &angle;
    }
  }
  if (worst == nullptr || !(worst_share > kLockingErrorShare))
    return "";
  return fmt::format(
      "the femur force's estimated error is {:.0f} % of the force at {:g} degrees: linear tets "
      "lock as a thin band bends, and their figures can lie far above the model's answer; build "
      "it with --order 2 (10-node tets, docs/labelmap.md)",
      100.0 * worst_share, worst->angle_deg);
}

std::optional<LigamentModel> load_companion(const LigamentModel& ligament)
{
  const fs::path folder = ligament.folder / companion_model_folder;
  if (!fs::exists(folder / "model.vtu"))
    return std::nullopt;
  LigamentModel companion = ligament;
  companion.folder = folder;
  KneeModel mesh = load_knee_model(folder);
  KneeModel& model = companion.model;
  model.mesh = std::move(mesh.mesh);
  model.tet10 = std::move(mesh.tet10);
  model.fiber_directions = std::move(mesh.fiber_directions);
  model.fiber_directions_at_points = std::move(mesh.fiber_directions_at_points);
  model.femur_nodes = std::move(mesh.femur_nodes);
  model.tibia_nodes = std::move(mesh.tibia_nodes);
  return companion;
}

std::vector<CompanionSweep> estimate_sweep_errors(const std::vector<LigamentModel>& ligaments,
                                                  const KneeMotion& motion,
                                                  const FlexionSettings& settings,
                                                  const fs::path& contact_cache,
                                                  std::vector<LigamentSweep>& sweeps)
{
  std::vector<CompanionSweep> reports(ligaments.size());
  std::vector<LigamentModel> companions;
  std::vector<std::size_t> owner; // the ligament of each companion
  for (std::size_t l = 0; l < ligaments.size(); ++l) {
    CompanionSweep& report = reports[l];
    report.ligament = ligaments[l].name;
    report.folder = ligaments[l].folder / companion_model_folder;
    std::optional<LigamentModel> companion = load_companion(ligaments[l]);
    if (!companion) {
      report.note = fmt::format("no companion model in {} (built with [error_estimate] "
                                "mesh_scale = 0, or before companions were built)",
                                report.folder.string());
      log_info(fmt::format("error estimate: {}: {}", report.ligament, report.note));
      continue;
    }
    companions.push_back(std::move(*companion));
    owner.push_back(l);
  }
  if (companions.empty())
    return reports;
  if (settings.mode == FlexionMode::interactive)
    linear_tets_for_frames(companions);
  log_info(fmt::format("error estimate: sweeping the companion model{} through the same motion",
                       companions.size() > 1 ? "s" : ""));
  const std::vector<LigamentSweep> coarse = run_knee_sweep(
      companions, motion, settings, contact_cache,
      [](std::size_t, const HyperelasticBody&, const AngleResult&, const Eigen::VectorXd&) {}, {},
      false);
  for (std::size_t c = 0; c < coarse.size(); ++c) {
    CompanionSweep& report = reports[owner[c]];
    LigamentSweep& fine = sweeps[owner[c]];
    report.swept = true;
    report.tets = coarse[c].setup.tets;
    report.size_ratio = size_ratio(fine.setup, coarse[c].setup);
    report.wall_s = coarse[c].result.wall_s;
    report.angles_reached =
        attach_errors(fine.result.angles, coarse[c].result.angles, report.size_ratio);
    if (!(report.size_ratio > 1.0))
      report.note = fmt::format("the companion's elements are not larger than the model's (size "
                                "ratio {:.2f}): no estimate",
                                report.size_ratio);
    else if (report.size_ratio < companion_min_size_ratio)
      report.note = fmt::format(
          "the companion's elements are only {:.2f} times the model's, below the {} a two-mesh "
          "estimate needs (Celik et al. 2008): the estimate is not reliable; build with a "
          "larger [error_estimate] mesh_scale (a thin band keeps its tets across its thickness as "
          "the sizes grow)",
          report.size_ratio, companion_min_size_ratio);
    else if (!coarse[c].result.success)
      report.note = "the companion stopped: " + coarse[c].result.failure;
    log_info(fmt::format("error estimate: {}: companion of {} tets (elements {:.2f} times the "
                         "model's), {} of {} angles",
                         report.ligament, report.tets, report.size_ratio, report.angles_reached,
                         fine.result.angles.size()));
    if (!report.note.empty())
      log_info(fmt::format("warning: error estimate: {}: {}", report.ligament, report.note));
    // Frames run 10-node models as linear tets: the remedy is the quasi-static sweep's.
    const bool linear = ligaments[owner[c]].model.tet10.rows() == 0;
    const std::string locking =
        locking_warning(fine.result.angles, linear && settings.mode == FlexionMode::quasi_static);
    if (!locking.empty())
      log_info(fmt::format("warning: error estimate: {}: {}", report.ligament, locking));
  }
  return reports;
}

} // namespace ligsim::sim
