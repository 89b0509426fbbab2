#include "sim/membrane/model/stiffness.hpp"

#include <cmath>

namespace ligsim::membrane {

Eigen::Matrix3d fiber_frame_stiffness(const MembraneMaterial& m)
{
  const double nu_f = m.fiber_poisson;
  const double nu_t = m.transverse_poisson();
  const double scale = 1.0 / (1.0 - nu_f * nu_t);
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  q(0, 0) = scale * m.fiber_modulus_mpa;
  q(1, 1) = scale * m.transverse_modulus_mpa;
  q(0, 1) = q(1, 0) = scale * nu_t * m.fiber_modulus_mpa;
  q(2, 2) = m.shear_modulus_mpa;
  return q;
}

Eigen::Matrix3d rotated_stiffness(const MembraneMaterial& material, double fiber_angle_rad)
{
  // The classical closed form of T^T Q T for a lamina whose fibers make the angle theta with x.
  const Eigen::Matrix3d q = fiber_frame_stiffness(material);
  const double c = std::cos(fiber_angle_rad);
  const double s = std::sin(fiber_angle_rad);
  const double c2 = c * c, s2 = s * s;
  const double c4 = c2 * c2, s4 = s2 * s2, c2s2 = c2 * s2;
  const double q11 = q(0, 0), q22 = q(1, 1), q12 = q(0, 1), q66 = q(2, 2);

  Eigen::Matrix3d k;
  k(0, 0) = q11 * c4 + 2.0 * (q12 + 2.0 * q66) * c2s2 + q22 * s4;
  k(1, 1) = q11 * s4 + 2.0 * (q12 + 2.0 * q66) * c2s2 + q22 * c4;
  k(0, 1) = (q11 + q22 - 4.0 * q66) * c2s2 + q12 * (c4 + s4);
  // Equals (q11 + q22 - 2 q12) c^2 s^2 + q66 (c^2 - s^2)^2.
  k(2, 2) = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * c2s2 + q66 * (c4 + s4);
  k(0, 2) = (q11 - q12 - 2.0 * q66) * s * c * c2 + (q12 - q22 + 2.0 * q66) * s * s2 * c;
  k(1, 2) = (q11 - q12 - 2.0 * q66) * s * s2 * c + (q12 - q22 + 2.0 * q66) * s * c * c2;
  k(1, 0) = k(0, 1);
  k(2, 0) = k(0, 2);
  k(2, 1) = k(1, 2);
  return k;
}

} // namespace ligsim::membrane
