#include "sim/contact/bone_penetration.hpp"

#include <cmath>

namespace ligsim::sim {

BonePenetration::BonePenetration(const TriangleSurface& bone)
    : m_winding(bone)
    , m_distance(bone)
{
}

double BonePenetration::depth_mm(const Eigen::Vector3d& p) const
{
  if (!m_winding.bounds().contains(p) || std::abs(m_winding(p)) < 0.5)
    return 0.0;
  return m_distance(p);
}

} // namespace ligsim::sim
