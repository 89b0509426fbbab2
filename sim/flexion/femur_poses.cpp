#include "sim/flexion/femur_poses.hpp"

#include "common/error.hpp"
#include "sim/flexion/knee_flexion.hpp"

namespace ligsim::sim {

std::vector<Eigen::Isometry3d> femur_poses(const BoundaryConditions& conditions,
                                           const std::vector<double>& angles_deg)
{
  const ConstraintSet* femur = nullptr;
  for (const ConstraintSet& set : conditions.constraints)
    if (set.name == "femur")
      femur = &set;
  if (!femur)
    fail("femur poses: the conditions have no node set called 'femur'");
  std::vector<Eigen::Isometry3d> poses;
  for (double t : flexion_load_factors(angles_deg))
    poses.push_back(femur->rigid ? femur->rigid->pose(t) : Eigen::Isometry3d::Identity());
  return poses;
}

} // namespace ligsim::sim
