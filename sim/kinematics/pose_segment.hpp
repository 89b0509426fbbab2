#pragma once
/// @brief A femur path between two joint poses, their coordinates interpolated linearly in the
/// load factor: what a solver follows from the femur's last equilibrium pose to a trial one. Its
/// ends can be moved between solves (the solver and the contact hold the same path).

#include "sim/kinematics/joint_coordinates.hpp"
#include "sim/solver/boundary_conditions.hpp"

namespace ligsim::sim {

class PoseSegment final : public RigidPath {
public:
  explicit PoseSegment(JointCoordinateSystem jcs)
      : m_jcs(std::move(jcs))
  {
  }

  /// The path now runs from `from` (load factor 0) to `to` (load factor 1).
  void set(const JointPose& from, const JointPose& to)
  {
    m_from = from;
    m_to = to;
  }
  Eigen::Isometry3d pose(double t) const override;
  const JointCoordinateSystem& jcs() const { return m_jcs; }

private:
  JointCoordinateSystem m_jcs;
  JointPose m_from, m_to;
};

} // namespace ligsim::sim
