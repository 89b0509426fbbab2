#pragma once
/// @brief One ligament held by a femur whose pose a solver chooses: its equilibrium with the
/// femoral footprint carried by the femur (and the femur's contact with it), solved again from
/// its last state whenever the pose moves; and what the femur feels of it in the knee's five free
/// coordinates: the generalized force (the footprint's reaction and the contact's, on the femur)
/// and the stiffness with the ligament's nodes eliminated (the Schur complement of its tangent).
///
/// The stiffness is exact: the ligament's elasticity, the footprint's motion and the
/// ligament-femur contact, whose barrier moves with the femur (a node's barrier is a function of
/// where the node lies in the femur's frame).

#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/kinematics/free_pose.hpp"
#include "sim/kinematics/pose_segment.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/implicit_euler.hpp"
#include "sim/solver/static_solver.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace ligsim::sim {

class LigamentAtPose {
public:
  /// `settings`: the ligament's own (ligament_settings), quasi-static.
  LigamentAtPose(const LigamentModel& ligament, const FlexionSettings& settings,
                 const JointCoordinateSystem& jcs, const std::filesystem::path& contact_cache);

  const std::string& name() const { return m_name; }
  /// Pushes the ligament out of the bones as the sweep does ([contact] initial_overlap) and
  /// settles it at the built pose; false when that fails (failure() says why).
  bool settle();
  /// Moves the femur from the current pose to `pose` and finds the equilibrium there; false when
  /// it cannot, leaving the last equilibrium and its pose.
  bool move_to(const JointPose& pose);
  const JointPose& pose() const { return m_pose; }
  /// The equilibrium at `pose` to first order, from the current one and the nodes' response that
  /// stiffness() computed at pose(); none when there is no such response or the flexion differs.
  std::optional<Eigen::VectorXd> predicted_positions(const JointPose& pose) const;
  /// An equilibrium found, to come back to without solving again.
  struct Equilibrium {
    JointPose pose;
    Eigen::VectorXd positions, residual;
  };
  Equilibrium equilibrium() const { return {m_pose, m_x, m_residual}; }
  void restore(const Equilibrium& equilibrium);
  /// The nodes' positions at equilibrium at pose() (flat, mm).
  const Eigen::VectorXd& positions() const { return m_x; }
  const std::string& failure() const { return m_failure; }

  /// Strain energy and contact barrier at the current equilibrium, N mm.
  double energy() const;
  /// d(energy)/dq at the current equilibrium (its nodes held there: they are in equilibrium).
  Vector5d generalized_force(const FreePose& pose) const;
  /// d^2(energy)/dq^2 with the nodes re-equilibrating (see above).
  Matrix5d stiffness(const FreePose& pose) const;
  /// What the femur exerts on the ligament: its footprint's reaction and its contact, N.
  Eigen::Vector3d femur_force() const;
  /// The femoral footprint's reaction alone (flexion.csv's femur_force_n), N.
  Eigen::Vector3d footprint_force() const;

  /// One implicit Euler frame of a live view ([interactive] settings, `time_step_s` long): the
  /// femur goes from pose() to `pose` within the frame and the tissue follows with its inertia,
  /// its velocity carried from frame to frame. False when the frame fails (failure() says why),
  /// leaving the last state.
  bool frame_to(const JointPose& pose, double time_step_s, FrameReport& report);
  /// Contact with the bones on or off from now on.
  void set_contact(bool on);
  bool contact() const { return m_contact_on; }
  const HyperelasticBody& body() const { return *m_body; }

private:
  void make_solver();

  std::string m_name;
  LigamentModel m_ligament;
  FlexionSettings m_settings;
  JointCoordinateSystem m_jcs;
  std::shared_ptr<PoseSegment> m_segment;
  BoundaryConditions m_conditions;
  std::unique_ptr<KneeContact> m_contact;
  bool m_contact_on = true;
  std::optional<HyperelasticBody> m_body;
  std::unique_ptr<StaticSolver> m_solver;
  std::unique_ptr<ImplicitEuler> m_dynamics; ///< the live frames' (made by the first)
  Eigen::VectorXd m_velocity;
  Eigen::VectorXd m_x, m_residual;
  JointPose m_pose;
  /// The nodes' first-order response to the five coordinates at m_response_pose (stiffness()
  /// computes it): move_to() starts a nearby pose's solve from it.
  mutable Eigen::MatrixXd m_response;
  mutable std::optional<JointPose> m_response_pose;
  int m_femur_obstacle = -1; ///< the femur's index among the contact's obstacles (-1: none)
  std::string m_failure;
};

} // namespace ligsim::sim
