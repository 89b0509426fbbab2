#pragma once
/// @brief The femur's pose at each step of a sweep, for the exporters: one rigid transform per
/// step, relative to the femur's rest pose, in the model's frame (mm): the "femur" constraint
/// set's rigid motion (a turn about the flexion axis, or the knee's six-degree-of-freedom path)
/// at the step's load factor.

#include "sim/flexion/knee_flexion.hpp"
#include "sim/solver/boundary_conditions.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace ligsim::sim {

/// One pose per step of `steps` (at its load factor, as the sweep uses); identities when the
/// "femur" set of `conditions` does not move rigidly. Throws InputError when there is no
/// "femur" set.
std::vector<Eigen::Isometry3d> femur_poses(const BoundaryConditions& conditions,
                                           const SweepSteps& steps);

} // namespace ligsim::sim
