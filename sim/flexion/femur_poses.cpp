#include "sim/flexion/femur_poses.hpp"

#include "common/error.hpp"

namespace ligsim::sim {

std::vector<Eigen::Isometry3d> femur_poses(const BoundaryConditions& conditions,
                                           const SweepSteps& steps)
{
  const ConstraintSet* femur = nullptr;
  for (const ConstraintSet& set : conditions.constraints)
    if (set.name == "femur")
      femur = &set;
  if (!femur)
    fail("femur poses: the conditions have no node set called 'femur'");
  std::vector<Eigen::Isometry3d> poses;
  for (double t : steps.load_factors)
    poses.push_back(femur->rigid ? femur->rigid->pose(t) : Eigen::Isometry3d::Identity());
  return poses;
}

} // namespace ligsim::sim
