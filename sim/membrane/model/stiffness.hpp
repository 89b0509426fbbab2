#pragma once
/// @brief Plane-stress stiffness of a transversely isotropic membrane (eq. 1 of Allard et al.).
///
/// Voigt order (sigma_x, sigma_y, tau_xy) = C (eps_x, eps_y, gamma_xy), with the engineering
/// shear strain gamma_xy = 2 eps_xy. The printed eq. 1 is garbled (see the seeds README); the
/// matrix here is the fiber-frame stiffness rotated by the fiber angle, C = T^T Q T.

#include "sim/membrane/model/material.hpp"

#include <Eigen/Core>

namespace ligsim::membrane {

/// Q: the stiffness in the fiber frame (F, T), MPa.
Eigen::Matrix3d fiber_frame_stiffness(const MembraneMaterial& material);

/// C(theta): the stiffness in a frame (x, y) where the fiber makes the angle `fiber_angle_rad`
/// with x (counter-clockwise), MPa.
Eigen::Matrix3d rotated_stiffness(const MembraneMaterial& material, double fiber_angle_rad);

} // namespace ligsim::membrane
