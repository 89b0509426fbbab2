#pragma once
/// @brief The femur's pose at each angle of a sweep, for the exporters: one rigid transform per
/// angle, relative to the femur's rest pose, in the model's frame (mm). Today's motion is the
/// "femur" constraint set's rigid motion at the angle's load factor (a turn about the flexion
/// axis); a six-degree-of-freedom path enters here.

#include "sim/solver/boundary_conditions.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace ligsim::sim {

/// One pose per angle of `angles_deg` (load factor angle / last angle, as the sweep uses);
/// identities when the "femur" set of `conditions` does not move rigidly. Throws InputError
/// when there is no "femur" set.
std::vector<Eigen::Isometry3d> femur_poses(const BoundaryConditions& conditions,
                                           const std::vector<double>& angles_deg);

} // namespace ligsim::sim
