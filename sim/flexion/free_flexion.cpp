#include "sim/flexion/free_flexion.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "common/svg_plot.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/flexion/knee_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// The ligaments' equilibrium tolerance in the search, as a fraction of the femur's.
constexpr double kSearchLigamentTolerance = 1e-2;

} // namespace

bool flexes_free_by_default(const std::vector<LigamentModel>& ligaments)
{
  std::set<std::string> names;
  for (const LigamentModel& l : ligaments) {
    std::string upper = l.name;
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    names.insert(upper);
    if (!l.model.femur || !l.model.tibia)
      return false;
  }
  return names.count("MCL") && names.count("LCL") && names.count("ACL") && names.count("PCL");
}

bool choose_free_path(FlexionSettings& settings, const std::vector<LigamentModel>& whole)
{
  if (settings.motion.path == MotionSettings::Path::automatic && flexes_free_by_default(whole)) {
    settings.motion.path = MotionSettings::Path::free;
    log_info("flexion: the knee has both collaterals and both cruciates: the femur is free in its "
             "five other coordinates ([motion] path = \"free\")");
  }
  return settings.motion.path == MotionSettings::Path::free;
}

std::vector<LigamentModel> free_path_ligaments(const std::vector<LigamentModel>& whole,
                                               const FlexionSettings& settings)
{
  FlexionSettings knee_settings = settings;
  knee_settings.ligaments.clear();
  return chosen_ligaments(whole, knee_settings);
}

FreeFlexion find_free_flexion(const std::vector<LigamentModel>& ligaments, const KneeMotion& motion,
                              const FlexionSettings& settings, const fs::path& contact_cache)
{
  FreeFlexion free;
  free.motion = motion;
  std::vector<LigamentAtPose> held;
  held.reserve(ligaments.size());
  for (const LigamentModel& ligament : ligaments) {
    FlexionSettings own = ligament_settings(settings, ligament);
    own.mode = FlexionMode::quasi_static;
    // The search needs each ligament's force on the femur to a small part of the femur's own
    // tolerance, not to the sweep's: the sweep that writes the results solves the ligaments
    // again at the found poses to its tolerance, starting from these equilibria.
    own.newton.residual_tolerance =
        std::max(own.newton.residual_tolerance, kSearchLigamentTolerance * settings.free.tolerance);
    held.emplace_back(ligament, own, motion.jcs, contact_cache);
  }
  std::unique_ptr<BoneLevelSet> tibia;
  std::unique_ptr<ArticularContact> articular;
  const KneeModel& model = ligaments.front().model;
  if (settings.free.articular_contact) {
    const TriangleSurface& tibia_surface = *model.tibia;
    // A wide band: a trial pose may press the femur millimetres into the tibia, and the
    // foundation must see how deep to push it back (the ligaments' 1 mm band would not).
    LevelSetSettings grid;
    grid.voxel_mm = 0.5;
    grid.band_mm = 8.0;
    tibia = BoneLevelSet::cached(tibia_surface, grid, contact_cache / "tibia_articular.vdb");
    articular = std::make_unique<ArticularContact>(*model.femur, *tibia, motion.jcs,
                                                   settings.free.articular);
    free.seat = articular->seat();
  }
  free.found = find_free_path(held, articular.get(), motion.jcs, motion.angles_deg, settings.free);
  std::vector<double> angles;
  std::vector<JointPose> poses;
  for (const FreeAngle& at : free.found.angles)
    if (at.converged) {
      angles.push_back(at.angle_deg);
      poses.push_back(at.pose);
      for (std::size_t l = 0; l < ligaments.size(); ++l)
        free.equilibria[ligaments[l].name].push_back(at.ligament_positions[l]);
    }
  if (angles.empty())
    return free;
  free.motion.angles_deg = angles;
  // The sweep starts from the built pose (load factor 0: a knot of its own, one degree before
  // the first angle) and reaches the found pose of each angle at its step.
  const double first = angles.front() - 1.0, last = angles.back();
  free.motion.load_factors.clear();
  for (double angle : angles)
    free.motion.load_factors.push_back((angle - first) / (last - first));
  free.motion.load_factors.back() = 1.0;
  std::vector<double> knots = {first};
  std::vector<JointPose> path_poses = {JointPose{}};
  knots.insert(knots.end(), angles.begin(), angles.end());
  path_poses.insert(path_poses.end(), poses.begin(), poses.end());
  KneePath path = KneePath::table(KneePath::Parameter::flexion_deg, knots, path_poses,
                                  "the knee's free equilibrium (femur free in five coordinates)");
  free.motion.figures.path = path.description();
  free.motion.femur_path = std::make_shared<FemurPath>(motion.jcs, std::move(path), first, last);
  return free;
}

std::pair<double, double> on_tibia(const Eigen::Vector3d& point, const JointCoordinateSystem& jcs)
{
  if (!point.allFinite())
    return {NAN, NAN};
  const Eigen::Matrix3d axes = joint_axes(jcs);
  const double side = jcs.side >= 0 ? 1.0 : -1.0;
  const Eigen::Vector3d d = point - jcs.origin_mm;
  // e1 points laterally in a right knee (side +1), medially in a left one.
  return {d.dot(axes.col(1)), -side * d.dot(axes.col(0))};
}

void write_kinematics_csv(const FreeFemurResult& found, const JointCoordinateSystem& jcs,
                          const fs::path& file)
{
  std::string text = "angle_deg,varus_deg,internal_rotation_deg,anterior_mm,medial_mm,proximal_mm,"
                     "medial_contact_force_n,lateral_contact_force_n,medial_contact_anterior_mm,"
                     "medial_contact_medial_mm,lateral_contact_anterior_mm,"
                     "lateral_contact_medial_mm,residual_force_n,residual_moment_nmm,converged,"
                     "iterations\n";
  for (const FreeAngle& at : found.angles) {
    const auto [ma, mm] = on_tibia(at.articular.medial_centre_mm, jcs);
    const auto [la, lm] = on_tibia(at.articular.lateral_centre_mm, jcs);
    // The coordinates to full precision: the file replays as the path it records.
    text += fmt::format(
        "{},{},{},{},{},{},{:.4f},{:.4f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3g},{:.3g},{},"
        "{}\n",
        at.angle_deg, at.pose.varus_deg, at.pose.internal_rotation_deg, at.pose.anterior_mm,
        -at.pose.lateral_mm, at.pose.proximal_mm, at.articular.medial_force_n.norm(),
        at.articular.lateral_force_n.norm(), ma, mm, la, lm, at.residual_force_n,
        at.residual_moment_nmm, at.converged ? 1 : 0, at.iterations);
  }
  write_text_atomically(file, text);
}

void write_kinematics_plot(const FreeFemurResult& found, const fs::path& file)
{
  PlotSpec plot;
  plot.title = "The knee's own path against the passive cadaver knee's (Walker et al. 1988)";
  plot.x_label = "flexion angle (deg)";
  plot.y_label = "tibia relative to the femur (deg)";
  PlotSeries rotation{"internal rotation, this knee", {}, {}, {}};
  PlotSeries varus{"varus, this knee", {}, {}, {}};
  for (const FreeAngle& at : found.angles) {
    rotation.x.push_back(at.angle_deg);
    rotation.y.push_back(at.pose.internal_rotation_deg);
    varus.x.push_back(at.angle_deg);
    varus.y.push_back(at.pose.varus_deg);
  }
  PlotSeries walker_rotation{"internal rotation, Walker 1988", {}, {}, {}};
  PlotSeries walker_varus{"varus, Walker 1988", {}, {}, {}};
  for (double angle = 0.0; angle <= 120.0; angle += 5.0) {
    const JointPose passive = passive_coupling(angle, false);
    walker_rotation.x.push_back(angle);
    walker_rotation.y.push_back(passive.internal_rotation_deg);
    walker_varus.x.push_back(angle);
    walker_varus.y.push_back(passive.varus_deg);
  }
  plot.series = {rotation, walker_rotation, varus, walker_varus};
  write_text_atomically(file, svg_line_plot(plot));
}
} // namespace ligsim::sim
