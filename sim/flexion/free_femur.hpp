#pragma once
/// @brief Passive flexion with the knee free, as Open Knee(s) and robot labs do it: the flexion
/// angle is prescribed about the femur's flexion axis, and the femur's five other Grood & Suntay
/// coordinates are unknowns, found where the ligaments, the articular contact and the loads on
/// the joint hold the femur in equilibrium (Wilson et al., J Biomech 1998;31:1127: ligaments and
/// articular contact guide passive flexion).
///
/// The ligaments' nodes are eliminated: at every trial pose each ligament is brought to its own
/// equilibrium (LigamentAtPose), and Newton works on the five coordinates with the exact
/// gradient of the knee's potential energy (the wrench the femur feels) and its stiffness with the
/// nodes re-equilibrated (the Schur complement of the whole system's tangent), a line search on
/// that energy and a trust region that keeps a lax knee from wandering. Rotations enter the
/// unknowns times `rotation_scale_mm`, so that both kinds of step and of residual are in
/// millimetres and newtons.

#include "sim/flexion/articular_contact.hpp"
#include "sim/flexion/ligament_at_pose.hpp"
#include "sim/kinematics/free_pose.hpp"

#include <string>
#include <vector>

namespace ligsim::sim {

/// Loads on the joint, held at every angle (Open Knee(s)' passive flexion: 20 N of compression).
struct JointLoads {
  double compression_n = 20.0; ///< along the tibial axis, pressing the tibia onto the femur
  double anterior_n = 0.0;     ///< on the tibia, anterior (a drawer: negative is posterior)
  double valgus_nm = 0.0;      ///< on the tibia, N m (negative: varus)
  double internal_nm = 0.0;    ///< on the tibia about its axis, N m (negative: external)
};

struct FreeFemurSettings {
  JointLoads loads;
  double rotation_scale_mm = 20.0;
  /// Converged when the femur's residual force, and its moment over rotation_scale_mm, are below
  /// this share of the largest force on it (a ligament's, the contact's or a load).
  double tolerance = 1e-4;
  int max_iterations = 60;  ///< Newton iterations per angle
  double max_step_mm = 2.0; ///< trust region radius in the scaled unknowns
  /// A coordinate that runs beyond these from the built pose is a load the knee cannot hold.
  double max_translation_mm = 25.0;
  double max_rotation_deg = 60.0;
};

/// The knee at one angle.
struct FreeAngle {
  double angle_deg = 0.0;
  JointPose pose; ///< the tibia relative to the femur, from the built pose
  bool converged = false;
  int iterations = 0;
  double residual_force_n = 0.0;    ///< net force on the femur left
  double residual_moment_nmm = 0.0; ///< net moment on the femur about the JCS axes left (free ones)
  double force_scale_n = 0.0;       ///< what the residual was judged against
  ArticularState articular;
  std::vector<Eigen::Vector3d> ligament_femur_forces_n; ///< per ligament, the femur on it
  double wall_s = 0.0;
};

struct FreeFemurResult {
  bool success = false;
  std::string failure;
  std::vector<FreeAngle> angles;
};

/// Finds the femur's equilibrium pose at each of `angles_deg` (increasing), from the built pose,
/// each angle starting from the last. `articular` may be null (no articular contact). Never
/// throws on divergence: the result says where it stopped and why (naming the coordinate that
/// ran away when a load cannot be held).
FreeFemurResult find_free_path(std::vector<LigamentAtPose>& ligaments,
                               const ArticularContact* articular, const JointCoordinateSystem& jcs,
                               const std::vector<double>& angles_deg,
                               const FreeFemurSettings& settings);

/// The potential of the loads at free coordinates q (N mm): minus their work from the built pose.
double load_potential(const JointLoads& loads, const Vector5d& q);
/// Its gradient in q.
Vector5d load_gradient(const JointLoads& loads);

} // namespace ligsim::sim
