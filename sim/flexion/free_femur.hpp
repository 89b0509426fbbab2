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
///
/// This is the one Newton iteration of sim/ outside NewtonEngine, and why: its unknowns are five
/// pose coordinates, not a body's nodes, and each evaluation of its energy is four of the
/// engine's own solves (each ligament's equilibrium at the trial pose), so its step, line search
/// and trust region work on a dense 5 x 5 Schur complement the engine's sparse, element-wise
/// machinery has no use for. Folding the pose into the engine's unknowns (one monolithic solve
/// of nodes and pose) would remove it; that is a different algorithm, with its own figures.

#include "sim/flexion/articular_contact.hpp"
#include "sim/flexion/ligament_at_pose.hpp"
#include "sim/kinematics/free_pose.hpp"

#include <string>
#include <vector>

namespace ligsim::sim {

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
  std::vector<Eigen::VectorXd> ligament_positions;      ///< per ligament, its equilibrium (mm)
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
                               const FreeKneeSettings& settings);

/// The potential of the loads at free coordinates q (N mm): minus their work from the built pose.
double load_potential(const JointLoads& loads, const Vector5d& q);
/// Its gradient in q.
Vector5d load_gradient(const JointLoads& loads);

} // namespace ligsim::sim
