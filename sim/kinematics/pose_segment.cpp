#include "sim/kinematics/pose_segment.hpp"

namespace ligsim::sim {

Eigen::Isometry3d PoseSegment::pose(double t) const
{
  const auto mix = [t](double a, double b) { return a + t * (b - a); };
  JointPose p;
  p.flexion_deg = mix(m_from.flexion_deg, m_to.flexion_deg);
  p.varus_deg = mix(m_from.varus_deg, m_to.varus_deg);
  p.internal_rotation_deg = mix(m_from.internal_rotation_deg, m_to.internal_rotation_deg);
  p.lateral_mm = mix(m_from.lateral_mm, m_to.lateral_mm);
  p.anterior_mm = mix(m_from.anterior_mm, m_to.anterior_mm);
  p.proximal_mm = mix(m_from.proximal_mm, m_to.proximal_mm);
  return femur_motion(m_jcs, p);
}

} // namespace ligsim::sim
