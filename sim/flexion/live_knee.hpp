#pragma once
/// @brief The knee moved by hand: the femur's flexion angle follows a target the user moves
/// (a slider, a script), at most at the interactive angular speed, and every ligament answers
/// with one implicit Euler frame per step of time, so the tissue lags and settles as a tissue
/// does. What a live window draws and reports, without the window.

#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/ligament_at_pose.hpp"
#include "sim/flexion/regional_strain.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

/// One ligament's figures at a frame.
struct LiveLigament {
  std::string name;
  double femur_force_n = 0.0; ///< the femoral footprint's reaction (flexion.csv's femur_force_n)
  double regional_peak_pct = 0.0; ///< the largest fiber strain over 2 mm regions, %
};

/// One frame of the live knee.
struct LiveFrame {
  int frame = 0;          ///< 1-based
  double time_s = 0.0;    ///< simulated time
  double angle_deg = 0.0; ///< where the femur is
  double target_deg = 0.0;
  int solves = 0; ///< linear solves of all ligaments in this frame
  bool equation_met = true;
  double wall_s = 0.0; ///< computing it (all ligaments, side by side)
  std::vector<LiveLigament> ligaments;
};

class LiveKnee {
public:
  /// Settles every ligament at the built pose and then at the path's pose at 0 degrees
  /// (quasi-static). `settings`: the flexion settings (interactive ones for the frames);
  /// `max_angle_deg` bounds the target. Throws InputError for a motion in time (the slider
  /// moves the flexion angle), SolverError when a ligament cannot be settled.
  LiveKnee(const std::vector<LigamentModel>& ligaments, const KneeMotion& motion,
           const FlexionSettings& settings, const std::filesystem::path& contact_cache,
           double max_angle_deg);

  /// One frame of `time_step_s()`: the femur moves towards `target_deg` (clamped to [0, max])
  /// by at most the angular speed times the time step. Throws SolverError when a frame fails.
  const LiveFrame& advance(double target_deg);

  /// Contact with the bones on or off for every ligament.
  void set_contact(bool on);
  bool contact() const { return m_contact; }

  double time_step_s() const { return m_time_step_s; }
  double max_angle_deg() const { return m_max_angle_deg; }
  double angle_deg() const { return m_angle_deg; }
  const LiveFrame& last() const { return m_last; }
  /// The femur's transform from its built pose at the current angle.
  Eigen::Isometry3d femur_pose() const;

  std::size_t ligament_count() const { return m_ligaments.size(); }
  const LigamentAtPose& ligament(std::size_t l) const { return m_ligaments[l]; }
  /// Per element of ligament `l`, its fiber strain (stretch - 1, with the in-situ pre-stretch)
  /// at the last frame.
  const Eigen::VectorXd& fiber_strain(std::size_t l) const { return m_strain[l]; }

private:
  JointPose pose_at(double angle_deg) const;
  void measure();

  std::vector<LigamentAtPose> m_ligaments;
  std::vector<RegionalMean> m_regions;
  std::vector<Eigen::VectorXd> m_strain; ///< per ligament, per element, at the last frame
  KneeMotion m_motion;
  double m_time_step_s = 0.01;
  double m_speed_deg_s = 45.0;
  double m_max_angle_deg = 120.0;
  double m_angle_deg = 0.0;
  bool m_contact = true;
  LiveFrame m_last;
};

} // namespace ligsim::sim
